#pragma once
// A simulated PowerCube (M5) module: answers a position GET with the simulated angle at the
// request's receive instant. Faults for tests: silence, the "not ok" state bit, short replies.

#include <atomic>
#include <functional>

#include "drivers/can/powercube_codec.hpp"
#include "test/support/can_bus.hpp"

namespace rangefit::sim {

class SimPowerCubeModule final : public SimCanDevice {
 public:
  SimPowerCubeModule(std::uint8_t module, std::function<double(hal::Timestamp)> angle = nullptr)
      : module_(module), angle_(std::move(angle)) {}

  void on_frame(const drivers::can::CanFrame& frame, drivers::can::CanTransport& bus) override;
  hal::Timestamp tick(hal::Timestamp now, drivers::can::CanTransport&) override {
    return now + std::chrono::milliseconds(20);
  }

  void set_angle(double rad) { angle_value_ = rad; }
  void set_silent(bool silent) { silent_ = silent; }
  void set_not_ok(bool not_ok) { not_ok_ = not_ok; }
  void short_next_reply() { short_reply_ = true; }
  std::uint64_t requests() const { return requests_; }

 private:
  std::uint8_t module_;
  std::function<double(hal::Timestamp)> angle_;
  std::atomic<double> angle_value_{0.0};
  std::atomic<bool> silent_{false}, not_ok_{false}, short_reply_{false};
  std::atomic<std::uint64_t> requests_{0};
};

}  // namespace rangefit::sim
