// SIGHUP's reload (daemon/service): a configuration whose simulated scene cannot be loaded is
// refused with the reason, and the running configuration stays in force.
#include <gtest/gtest.h>

#include <filesystem>

#include "daemon/rangefitd/service.hpp"
#include "test/daemon/dds_test_env.hpp"

namespace rangefit::daemon {
namespace service_reload_test {
namespace fs = std::filesystem;

DaemonConfig sim_config(const fs::path& dir, const fs::path& scene) {
  DaemonConfig c;
  c.dds.domain_id = test::dds_test_domain();
  c.spool.directory = dir / "spool";
  c.sim.time_scale = 0.0;
  DeviceConfig css;
  css.name = css.kind = "css";
  css.driver = DriverKind::kSim;
  css.scene = scene;
  c.devices.push_back(css);
  c.service.bore_sensor = "css";
  return c;
}

fs::path emptied_temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  return dir;
}

// A service running the simulated bore plate, its spool in a temporary folder of its own.
struct RunningService {
  fs::path dir;
  fs::path plate = std::string(RANGEFIT_SOURCE_DIR) + "/data/scenes/bore_plate.toml";
  hal::MonotonicClock clock;
  Service service;
  explicit RunningService(const std::string& name)
      : dir(emptied_temp_dir(name)), service(sim_config(dir, plate), clock) {}
  ~RunningService() { fs::remove_all(dir); }
};

TEST(ServiceReload, BrokenSceneIsRefusedAndTheRunningConfigStays) {
  RunningService running("rangefit_service_reload_test");
  const fs::path &dir = running.dir, &plate = running.plate;
  Service& service = running.service;

  DaemonConfig broken = sim_config(dir, dir / "missing_scene.toml");
  broken.service.queue_capacity = 9;
  std::string why;
  EXPECT_FALSE(service.reload(broken, &why));
  EXPECT_NE(why.find("missing_scene.toml"), std::string::npos) << why;
  EXPECT_EQ(service.config().device("css")->scene, plate);
  EXPECT_EQ(service.config().service.queue_capacity, 4u);

  DaemonConfig good = sim_config(dir, plate);
  good.service.queue_capacity = 9;
  why.clear();
  EXPECT_TRUE(service.reload(good, &why)) << why;
  EXPECT_EQ(service.config().service.queue_capacity, 9u);
}

TEST(ServiceReload, ChangedDdsSecurityWaitsForARestart) {
  RunningService running("rangefit_service_reload_security_test");
  Service& service = running.service;
  DaemonConfig secured = sim_config(running.dir, running.plate);
  secured.dds.security.identity_ca = running.dir / "ca.pem";
  std::string why;
  EXPECT_FALSE(service.reload(secured, &why));
  EXPECT_NE(why.find("apply on restart only"), std::string::npos) << why;
  EXPECT_FALSE(service.config().dds.security.enabled());
}

TEST(ServiceReload, BrokenSceneAtStartIsAStartUpError) {
  const fs::path dir = fs::temp_directory_path() / "rangefit_service_start_test";
  hal::MonotonicClock clock;
  EXPECT_THROW(Service(sim_config(dir, dir / "missing_scene.toml"), clock), std::runtime_error);
  fs::remove_all(dir);
}

}  // namespace service_reload_test
}  // namespace rangefit::daemon
