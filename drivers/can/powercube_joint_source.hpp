#pragma once
// Robot joints as Schunk/AMTEC PowerCube modules: the driver polls each module's position in
// turn (one request, one reply, per joint) and stamps a sample with the reply's receive stamp,
// optionally minus half the round trip. A reply that does not come within the timeout is
// counted; a module that misses several in a row is reported silent until it answers again.

#include <memory>
#include <string>
#include <vector>

#include "drivers/can/can_source.hpp"
#include "drivers/can/powercube_codec.hpp"

namespace rangefit::drivers::can {

struct PowerCubeModuleConfig {
  std::uint8_t module = 1;  // 1..31
  std::uint8_t joint = 1;   // JointSample::joint
  double offset_rad = 0.0;  // angle = reported position + offset
};

struct PowerCubeConfig {
  std::string name = "powercube";
  std::vector<PowerCubeModuleConfig> modules;
  hal::Duration poll_period = std::chrono::milliseconds(10);  // one round over all modules
  hal::Duration reply_timeout = std::chrono::milliseconds(5);
  bool subtract_half_round_trip = true;
  int misses_until_lost = 3;
  std::size_t queue_capacity = 4096;
  LoopConfig loop;
};

FrameFilter powercube_filter(const PowerCubeConfig& config);

class PowerCubeJointSource final : public CanSource<hal::JointSample> {
 public:
  PowerCubeJointSource(PowerCubeConfig config, std::unique_ptr<CanTransport> transport);
  ~PowerCubeJointSource() override { stop(); }

 private:
  hal::Status check_config() const override;
  void on_start(hal::Timestamp now) override;
  bool devices_faulted() const override { return lost_modules_ > 0; }
  hal::Timestamp on_tick(hal::Timestamp now) override;
  void on_frame(const CanFrame& frame) override;
  void on_link(bool up) override;
  void request_next(hal::Timestamp now);

  PowerCubeConfig config_;
  std::vector<int> misses_;
  std::vector<std::uint8_t> last_state_;
  std::size_t current_ = 0;  // module index polled last
  bool outstanding_ = false;
  hal::Timestamp request_time_{};
  hal::Timestamp round_start_{};
  std::atomic<int> lost_modules_{0};
};

}  // namespace rangefit::drivers::can
