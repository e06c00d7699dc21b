// SIGHUP's reload (daemon/service): a configuration whose simulated scene cannot be loaded is
// refused with the reason, and the running configuration stays in force.
#include <gtest/gtest.h>

#include <filesystem>

#include "daemon/service.hpp"
#include "test/daemon/dds_test_env.hpp"

namespace rangefit::daemon {
namespace {
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

TEST(ServiceReload, BrokenSceneIsRefusedAndTheRunningConfigStays) {
  const fs::path dir = fs::temp_directory_path() / "rangefit_service_reload_test";
  fs::remove_all(dir);
  const fs::path plate = std::string(RANGEFIT_SOURCE_DIR) + "/data/scenes/bore_plate.toml";
  hal::MonotonicClock clock;
  Service service(sim_config(dir, plate), clock);

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
  fs::remove_all(dir);
}

TEST(ServiceReload, ChangedDdsSecurityWaitsForARestart) {
  const fs::path dir = fs::temp_directory_path() / "rangefit_service_reload_security_test";
  fs::remove_all(dir);
  const fs::path plate = std::string(RANGEFIT_SOURCE_DIR) + "/data/scenes/bore_plate.toml";
  hal::MonotonicClock clock;
  Service service(sim_config(dir, plate), clock);
  DaemonConfig secured = sim_config(dir, plate);
  secured.dds.security.identity_ca = dir / "ca.pem";
  std::string why;
  EXPECT_FALSE(service.reload(secured, &why));
  EXPECT_NE(why.find("apply on restart only"), std::string::npos) << why;
  EXPECT_FALSE(service.config().dds.security.enabled());
  fs::remove_all(dir);
}

TEST(ServiceReload, BrokenSceneAtStartIsAStartUpError) {
  const fs::path dir = fs::temp_directory_path() / "rangefit_service_start_test";
  hal::MonotonicClock clock;
  EXPECT_THROW(Service(sim_config(dir, dir / "missing_scene.toml"), clock), std::runtime_error);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rangefit::daemon
