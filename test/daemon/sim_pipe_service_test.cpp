// A thick-walled pipe (inner r 6, outer r 8 mm) under the simulated CSS, asked for through DDS
// with both walls, is found as `rangefit bore --walls both` finds it on the spooled scan with the
// CSS's view direction: the same entrance, axis and radii, both walls within 50 um of the truth.
// Without the pipe fields the service used to fit one cylinder between the walls (r = 7).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>

#include "daemon/dds/client.hpp"
#include "daemon/rangefitd/service.hpp"
#include "daemon/service/scan_sensor.hpp"
#include "io/stl.hpp"
#include "test/daemon/cli_run.hpp"
#include "test/daemon/replay_service.hpp"

namespace rangefit::daemon {
namespace sim_pipe_service_test {
namespace fs = std::filesystem;

constexpr double kTop = 285.8;  // the CSS's standoff plane (data/scenes/bore_plate.toml)

// A tube along z, its end face the annulus inner..outer at z = kTop, closed at the bottom end.
io::TriangleMesh pipe_mesh(double inner, double outer, double length, int segments) {
  io::TriangleMesh m;
  for (const double z : {kTop, kTop - length}) {
    for (const double r : {inner, outer}) {
      for (int i = 0; i < segments; ++i) {
        const double a = 2.0 * std::numbers::pi * i / segments;
        m.vertices.emplace_back(r * std::cos(a), r * std::sin(a), z);
      }
    }
  }
  const auto v = [segments](int ring, int i) {  // rings: top inner, top outer, bottom in, out
    return static_cast<std::uint32_t>(ring * segments + (i % segments));
  };
  for (int i = 0; i < segments; ++i) {
    const int j = i + 1;
    m.triangles.push_back({v(0, i), v(1, i), v(1, j)});  // top annulus, facing +z
    m.triangles.push_back({v(0, i), v(1, j), v(0, j)});
    m.triangles.push_back({v(1, i), v(3, i), v(3, j)});  // outer wall, facing out
    m.triangles.push_back({v(1, i), v(3, j), v(1, j)});
    m.triangles.push_back({v(0, i), v(0, j), v(2, j)});  // inner wall, facing the axis
    m.triangles.push_back({v(0, i), v(2, j), v(2, i)});
    m.triangles.push_back({v(2, i), v(2, j), v(3, j)});  // bottom annulus, facing -z
    m.triangles.push_back({v(2, i), v(3, j), v(3, i)});
  }
  return m;
}

#ifdef RANGEFIT_CLI_PATH
nlohmann::json run_cli_json(const std::string& args, int* exit_code) {
  const test::CliRun r = test::run_command(std::string(RANGEFIT_CLI_PATH) + " " + args);
  *exit_code = r.exit_code;
  return nlohmann::json::parse(r.output, nullptr, false);
}

std::string arg(const Eigen::Vector3d& v) {
  char s[128];
  std::snprintf(s, sizeof s, "%.17g,%.17g,%.17g", v.x(), v.y(), v.z());
  return s;
}

Eigen::Vector3d vec(const nlohmann::json& j) {
  return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
}

TEST(SimPipeService, BothWallsThroughDdsEqualTheCliOnTheSpooledScan) {
  const fs::path dir = test::fresh_test_dir("rangefit_sim_pipe_service");
  io::write_stl(dir / "pipe.stl", pipe_mesh(6.0, 8.0, 30.0, 256));
  std::ofstream(dir / "pipe.toml") << "[[object]]\nname = \"pipe\"\ntype = \"mesh\"\n"
                                      "file = \"pipe.stl\"\n";
  DaemonConfig config;
  config.dds.domain_id = test::dds_test_domain();
  config.spool.directory = dir / "spool";
  config.spool.pictures = false;
  config.sim.time_scale = 0.0;
  config.sim.seed = 3;
  DeviceConfig css;
  css.name = css.kind = "css";
  css.scene = dir / "pipe.toml";
  config.devices.push_back(css);
  config.service.bore_sensor = "css";
  hal::MonotonicClock clock;
  Service service(config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);
  DdsClient client(config.dds.domain_id);
  ASSERT_TRUE(client.wait_for_daemon(std::chrono::seconds(20)));
  ScanRequest req;
  req.id = "pipe";
  req.kind = DetectKind::kBore;
  req.bore.position_mm = Eigen::Vector3d(0.3, -0.2, kTop);  // CAD vs. real
  req.bore.axis = Eigen::Vector3d(0.01, 0.0, 1.0);
  req.bore.radius_mm = 6.0;
  req.bore.outer_radius_mm = 8.0;
  req.bore.walls = "both";
  req.seed = 5;
  ASSERT_TRUE(client.send(req, false));
  const auto result = client.wait_result(req.id, std::chrono::seconds(120));
  loop.reset();
  ASSERT_TRUE(result);
  ASSERT_TRUE(result->found) << result->reason;
  ASSERT_EQ(result->parts.size(), 2u);
  EXPECT_EQ(result->parts[0].name, "bore");
  EXPECT_EQ(result->parts[1].name, "outer");
  ASSERT_TRUE(result->details.is_object());
  const double outer_radius = result->details.at("outer").at("radius_mm").get<double>();
  const Eigen::Vector3d truth(0.0, 0.0, kTop);
  const Eigen::Isometry3d& inner = result->parts[0].T_world_part;
  const Eigen::Isometry3d& outer = result->parts[1].T_world_part;
  EXPECT_NEAR(result->bore_radius_mm, 6.0, 0.05);
  EXPECT_NEAR(outer_radius, 8.0, 0.05);
  EXPECT_LT((inner.translation() - truth).norm(), 0.05);
  EXPECT_LT((outer.translation() - truth).norm(), 0.05);
  EXPECT_GT(std::abs(inner.linear().col(2).z()), std::cos(0.1 * std::numbers::pi / 180));

  // The CLI on the very cloud the service detected in, told the CSS's view direction.
  const ScanSensor sensor = css_sensor(hal::CssGeometry{}, 0.0);
  ASSERT_TRUE(sensor.view_dir);
  int code = -1;
  const nlohmann::json cli = run_cli_json(
      "bore --cloud " + (fs::path(result->spool_entry) / "cloud.ply").string() +
          " --cad-entrance " + arg(req.bore.position_mm) + " --cad-axis " + arg(req.bore.axis) +
          " --cad-radius 6 --cad-outer-radius 8 --walls both --seed 5 --json --view-dir " +
          arg(*sensor.view_dir),
      &code);
  ASSERT_EQ(code, 0) << cli.dump();
  // The service's pose crossed DDS in metres: equal up to the conversion's last bits.
  EXPECT_LT((vec(cli.at("entrance")) - inner.translation()).norm(), 1e-9);
  EXPECT_LT((vec(cli.at("axis")) - inner.linear().col(2)).norm(), 1e-9);
  EXPECT_NEAR(cli.at("radius").get<double>(), result->bore_radius_mm, 1e-9);
  EXPECT_LT((vec(cli.at("outer").at("entrance")) - outer.translation()).norm(), 1e-9);
  EXPECT_NEAR(cli.at("outer").at("radius").get<double>(), outer_radius, 1e-12);
  fs::remove_all(dir);
}
#endif

}  // namespace sim_pipe_service_test
}  // namespace rangefit::daemon
