#include "drivers/can/cia402_pan_tilt_source.hpp"

namespace rangefit::drivers::can {

Cia402Config pan_tilt_bus_config(const PanTiltConfig& config) {
  Cia402Config bus = config.bus;
  bus.joints = {config.pan, config.tilt};
  if (bus.name == Cia402Config{}.name) bus.name = "pan-tilt";
  return bus;
}

Cia402PanTiltSource::Cia402PanTiltSource(const PanTiltConfig& config,
                                         std::unique_ptr<CanTransport> transport)
    : pan_joint_(config.pan.joint),
      tilt_joint_(config.tilt.joint),
      joints_(pan_tilt_bus_config(config), std::move(transport)) {}

std::size_t Cia402PanTiltSource::read(std::vector<hal::PanTiltSample>& out, hal::Duration timeout) {
  const hal::Timestamp deadline = hal::monotonic_now() + timeout;
  std::size_t produced = 0;
  do {
    scratch_.clear();
    joints_.read(scratch_, deadline - hal::monotonic_now());
    for (const hal::JointSample& s : scratch_) {
      if (s.joint == pan_joint_)
        pan_ = s;
      else if (s.joint == tilt_joint_)
        tilt_ = s;
      if (pan_ && tilt_ && pan_->stamp == tilt_->stamp) {
        out.push_back(
            {pan_->stamp, pan_->angle_rad, tilt_->angle_rad, pan_->valid && tilt_->valid});
        ++produced;
        pan_.reset();
        tilt_.reset();
      }
    }
  } while (produced == 0 && hal::monotonic_now() < deadline);
  return produced;
}

}  // namespace rangefit::drivers::can
