#pragma once
// rangefitd as a separate process on the simulated cell with its HTTP and TCP interfaces on
// loopback ports chosen free, DDS on loopback (a domain reserved for this process), a temporary spool.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <httplib.h>

#include "test/daemon/dds_test_env.hpp"

namespace rangefit::test {

inline const std::string kToken = "cell-token-for-tests";

// A port nobody listens on now (bound to 0, read, closed).
inline int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  inet_pton(AF_INET, "127.0.0.1", &a.sin_addr);
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(fd);
  return ntohs(a.sin_port);
}

class WebDaemon {
 public:
  // extra: TOML appended to [service] (e.g. queue_capacity); time_scale of the simulated cell.
  WebDaemon(const std::string& name, const std::string& service_extra, double time_scale = 0) {
    namespace fs = std::filesystem;
    dir_ = fs::temp_directory_path() / ("rangefit_web_" + name + "_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    http_port_ = free_port();
    tcp_port_ = free_port();
    const std::string scenes = std::string(RANGEFIT_SOURCE_DIR) + "/data/scenes/";
    std::ofstream(dir_ / "rangefitd.toml")
        << "[service]\nbore_sensor = \"css\"\nobject_sensor = \"stripe\"\n"
        << service_extra << "\n[http]\nlisten = \"127.0.0.1:" << http_port_ << "\"\ntoken = \""
        << kToken << "\"\n"
        << "max_request_bytes = 4096\n"
        << "[tcp]\nlisten = \"127.0.0.1:" << tcp_port_ << "\"\ntoken = \"" << kToken << "\"\n"
        << "[dds]\ndomain_id = " << dds_test_domain() << "\ndiagnostics_period_s = 0.2\n"
        << "[spool]\ndirectory = \"" << (dir_ / "spool").string() << "\"\n"
        << "[sim]\ntime_scale = " << time_scale << "\nseed = 3\n"
        << "[[devices]]\nname = \"css\"\nkind = \"css\"\ndriver = \"sim\"\nscene = \"" << scenes
        << "bore_plate.toml\"\n"
        << "[[devices]]\nname = \"stripe\"\nkind = \"stripe\"\ndriver = \"sim\"\nscene = \""
        << scenes << "table_top_fig5_18.toml\"\n"
        << "[[objects]]\nname = \"sphere\"\nscale_mm = [50, 50, 50]\nshape = [1.0, 1.0]\n";
    const std::string uri =
        std::string("file://") + RANGEFIT_SOURCE_DIR + "/systemd/cyclonedds-loopback.xml";
    setenv("CYCLONEDDS_URI", uri.c_str(), 1);  // the child's DDS: loopback only
    const std::string config = (dir_ / "rangefitd.toml").string();
    const std::string log = (dir_ / "rangefitd.log").string();
    pid_ = fork();
    if (pid_ == 0) {
      const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(fd, 2);
      execl(RANGEFITD_PATH, RANGEFITD_PATH, "--config", config.c_str(), nullptr);
      _exit(127);
    }
  }
  ~WebDaemon() {
    if (pid_ > 0 && !exited_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    std::filesystem::remove_all(dir_);
  }

  // Waits until GET /v1/state answers.
  bool wait_ready(std::chrono::seconds limit = std::chrono::seconds(30)) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < deadline) {
      if (!alive()) return false;
      auto c = client();
      if (auto r = c.Get("/v1/state"); r && r->status == 200) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return false;
  }
  bool alive() const {
    int status = 0;
    return pid_ > 0 && waitpid(pid_, &status, WNOHANG) == 0;
  }
  // SIGTERM; the exit status (-1 when it died of a signal).
  int stop() {
    kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
    exited_ = true;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  httplib::Client client(bool with_token = true) const {
    httplib::Client c("127.0.0.1", http_port_);
    c.set_connection_timeout(5, 0);
    c.set_read_timeout(120, 0);
    if (with_token) c.set_bearer_token_auth(kToken);
    return c;
  }
  int http_port() const { return http_port_; }
  int tcp_port() const { return tcp_port_; }
  std::string log() const {
    std::ifstream in(dir_ / "rangefitd.log");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

 private:
  std::filesystem::path dir_;
  int http_port_ = 0, tcp_port_ = 0;
  pid_t pid_ = -1;
  bool exited_ = false;
};

}  // namespace rangefit::test
