#pragma once
// The mobile scanning head's pan and tilt axes as two CiA 402 nodes on one bus (thesis eq.
// 5.7-5.10). Runs a Cia402JointSource for both and pairs the two joints' samples of the same
// SYNC (equal stamps) into one PanTiltSample; a SYNC where one axis is missing yields nothing.

#include <memory>
#include <optional>

#include "drivers/can/cia402_joint_source.hpp"

namespace rangefit::drivers::can {

struct PanTiltConfig {
  Cia402Config bus;  // sync, heartbeat and loop settings; joints are set from below
  Cia402JointConfig pan{1, 1, 1e-6, 0.0};
  Cia402JointConfig tilt{2, 2, 1e-6, 0.0};
};

// The joint configuration the underlying driver runs (pan and tilt nodes filled in).
Cia402Config pan_tilt_bus_config(const PanTiltConfig& config);

class Cia402PanTiltSource final : public hal::PanTiltSource {
 public:
  Cia402PanTiltSource(const PanTiltConfig& config, std::unique_ptr<CanTransport> transport);

  std::string name() const override { return joints_.name(); }
  hal::Status start() override { return joints_.start(); }
  void stop() override { joints_.stop(); }
  hal::DeviceHealth health() const override { return joints_.health(); }
  std::size_t read(std::vector<hal::PanTiltSample>& out, hal::Duration timeout) override;
  CanCounters counters() const { return joints_.counters(); }

 private:
  std::uint8_t pan_joint_;
  std::uint8_t tilt_joint_;
  Cia402JointSource joints_;
  std::vector<hal::JointSample> scratch_;
  std::optional<hal::JointSample> pan_, tilt_;  // waiting for their partner
};

}  // namespace rangefit::drivers::can
