// rangefit models: the object models a running rangefitd knows (rt/rangefit/models), one per
// line with its parts, or as JSON. Exit 0 when the daemon answered, 1 when none did in time.
#include <chrono>
#include <cmath>
#include <iostream>
#include <optional>

#include <nlohmann/json.hpp>

#include "daemon/cli/commands.hpp"
#include "daemon/cli/option_checks.hpp"
#include "daemon/dds/models_msg.hpp"
#include "daemon/dds/topics.hpp"
#include "daemon/service/ros_env.hpp"

namespace rangefit::cli {
namespace {

struct ModelsArgs {
  std::optional<std::uint32_t> domain;
  double timeout_s = 10;
  bool json = false;
};

int run(const ModelsArgs& a) {
  try {
    const std::uint32_t domain = a.domain ? *a.domain : daemon::ros_domain_id().value_or(0);
    dds::Participant participant(domain);
    daemon::topics::Reader<daemon::topics::Models> reader(participant, daemon::topics::models());
    std::optional<std::vector<daemon::ModelInfo>> models;
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::milliseconds(std::llround(a.timeout_s * 1000));
    while (!models && std::chrono::steady_clock::now() < deadline) {
      if (reader.wait(std::chrono::milliseconds(100))) {
        reader.take_each(
            [&](const rangefit_msgs_msg_dds__Models_& m) { models = daemon::from_msg(m); });
      }
    }
    if (!models) {
      std::cerr << "rangefit models: no rangefitd on DDS domain " << domain << " within "
                << a.timeout_s << " s\n";
      return kExitBadInput;
    }
    if (a.json) {
      nlohmann::json out = nlohmann::json::array();
      for (const auto& m : *models) out.push_back({{"name", m.name}, {"parts", m.parts}});
      std::cout << out.dump(2) << "\n";
    } else {
      for (const auto& m : *models) {
        std::cout << m.name;
        for (std::size_t i = 0; i < m.parts.size(); ++i) {
          std::cout << (i == 0 ? "  (" : ", ") << m.parts[i];
        }
        std::cout << (m.parts.empty() ? "" : ")") << "\n";
      }
    }
    return kExitOk;
  } catch (const std::exception& e) {
    std::cerr << "rangefit models: " << e.what() << "\n";
    return kExitBadInput;
  }
}

}  // namespace

void add_models_command(CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand("models", "list the object models a running rangefitd knows");
  static ModelsArgs args;
  cmd->add_option("--domain", args.domain, "DDS domain id (default: ROS_DOMAIN_ID, else 0)")
      ->check(CLI::Range(0, 232));
  cmd->add_option("--timeout", args.timeout_s, "seconds to wait for the daemon")
      ->capture_default_str()
      ->check(finite_range(0.001, 86400.0));
  cmd->add_flag("--json", args.json, "print a JSON array of {name, parts}");
  cmd->callback([exit_code] { *exit_code = run(args); });
}

}  // namespace rangefit::cli
