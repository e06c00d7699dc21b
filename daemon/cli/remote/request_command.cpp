#include "daemon/cli/remote/request_command.hpp"

#include <array>
#include <chrono>
#include <cmath>
#include <iostream>
#include <optional>
#include <random>
#include <vector>

#include "daemon/cli/commands.hpp"
#include "daemon/cli/option_checks.hpp"
#include "daemon/dds/client.hpp"
#include "daemon/service/json_codec.hpp"
#include "daemon/service/result_outcome.hpp"
#include "daemon/service/ros_env.hpp"

namespace rangefit::cli {
namespace {

struct RequestArgs {
  std::optional<std::uint32_t> domain;  // none: ROS_DOMAIN_ID, else 0
  std::string id;
  std::string model;
  std::string sensor;
  bool linear = false;
  std::array<double, 3> position_mm{};
  std::array<double, 3> axis{0, 0, 1};
  double radius_mm = 0;
  std::array<double, 3> sweep{};  // start, end, speed
  double timeout_s = 120;
  std::vector<double> plane_normal;  // bore: optional
  int instances = 1;
  int hypotheses = 0;
  int trials = 0;
  std::uint64_t seed = 0;
};

std::string make_id() {
  std::random_device rd;
  return "req-" + std::to_string(rd() % 1000000);
}

int run(RequestArgs& a, daemon::DetectKind kind) {
  daemon::ScanRequest req;
  req.id = a.id.empty() ? make_id() : a.id;
  req.kind = kind;
  req.model = a.model;
  req.sensor = a.sensor;
  req.bore.position_mm = {a.position_mm[0], a.position_mm[1], a.position_mm[2]};
  req.bore.axis = {a.axis[0], a.axis[1], a.axis[2]};
  req.bore.radius_mm = a.radius_mm;
  req.sweep_start = a.sweep[0];
  req.sweep_end = a.sweep[1];
  req.sweep_speed = a.sweep[2];
  if (a.plane_normal.size() == 3) {
    req.bore.plane_normal =
        Eigen::Vector3d(a.plane_normal[0], a.plane_normal[1], a.plane_normal[2]);
  }
  req.instances = a.instances;
  req.hypotheses = a.hypotheses;
  req.trials = a.trials;
  req.seed = a.seed;
  try {
    const std::uint32_t domain = a.domain ? *a.domain : daemon::ros_domain_id().value_or(0);
    daemon::DdsClient client(domain);
    const auto timeout = std::chrono::milliseconds(std::llround(a.timeout_s * 1000));
    // Discovery may take a while when many clients start at once: the whole timeout is
    // available for it, and the result's own wait starts once the daemon is matched.
    if (!client.wait_for_daemon(timeout)) {
      std::cerr << "rangefit request: no rangefitd on DDS domain " << domain << " within "
                << a.timeout_s << " s\n";
      return kExitBadInput;
    }
    client.send(req, a.linear);
    const auto result = client.wait_result(req.id, timeout);
    if (!result) {
      std::cerr << "rangefit request: no result for " << req.id << " within " << a.timeout_s
                << " s\n";
      return kExitBadInput;
    }
    std::cout << daemon::to_json(*result).dump(2) << "\n";
    return daemon::exit_code_of(*result);
  } catch (const std::exception& e) {
    std::cerr << "rangefit request: " << e.what() << "\n";
    return kExitBadInput;
  }
}

void common(CLI::App* sub, RequestArgs& a) {
  sub->add_option("--domain", a.domain,
                  "DDS domain id of rangefitd (default: ROS_DOMAIN_ID, else 0)")
      ->check(CLI::Range(0, 232));
  sub->add_option("--id", a.id, "request id (default: random)");
  sub->add_option("--sensor", a.sensor, "device name (default: the daemon's default for the kind)");
  sub->add_option("--sweep", a.sweep, "sweep start end speed (mm or rad, per second)");
  sub->add_flag("--linear", a.linear, "the sensor sweeps linearly (values in mm)");
  sub->add_option("--timeout", a.timeout_s, "seconds to wait for the daemon and for the result")
      ->capture_default_str()
      ->check(finite_range(0.001, 86400.0));
  sub->add_option("--seed", a.seed, "seed of the detection (default: the daemon's)");
}

}  // namespace

void add_request_command(CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand("request", "ask a running rangefitd to scan and detect (DDS)");
  cmd->require_subcommand(1);
  static RequestArgs bore_args, object_args;
  auto* bore = cmd->add_subcommand("bore", "find a bore near a CAD prior");
  common(bore, bore_args);
  bore->add_option("--position", bore_args.position_mm, "expected entrance x y z, mm (world)")
      ->required();
  bore->add_option("--axis", bore_args.axis, "expected axis x y z")->capture_default_str();
  bore->add_option("--radius", bore_args.radius_mm, "expected radius, mm")->required();
  bore->add_option("--plane-normal", bore_args.plane_normal,
                   "normal x y z of the surface around the bore (default: the axis)")
      ->expected(3);
  bore->callback([exit_code] { *exit_code = run(bore_args, daemon::DetectKind::kBore); });
  auto* object = cmd->add_subcommand("object", "find a configured object model");
  common(object, object_args);
  object->add_option("--model", object_args.model, "object model name (daemon config)")->required();
  object->add_option("--instances", object_args.instances, "K: instances to report, best first")
      ->check(CLI::Range(1, 1000));
  object
      ->add_option("--hypotheses", object_args.hypotheses,
                   "m: pose hypotheses per part (default: the detector's)")
      ->check(CLI::Range(1, 10000));
  object->add_option("--trials", object_args.trials, "n: RANSAC trials per hypothesis")
      ->check(CLI::Range(1, 10000));
  object->callback([exit_code] { *exit_code = run(object_args, daemon::DetectKind::kObject); });
}

}  // namespace rangefit::cli
