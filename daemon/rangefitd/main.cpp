// rangefitd: runs the cell, answers scan requests and publishes results over DDS.
// Signals are blocked in every thread and taken synchronously in the main loop (sigtimedwait),
// so no handler runs in signal context. systemd protocol: READY=1 once config, devices and DDS
// entities are up; WATCHDOG=1 only while the pipeline makes progress; RELOADING=1 then READY=1
// around SIGHUP; STOPPING=1 on SIGTERM/SIGINT.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/sinks/systemd_sink.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "daemon/rangefitd/interfaces.hpp"
#include "daemon/rangefitd/service.hpp"
#include "daemon/rangefitd/systemd_notify.hpp"
#include "daemon/service/address_check.hpp"
#include "daemon/service/config.hpp"

namespace {

using namespace rangefit;

void setup_logging(const std::string& level) {
  std::vector<spdlog::sink_ptr> sinks;
  // Under systemd stderr goes to the journal anyway; the systemd sink adds priorities and fields.
  if (getenv("JOURNAL_STREAM") != nullptr || getenv("INVOCATION_ID") != nullptr) {
    sinks.push_back(std::make_shared<spdlog::sinks::systemd_sink_mt>("rangefitd"));
  } else {
    sinks.push_back(std::make_shared<spdlog::sinks::stderr_color_sink_mt>());
  }
  auto logger = std::make_shared<spdlog::logger>("rangefitd", sinks.begin(), sinks.end());
  spdlog::set_default_logger(logger);
  spdlog::set_level(spdlog::level::from_str(level));
}

void usage(std::ostream& out) {
  out << "usage: rangefitd --config FILE\n"
         "       rangefitd --help | --version\n"
         "  Runs the rangefit cell service: scans on request, detects bore holes and objects and\n"
         "  publishes the results over DDS. FILE is its TOML configuration (installed sample:\n"
         "  " RANGEFITD_CONFIG
         "; every field is documented there).\n"
         "  -c, --config FILE  configuration to run with (re-read on SIGHUP)\n"
         "  -h, --help         print this text and exit\n"
         "  -V, --version      print the version and exit\n"
         "Exit codes: 0 stopped by SIGTERM/SIGINT, 1 bad configuration or start-up failure,\n"
         "2 bad command line.\n";
}

// Command-line outcome: run with config_path, or exit with `exit_code` right away.
struct CommandLine {
  std::string config_path;
  int exit_code = -1;  // >= 0: exit with it
};

CommandLine parse_command_line(int argc, char** argv) {
  CommandLine cl;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      usage(std::cout);
      return {"", 0};
    }
    if (arg == "--version" || arg == "-V") {
      std::cout << "rangefitd " RANGEFIT_VERSION "\n";
      return {"", 0};
    }
    if (arg == "--config" || arg == "-c") {
      if (i + 1 == argc) {
        std::cerr << "rangefitd: " << arg << " needs a FILE\n";
        return {"", 2};
      }
      cl.config_path = argv[++i];
    } else if (arg.starts_with("--config=")) {
      cl.config_path = arg.substr(9);
    } else {
      std::cerr << "rangefitd: unexpected argument '" << arg << "'\n";
      cl.config_path.clear();
      break;
    }
  }
  if (cl.config_path.empty()) {
    usage(std::cerr);
    cl.exit_code = 2;
  }
  return cl;
}

// "" when the config's interfaces lie inside the unit's IPAddressAllow= this build knows.
std::string allowed_addresses_error(const daemon::DaemonConfig& config) {
  try {
    return daemon::check_allowed_addresses(config, daemon::built_ip_allow());
  } catch (const std::exception& e) {  // a list CMake was given that systemd would refuse too
    return e.what();
  }
}

// SIGHUP: re-reads config_path and swaps it in between scans; a refused one changes nothing.
bool reload(daemon::Service& service, const std::string& config_path, daemon::Notifier& notifier) {
  notifier.notify("RELOADING=1");
  spdlog::info("SIGHUP: reloading {}", config_path);
  auto next = daemon::load_config(config_path);
  std::string why = next.error;
  if (next.config) why = allowed_addresses_error(*next.config);
  if (next.config && why.empty() && service.reload(*next.config, &why)) {
    spdlog::set_level(spdlog::level::from_str(next.config->service.log_level));
    spdlog::info("configuration reloaded");
    notifier.notify("READY=1\nSTATUS=configuration reloaded");
    return true;
  }
  spdlog::error("reload refused, keeping the running configuration: {}", why);
  notifier.notify("READY=1\nSTATUS=reload refused: " + why);
  return false;
}

// The configuration rangefitd starts with, or nothing after saying why (log, systemd status).
std::optional<daemon::DaemonConfig> startup_config(const std::string& config_path,
                                                   daemon::Notifier& notifier) {
  auto loaded = daemon::load_config(config_path);
  if (!loaded.config) {
    setup_logging("info");
    spdlog::critical("{}", loaded.error);
    notifier.notify("STATUS=config error: " + loaded.error);
    return std::nullopt;
  }
  setup_logging(loaded.config->service.log_level);
  // The unit drops every peer outside its IPAddressAllow=: a socket there would never be reached.
  if (const std::string why = allowed_addresses_error(*loaded.config); !why.empty()) {
    spdlog::critical("{}: {}", config_path, why);
    notifier.notify("STATUS=config error: " + why);
    return std::nullopt;
  }
  return std::move(loaded.config);
}

// Steps the service, feeds the watchdog, keeps systemd's status line current and reloads on
// SIGHUP, until SIGTERM or SIGINT, which it returns.
int serve(daemon::Service& service, const hal::Clock& clock, const sigset_t& signals,
          const std::string& config_path, daemon::Notifier& notifier) {
  auto stall_limit = [&] {
    return std::chrono::duration_cast<hal::Duration>(
        std::chrono::duration<double>(service.config().service.stall_timeout_s));
  };
  daemon::WatchdogFeeder watchdog(notifier, stall_limit());
  const hal::Duration watchdog_period = daemon::watchdog_interval() / 2;
  hal::Timestamp next_feed{0};
  std::string last_status;
  for (;;) {
    service.step(std::chrono::milliseconds(100));

    const hal::Timestamp now = clock.now();
    if (watchdog_period > hal::Duration::zero() && now >= next_feed) {
      std::string why;
      watchdog.tick(now, service.last_progress(), &why);
      if (!why.empty()) spdlog::error("{}", why);
      next_feed = now + watchdog_period;
    }
    std::string status = service.status_line();
    if (service.stalled()) status = "STALLED; " + status;
    if (status != last_status) {
      notifier.notify("STATUS=" + status);
      last_status = status;
    }

    timespec zero{};
    siginfo_t info{};
    const int sig = sigtimedwait(&signals, &info, &zero);
    if (sig == SIGHUP) {
      if (reload(service, config_path, notifier)) watchdog.set_stall_limit(stall_limit());
    } else if (sig == SIGTERM || sig == SIGINT) {
      return sig;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const CommandLine command_line = parse_command_line(argc, argv);
  if (command_line.exit_code >= 0) return command_line.exit_code;
  const std::string& config_path = command_line.config_path;

  // Block before any thread exists so every thread inherits the mask.
  sigset_t signals;
  sigemptyset(&signals);
  for (int s : {SIGHUP, SIGTERM, SIGINT}) sigaddset(&signals, s);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  daemon::SdNotifier notifier;
  const std::optional<daemon::DaemonConfig> config = startup_config(config_path, notifier);
  if (!config) return 1;
  notifier.notify("STATUS=starting");

  hal::MonotonicClock clock;
  std::unique_ptr<daemon::Service> service;
  std::unique_ptr<daemon::Interfaces> interfaces;  // [http], [tcp]
  try {
    service = std::make_unique<daemon::Service>(*config, clock);
    interfaces = std::make_unique<daemon::Interfaces>(*service, *config);
    std::string why;
    if (!interfaces->start(&why)) throw std::runtime_error(why);
  } catch (const std::exception& e) {
    spdlog::critical("start-up failed: {}", e.what());
    notifier.notify(std::string("STATUS=start-up failed: ") + e.what());
    return 1;
  }
  spdlog::info("rangefitd up: config {}, DDS domain {}, spool {}", config_path,
               config->dds.domain_id, config->spool.directory.string());
  notifier.notify("READY=1");

  const int sig = serve(*service, clock, signals, config_path, notifier);
  notifier.notify("STOPPING=1\nSTATUS=stopping");
  spdlog::info("{}: stopping (aborting the running scan)", strsignal(sig));
  service->stop(true);  // answers what the interfaces wait for, then they stop
  interfaces.reset();
  service.reset();
  spdlog::info("stopped");
  return 0;
}
