#include "daemon/cli/watch_command.hpp"

#include <chrono>
#include <iostream>

#include "daemon/cli/commands.hpp"
#include "daemon/client.hpp"
#include "daemon/json_codec.hpp"

namespace rangefit::cli {

void add_watch_command(CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand("watch", "print rangefitd's detections and diagnostics (DDS)");
  static std::uint32_t domain = 0;
  static double seconds = 0;
  static bool diagnostics = true;
  cmd->add_option("--domain", domain, "DDS domain id")->capture_default_str();
  cmd->add_option("--seconds", seconds, "stop after this long (0: run until killed)");
  cmd->add_flag("!--no-diagnostics", diagnostics, "do not print rt/diagnostics");
  cmd->callback([exit_code] {
    try {
      daemon::DdsClient client(domain);
      daemon::DdsClient::Callbacks cb;
      cb.detection = [](const daemon::DetectionResult& r) {
        std::cout << nlohmann::json{{"detection", daemon::to_json(r)}}.dump() << std::endl;
      };
      cb.state = [](daemon::LifecycleState s, const std::string& detail) {
        std::cout << nlohmann::json{{"state", daemon::to_string(s)}, {"detail", detail}}.dump()
                  << std::endl;
      };
      cb.cloud = [](const PointCloud& c) {
        std::cout
            << nlohmann::json{{"cloud", {{"frame_id", c.frame_id}, {"points", c.size()}}}}.dump()
            << std::endl;
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
          std::cout << nlohmann::json{{"diagnostics", arr}}.dump() << std::endl;
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
