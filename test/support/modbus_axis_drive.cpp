#include "test/support/modbus_axis_drive.hpp"

#include <algorithm>
#include <cmath>

namespace rangefit::sim {

namespace fhpp = drivers::fhpp;

namespace {
double seconds(hal::Duration d) { return std::chrono::duration<double>(d).count(); }
}  // namespace

SimFhppDrive::SimFhppDrive(SimAxisConfig config) : config_(config) {
  const double p = std::clamp(config_.initial_mm, config_.min_mm, config_.max_mm);
  path_.push_back({hal::Timestamp::min(), p, 0.0, hal::Timestamp::min(), p});
  referenced_ = config_.referenced;
}

double SimFhppDrive::position_locked(hal::Timestamp t) const {
  // Segments are appended in time order; the last one starting at or before t holds t.
  auto it = std::upper_bound(path_.begin(), path_.end(), t,
                             [](hal::Timestamp x, const Segment& s) { return x < s.t0; });
  if (it == path_.begin()) return path_.front().p0;
  const Segment& s = *(it - 1);
  if (t >= s.t1) return s.p1;
  return s.p0 + s.v * seconds(t - s.t0);
}

double SimFhppDrive::position_at(hal::Timestamp t) const {
  std::lock_guard lock(mutex_);
  return position_locked(t);
}

bool SimFhppDrive::moving(hal::Timestamp t) const { return t < path_.back().t1; }

void SimFhppDrive::move(hal::Timestamp t, double target_mm, double speed_mm_s) {
  const double p = position_locked(t);
  const double target = std::clamp(target_mm, config_.min_mm, config_.max_mm);
  Segment s{t, p, 0.0, t, target};
  if (speed_mm_s > 0.0 && target != p) {
    const double duration_s = std::abs(target - p) / speed_mm_s;
    s.v = target > p ? speed_mm_s : -speed_mm_s;
    s.t1 = t + std::chrono::duration_cast<hal::Duration>(std::chrono::duration<double>(duration_s));
  }
  path_.push_back(s);
}

void SimFhppDrive::stop_motion(hal::Timestamp t) {
  if (!moving(t)) return;
  const double p = position_locked(t);
  path_.push_back({t, p, 0.0, t, p});
  homing_ = false;
}

void SimFhppDrive::latch_fault(hal::Timestamp t, const std::string& reason) {
  stop_motion(t);
  fault_ = true;
  fault_reason_ = reason;
  enabled_ = open_ = ack_ = false;
  armed_ = false;  // one fault per silence, not one per period
}

void SimFhppDrive::update(hal::Timestamp t) {
  if (armed_ && config_.comm_timeout > hal::Duration::zero() && !fault_ &&
      t - last_request_ > config_.comm_timeout) {
    latch_fault(last_request_ + config_.comm_timeout, "connection timeout (fault 47h)");
  }
  if (homing_ && !moving(t)) {
    homing_ = false;
    referenced_ = true;
  }
}

void SimFhppDrive::write(const fhpp::OutputTelegram& out, hal::Timestamp t, int client) {
  std::lock_guard lock(mutex_);
  update(t);
  const fhpp::OutputTelegram prev = previous_[client];
  previous_[client] = out;
  const auto rising = [&](std::uint8_t now, std::uint8_t before, std::uint8_t bit) {
    return (now & bit) && !(before & bit);
  };
  if (controller_ != client) {
    const bool takes_over = controller_ == -1 || rising(out.ccon, prev.ccon, fhpp::kCconEnable);
    if (!takes_over) return;
    controller_ = client;
  }
  last_request_ = t;
  armed_ = true;
  if (fault_ && rising(out.ccon, prev.ccon, fhpp::kCconReset)) {
    fault_ = false;
    fault_reason_.clear();
  }
  enabled_ = !fault_ && (out.ccon & fhpp::kCconEnable);
  open_ = enabled_ && (out.ccon & fhpp::kCconStop);
  halt_ = !(out.cpos & fhpp::kCposHalt);
  if (!open_ || halt_) stop_motion(t);
  if (!(out.cpos & (fhpp::kCposStart | fhpp::kCposHome))) ack_ = false;
  if (!open_ || halt_) return;
  if (rising(out.cpos, prev.cpos, fhpp::kCposHome)) {
    homing_ = true;
    referenced_ = false;
    velocity_pct_ = config_.scale.mm_s_to_pct(config_.homing_speed_mm_s);
    move(t, config_.home_mm, config_.homing_speed_mm_s);
    ack_ = true;
  } else if (rising(out.cpos, prev.cpos, fhpp::kCposStart)) {
    warn_ = !referenced_;  // a positioning task needs a reference: refused with WARN
    if (referenced_) {
      velocity_pct_ = out.velocity_pct;
      move(t, config_.scale.to_mm(out.position_inc), config_.scale.pct_to_mm_s(out.velocity_pct));
      ack_ = true;
    }
  }
}

fhpp::InputTelegram SimFhppDrive::read(hal::Timestamp t, int client) {
  std::lock_guard lock(mutex_);
  update(t);
  fhpp::InputTelegram in;
  in.scon = fhpp::kSconLoadVoltage | fhpp::kSconModeDirect;
  if (enabled_) in.scon |= fhpp::kSconEnabled;
  if (open_) in.scon |= fhpp::kSconOpen;
  if (warn_) in.scon |= fhpp::kSconWarn;
  if (fault_) in.scon |= fhpp::kSconFault;
  if (controller_ != -1 && controller_ != client) in.scon |= fhpp::kSconFctMmi;
  const bool mov = moving(t);
  if (!halt_) in.spos |= fhpp::kSposHalt;
  if (ack_) in.spos |= fhpp::kSposAck;
  if (!mov) in.spos |= fhpp::kSposMotionComplete | fhpp::kSposStandstill;
  if (mov) in.spos |= fhpp::kSposMoving;
  if (referenced_) in.spos |= fhpp::kSposReferenced;
  in.velocity_pct = mov ? velocity_pct_ : 0;
  in.position_inc = config_.scale.to_increments(position_locked(t));
  return in;
}

void SimFhppDrive::disconnected(int client) {
  std::lock_guard lock(mutex_);
  previous_.erase(client);
  if (controller_ == client) controller_ = -1;
}

void SimFhppDrive::tick(hal::Timestamp t) {
  std::lock_guard lock(mutex_);
  update(t);
}

void SimFhppDrive::inject_fault(hal::Timestamp t, const std::string& reason) {
  std::lock_guard lock(mutex_);
  latch_fault(t, reason);
}

bool SimFhppDrive::fault() const {
  std::lock_guard lock(mutex_);
  return fault_;
}

std::string SimFhppDrive::fault_reason() const {
  std::lock_guard lock(mutex_);
  return fault_reason_;
}

int SimFhppDrive::controller() const {
  std::lock_guard lock(mutex_);
  return controller_;
}

}  // namespace rangefit::sim
