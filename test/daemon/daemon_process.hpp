#pragma once
// rangefitd as a separate process for end-to-end tests: started with a config file, talked to
// over DDS by the test process, stopped with SIGTERM like systemctl stop.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

namespace rangefit::test {

class DaemonProcess {
 public:
  // extra_env: "NAME=value" entries added to this process's environment.
  DaemonProcess(const std::filesystem::path& exe, const std::filesystem::path& config,
                std::vector<std::string> extra_env = {}) {
    // Everything the child needs is prepared before fork(): only execve runs in the child.
    for (char** e = environ; *e != nullptr; ++e) env_.emplace_back(*e);
    for (auto& e : extra_env) env_.push_back(std::move(e));
    for (auto& e : env_) envp_.push_back(e.data());
    envp_.push_back(nullptr);
    args_ = {exe.string(), "--config", config.string()};
    for (auto& a : args_) argv_.push_back(a.data());
    argv_.push_back(nullptr);
    pid_ = fork();
    if (pid_ == 0) {
      execve(argv_[0], argv_.data(), envp_.data());
      _exit(127);
    }
  }
  ~DaemonProcess() {
    if (pid_ > 0 && !exited_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  DaemonProcess(const DaemonProcess&) = delete;
  DaemonProcess& operator=(const DaemonProcess&) = delete;

  bool started() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }
  void signal(int sig) const { kill(pid_, sig); }
  // SIGTERM and wait; the exit status (-1 when killed by a signal).
  int stop() {
    kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
    exited_ = true;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

 private:
  std::vector<std::string> env_, args_;
  std::vector<char*> envp_, argv_;
  pid_t pid_ = -1;
  bool exited_ = false;
};

}  // namespace rangefit::test
