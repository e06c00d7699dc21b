#include "daemon/cli/remote/watch_command.hpp"

#include <chrono>
#include <iostream>

#include "daemon/cli/commands.hpp"
#include "daemon/cli/option_checks.hpp"
#include "daemon/dds/client.hpp"
#include "daemon/service/json_codec.hpp"

namespace rangefit::cli {
namespace {

// One JSON line per message. Strings from the wire may be invalid UTF-8, which dump() would
// throw on and end the watch; they are printed with U+FFFD instead.
void print_line(const nlohmann::json& j) {
  std::cout << j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << std::endl;
}

}  // namespace

void add_watch_command(CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand("watch", "print rangefitd's detections and diagnostics (DDS)");
  static std::uint32_t domain = 0;
  static double seconds = 0;
  static bool diagnostics = true;
  cmd->add_option("--domain", domain, "DDS domain id")->capture_default_str();
  cmd->add_option("--seconds", seconds, "stop after this long (0: run until killed)")
      ->check(finite_range(0.0, 1e7));
  cmd->add_flag("!--no-diagnostics", diagnostics, "do not print rt/diagnostics");
  cmd->callback([exit_code] {
    try {
      daemon::DdsClient client(domain);
      daemon::DdsClient::Callbacks cb;
      cb.detection = [](const daemon::DetectionResult& r) {
        print_line({{"detection", daemon::to_json(r)}});
      };
      cb.state = [](daemon::LifecycleState s, const std::string& detail) {
        print_line({{"state", daemon::to_string(s)}, {"detail", detail}});
      };
      cb.cloud = [](const PointCloud& c) {
        print_line({{"cloud", {{"frame_id", c.frame_id}, {"points", c.size()}}}});
      };
      if (diagnostics) {
        cb.diagnostics = [](const std::vector<daemon::DiagStatus>& statuses) {
          nlohmann::json arr = nlohmann::json::array();
          for (const auto& s : statuses) {
            nlohmann::json values = nlohmann::json::object();
            for (const auto& [k, v] : s.values) values[k] = v;
            arr.push_back(
                {{"name", s.name}, {"level", s.level}, {"message", s.message}, {"values", values}});
          }
          print_line({{"diagnostics", arr}});
        };
      }
      const auto end = std::chrono::steady_clock::now() +
                       std::chrono::milliseconds(static_cast<long>(seconds * 1000));
      while (seconds <= 0 || std::chrono::steady_clock::now() < end) {
        client.poll(std::chrono::milliseconds(200), cb);
      }
      *exit_code = kExitOk;
    } catch (const std::exception& e) {
      std::cerr << "rangefit watch: " << e.what() << "\n";
      *exit_code = kExitBadInput;
    }
  });
}

}  // namespace rangefit::cli
