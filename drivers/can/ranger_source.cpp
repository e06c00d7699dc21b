#include "drivers/can/ranger_source.hpp"

#include <cmath>

#include "drivers/can/cia402_codec.hpp"
#include "hal/stripe_geometry.hpp"

namespace rangefit::drivers::can {

namespace {
hal::RangerProfile prototype() {
  hal::RangerProfile p;
  p.x_mm.reserve(ranger::kMaxPoints);
  p.z_mm.reserve(ranger::kMaxPoints);
  return p;
}
}  // namespace

FrameFilter ranger_filter(const RangerConfig& config) {
  FrameFilter f;
  f.ids = {ranger::profile_id(config.node), cia402::heartbeat_id(config.node),
           cia402::emcy_id(config.node)};
  return f;
}

RangerCanSource::RangerCanSource(RangerConfig config, std::unique_ptr<CanTransport> transport)
    : CanSource(config.name, std::move(transport), config.queue_capacity, config.loop, prototype()),
      config_(std::move(config)),
      reassembler_(config_.incomplete_timeout),
      scratch_(prototype()) {}

void RangerCanSource::on_link(bool up) {
  if (!up) {
    report(Problem::kLinkDown);
    return;
  }
  last_heartbeat_ = hal::monotonic_now();
  send(cia402::encode_nmt(cia402::kNmtStart, config_.node));
}

std::size_t RangerCanSource::pending_incomplete() {
  const std::uint64_t now = reassembler_.counters().incomplete;
  const std::uint64_t n = now - incomplete_seen_;
  incomplete_seen_ = now;
  return static_cast<std::size_t>(n);
}

hal::Timestamp RangerCanSource::on_tick(hal::Timestamp now) {
  if (reassembler_.expire(now)) report(Problem::kTimeout, config_.node);
  if (const std::size_t n = pending_incomplete()) bump(Counter::kTimeouts, n);
  if (alive_ && now - last_heartbeat_ > config_.heartbeat_timeout) {
    alive_ = false;
    bump(Counter::kNodesLost);
    report(Problem::kNodeLost, config_.node);
  }
  return now + std::chrono::milliseconds(10);
}

void RangerCanSource::on_frame(const CanFrame& f) {
  if (f.id == ranger::profile_id(config_.node)) {
    switch (reassembler_.feed(f)) {
      case ranger::FeedResult::kComplete:
        deliver_profile();
        break;
      case ranger::FeedResult::kCrcError:
        bump(Counter::kCrcErrors);
        report(Problem::kCrcError, config_.node);
        break;
      case ranger::FeedResult::kBadFrame:
        bump(Counter::kBadLengths);
        break;
      case ranger::FeedResult::kDuplicate:
        bump(Counter::kDuplicates);
        break;
      case ranger::FeedResult::kPending:
        break;
    }
    if (const std::size_t n = pending_incomplete()) bump(Counter::kTimeouts, n);
    return;
  }
  const cia402::Message m = cia402::decode(f);
  if (m.kind == cia402::Kind::kHeartbeat && m.node == config_.node) {
    last_heartbeat_ = f.stamp;
    alive_ = true;
    if (m.nmt_state == cia402::kBootUp) {
      bump(Counter::kReboots);
      report(Problem::kNodeReboot, config_.node);
      have_offset_ = false;  // the device clock restarted
      send(cia402::encode_nmt(cia402::kNmtStart, config_.node));
    }
  } else if (m.kind == cia402::Kind::kEmcy && m.node == config_.node) {
    if (m.emcy_code != 0) {
      bump(Counter::kFaults);
      report(Problem::kEmcy, config_.node);
    }
  } else if (m.kind == cia402::Kind::kBadLength) {
    bump(Counter::kBadLengths);
  } else {
    bump(Counter::kUnknownIds);
  }
}

void RangerCanSource::deliver_profile() {
  const ranger::WireProfile& w = reassembler_.profile();
  if (have_sequence_) {
    const std::uint32_t step = w.sequence - last_sequence_;
    if (step == 0 || step > 0x8000'0000u) {
      bump(step == 0 ? Counter::kDuplicates : Counter::kReordered);
      return;
    }
    if (step > 1) bump(Counter::kGaps, step - 1);
  }
  have_sequence_ = true;
  last_sequence_ = w.sequence;
  // Unwrap the 32-bit µs device clock, then map it with the running-minimum offset.
  if (!have_offset_)
    device_us_ = w.device_time_us;
  else
    device_us_ += static_cast<std::int32_t>(w.device_time_us - last_device_us_);
  last_device_us_ = w.device_time_us;
  const std::int64_t measured = reassembler_.header_stamp().count() - device_us_ * 1000;
  if (!have_offset_ || measured < offset_ns_ + config_.offset_creep.count()) {
    offset_ns_ = measured;
  } else {
    offset_ns_ += config_.offset_creep.count();
  }
  have_offset_ = true;

  scratch_.sequence = w.sequence;
  scratch_.stamp = hal::Timestamp{device_us_ * 1000 + offset_ns_};
  scratch_.exposure = std::chrono::microseconds(w.exposure_us);
  scratch_.flags = w.flags & (hal::kRangerOverrun | hal::kRangerSaturated | hal::kRangerLaserOff);
  if (w.flags & ranger::kWireOverrun) bump(Counter::kFaults);
  const std::size_t n = w.point_count;
  scratch_.x_mm.resize(n);
  scratch_.z_mm.resize(n);
  const double centre = (static_cast<double>(n) - 1.0) / 2.0;
  const double unit_mm = w.units_um / 1000.0;
  const hal::StripeRanger fan{.fan_angle_rad = config_.fan_angle_rad};
  for (std::size_t k = 0; k < n; ++k) {
    if (w.range[k] == ranger::kNoReturn) {
      scratch_.x_mm[k] = hal::kNoReturn;
      scratch_.z_mm[k] = hal::kNoReturn;
      continue;
    }
    const double z = config_.range_offset_mm + w.range[k] * unit_mm;
    const double x = config_.fan_angle_rad > 0.0 && n > 1
                         ? z * std::tan(fan.ray_angle(static_cast<int>(k), static_cast<int>(n)))
                         : (static_cast<double>(k) - centre) * config_.lateral_pitch_mm;
    scratch_.x_mm[k] = static_cast<float>(x);
    scratch_.z_mm[k] = static_cast<float>(z);
  }
  deliver(scratch_);
}

}  // namespace rangefit::drivers::can
