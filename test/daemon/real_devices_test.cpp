// driver = "real": the daemon builds the cell's drivers from the config. Tested against peers that
// speak the real protocol on this machine: the simulated Festo drive's Modbus TCP server on
// loopback (test/support/modbus_axis_server). SocketCAN and USB hardware are absent here, which is
// itself the case to test: reported, never fatal.
#include "daemon/cell/real_devices.hpp"

#include <gtest/gtest.h>

#include <thread>

#include "daemon/cell/device_backend.hpp"
#include "daemon/service/diagnostics.hpp"
#include "test/support/modbus_axis_server.hpp"

namespace rangefit::daemon {
namespace real_devices_test {

using std::chrono::milliseconds;

// A loopback port nobody listens on (taken from a server that is then closed).
int free_port() {
  sim::SimFhppDrive drive(sim::SimAxisConfig{});
  sim::SimAxisServer server(drive, {});
  EXPECT_TRUE(server.start().ok);
  const int port = server.port();
  server.stop();
  return port;
}

DeviceConfig real(const std::string& name, const std::string& kind, const std::string& transport) {
  DeviceConfig d;
  d.name = name;
  d.kind = kind;
  d.driver = DriverKind::kReal;
  d.transport = transport;
  return d;
}

hal::DeviceHealth health_of(const ScanBackend& backend, const std::string& name) {
  for (const auto& h : backend.health()) {
    if (h.name == name) return h.health;
  }
  ADD_FAILURE() << "no health for " << name;
  return {};
}

std::uint8_t diag_level(const ScanBackend& backend, const std::string& name) {
  DiagnosticsBuilder builder;
  for (const auto& s : builder.build(backend.health(), {}, hal::Timestamp(milliseconds(1)))) {
    if (s.hardware_id == name) return s.level;
  }
  return kDiagStale;
}

// Polls (not a timing assertion: the bound is generous) until pred holds.
template <class Pred>
bool eventually(Pred pred) {
  for (int i = 0; i < 300; ++i) {
    if (pred()) return true;
    std::this_thread::sleep_for(milliseconds(50));
  }
  return pred();
}

TEST(ModbusAddress, ParsesTcpAndRtuTransports) {
  ModbusAddress a;
  std::string why;
  ASSERT_TRUE(parse_modbus_address("10.0.0.5:502", &a, &why)) << why;
  EXPECT_EQ(a.host, "10.0.0.5");
  EXPECT_EQ(a.port, 502);
  ModbusAddress rtu;
  ASSERT_TRUE(parse_modbus_address("/dev/ttyUSB0", &rtu, &why));
  EXPECT_EQ(rtu.serial_device, "/dev/ttyUSB0");
  for (const char* bad : {"", "10.0.0.5", "10.0.0.5:0", "10.0.0.5:70000", "host:port", ":502"}) {
    ModbusAddress b;
    EXPECT_FALSE(parse_modbus_address(bad, &b, &why)) << bad;
    EXPECT_FALSE(why.empty());
  }
}

TEST(RealDevices, UnreadableTransportIsAStartUpErrorNamingTheDevice) {
  DaemonConfig config;
  config.devices.push_back(real("axis", "axis", "nowhere"));
  try {
    DeviceBackend backend(config);
    FAIL() << "accepted transport \"nowhere\"";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("device axis: transport"), std::string::npos) << e.what();
  }
}

TEST(RealDevices, AxisAbsentAtStartIsReportedAsErrorThenStreamsWhenTheDriveAppears) {
  const int port = free_port();
  DaemonConfig config;
  config.devices.push_back(real("axis", "axis", "127.0.0.1:" + std::to_string(port)));
  DeviceBackend backend(config);  // the drive is absent: not fatal
  EXPECT_TRUE(eventually([&] { return diag_level(backend, "axis") == kDiagError; }))
      << hal::to_string(health_of(backend, "axis").state);

  sim::SimFhppDrive drive(sim::SimAxisConfig{});
  sim::SimAxisServerConfig sc;
  sc.port = port;
  sim::SimAxisServer server(drive, sc);
  ASSERT_TRUE(server.start().ok);
  EXPECT_TRUE(eventually([&] {
    return health_of(backend, "axis").state == hal::DeviceState::kStreaming;
  })) << health_of(backend, "axis").message;
  EXPECT_EQ(diag_level(backend, "axis"), kDiagOk);
  EXPECT_GT(server.requests(), 0u);
}

TEST(RealDevices, ConfiguredModbusUnitIsTheOneTheDriveAnswers) {
  sim::SimFhppDrive drive(sim::SimAxisConfig{});
  sim::SimAxisServerConfig sc;
  sc.unit_id = 17;  // other units are answered with exception 0Bh (gateway target)
  sim::SimAxisServer server(drive, sc);
  ASSERT_TRUE(server.start().ok);
  DaemonConfig config;
  config.devices.push_back(real("axis", "axis", "127.0.0.1:" + std::to_string(server.port())));
  config.devices.back().modbus_unit = 17;
  DeviceBackend backend(config);
  EXPECT_TRUE(eventually([&] {
    return health_of(backend, "axis").state == hal::DeviceState::kStreaming;
  })) << health_of(backend, "axis").message;
}

TEST(RealDevices, ScanWithAnAbsentDeviceIsAnErrorResultNamingItAndTheBackendGoesOn) {
  const int port = free_port();
  DaemonConfig config;
  config.devices.push_back(real("axis", "axis", "127.0.0.1:" + std::to_string(port)));
  config.devices.push_back(real("stripe", "stripe", "rfnocan0"));  // no such CAN interface
  DeviceBackend backend(config);
  ScanRequest request;
  request.id = "r";
  request.kind = DetectKind::kObject;
  request.sensor = "stripe";
  std::atomic<bool> cancel{false};
  for (int attempt = 0; attempt < 2; ++attempt) {
    const ScanOutcome out = backend.scan(request, cancel, [] {});
    EXPECT_FALSE(out.status);
    EXPECT_NE(out.status.message.find("not available"), std::string::npos) << out.status.message;
    EXPECT_TRUE(out.cloud.empty());
  }
  EXPECT_EQ(diag_level(backend, "stripe"), kDiagError);
}

TEST(RealDevices, PanTiltHeadReportsItsRangerAndAnglesAndAScanWithoutTheBusIsAnError) {
  DaemonConfig config;
  config.devices.push_back(real("head", "pan_tilt", "rfnocan1"));  // no such CAN interface
  DeviceBackend backend(config);
  EXPECT_EQ(diag_level(backend, "head"), kDiagError);
  EXPECT_EQ(diag_level(backend, "head/angles"), kDiagError);
  ScanRequest request;
  request.id = "r";
  request.kind = DetectKind::kObject;
  request.sensor = "head";
  std::atomic<bool> cancel{false};
  const ScanOutcome out = backend.scan(request, cancel, [] {});
  EXPECT_FALSE(out.status);
  EXPECT_NE(out.status.message.find("not available"), std::string::npos) << out.status.message;
  EXPECT_TRUE(out.cloud.empty());
}

TEST(RealDevices, NoRealDevicesMeansNoHealthEntries) {
  DaemonConfig config;
  RealDevices devices(config);
  EXPECT_TRUE(devices.health().empty());
}

}  // namespace real_devices_test
}  // namespace rangefit::daemon
