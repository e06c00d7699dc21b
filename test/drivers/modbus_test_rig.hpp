#pragma once
// Test rig for the FHPP driver: the simulated drive behind its Modbus TCP server on loopback,
// optionally behind the fault proxy, and the real driver with short periods and timeouts.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "drivers/modbus/fhpp_axis.hpp"
#include "test/support/fault_proxy.hpp"
#include "test/support/modbus_axis_drive.hpp"
#include "test/support/modbus_axis_server.hpp"

namespace rangefit::test {

using namespace std::chrono_literals;

inline sim::SimAxisConfig sim_axis_config() {
  sim::SimAxisConfig c;
  c.scale = {.increments_per_mm = 1000.0, .max_speed_mm_s = 500.0};
  c.min_mm = 0.0;
  c.max_mm = 500.0;
  c.initial_mm = 100.0;
  c.homing_speed_mm_s = 500.0;
  c.comm_timeout = 600ms;
  return c;
}

inline drivers::FhppAxisConfig fast_axis_config(int port) {
  drivers::FhppAxisConfig c;
  c.link.port = port;
  c.link.response_timeout = 100ms;
  c.link.byte_timeout = 20ms;
  c.scale = {.increments_per_mm = 1000.0, .max_speed_mm_s = 500.0};
  c.travel = {.min_mm = 0.0, .max_mm = 500.0, .margin_mm = 2.0, .max_speed_mm_s = 500.0};
  c.poll_period = 5ms;
  c.max_round_trip = 30ms;
  c.backoff_initial = 5ms;
  c.backoff_max = 80ms;
  c.drive_comm_timeout = 600ms;
  c.command_timeout = 500ms;
  return c;
}

// Polls pred every millisecond until it holds or `timeout` passes.
inline bool wait_until(const std::function<bool()>& pred, std::chrono::milliseconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < end) {
    if (pred()) return true;
    std::this_thread::sleep_for(1ms);
  }
  return pred();
}

inline bool any_event_contains(const drivers::FhppAxis& axis, const std::string& text) {
  const auto ev = axis.events();
  return std::any_of(ev.begin(), ev.end(),
                     [&](const std::string& e) { return e.find(text) != std::string::npos; });
}

inline std::string joined_events(const drivers::FhppAxis& axis) {
  std::string s;
  for (const auto& e : axis.events()) s += "\n  " + e;
  return s;
}

struct ModbusRig {
  explicit ModbusRig(bool with_proxy, sim::SimAxisServerConfig server_config = {},
                     sim::SimAxisConfig drive_config = sim_axis_config())
      : drive(drive_config), server(drive, server_config) {
    EXPECT_TRUE(server.start().ok);
    int port = server.port();
    if (with_proxy) {
      proxy = std::make_unique<sim::FaultProxy>("127.0.0.1", server.port());
      EXPECT_TRUE(proxy->start().ok);
      port = proxy->port();
    }
    config = fast_axis_config(port);
  }
  drivers::FhppAxis& make_axis() {
    axis = std::make_unique<drivers::FhppAxis>(config);
    return *axis;
  }
  bool streaming() const { return axis->health().state == hal::DeviceState::kStreaming; }
  // Starts the driver and waits until it streams.
  void start_streaming() {
    if (!axis) make_axis();
    ASSERT_TRUE(axis->start().ok);
    ASSERT_TRUE(wait_until([&] { return streaming(); }, 2s)) << joined_events(*axis);
  }
  void enable_and_home() {
    ASSERT_TRUE(axis->enable().ok) << axis->health().message;
    ASSERT_TRUE(axis->home().ok) << axis->health().message;
    ASSERT_TRUE(wait_until([&] { return axis->motion_complete(); }, 2s));
  }
  std::uint64_t exchanges() const { return axis->stats().exchanges; }
  // True when the driver keeps exchanging telegrams (n more successful polls).
  bool polls_again(std::uint64_t n = 5) {
    const auto start = exchanges();
    return wait_until([&] { return exchanges() >= start + n && streaming(); }, 3s);
  }

  sim::SimFhppDrive drive;
  sim::SimAxisServer server;
  std::unique_ptr<sim::FaultProxy> proxy;
  drivers::FhppAxisConfig config;
  std::unique_ptr<drivers::FhppAxis> axis;
};

}  // namespace rangefit::test
