#include "drivers/can/powercube_joint_source.hpp"

namespace rangefit::drivers::can {

FrameFilter powercube_filter(const PowerCubeConfig& config) {
  FrameFilter f;
  for (const auto& m : config.modules) f.ids.push_back(powercube::reply_id(m.module));
  return f;
}

PowerCubeJointSource::PowerCubeJointSource(PowerCubeConfig config,
                                           std::unique_ptr<CanTransport> transport)
    : CanSource(config.name, std::move(transport), config.queue_capacity, config.loop),
      config_(std::move(config)),
      misses_(config_.modules.size(), 0),
      last_state_(config_.modules.size(), 0) {}

hal::Status PowerCubeJointSource::check_config() const {
  if (config_.modules.empty()) return hal::Status::Error(config_.name + ": no modules configured");
  return hal::Status::Ok();
}

void PowerCubeJointSource::on_start(hal::Timestamp now) {
  current_ = config_.modules.size() - 1;  // the first poll goes to module 0
  round_start_ = now;
  outstanding_ = false;
}

void PowerCubeJointSource::on_link(bool up) {
  if (!up) report(Problem::kLinkDown);
  outstanding_ = false;
}

void PowerCubeJointSource::request_next(hal::Timestamp now) {
  current_ = (current_ + 1) % config_.modules.size();
  if (current_ == 0) round_start_ = now;
  const std::uint8_t module = config_.modules[current_].module;
  if (send(powercube::encode_position_request(module)) != TxResult::kOk) return;
  outstanding_ = true;
  request_time_ = now;
}

hal::Timestamp PowerCubeJointSource::on_tick(hal::Timestamp now) {
  if (outstanding_) {
    if (now - request_time_ < config_.reply_timeout) return request_time_ + config_.reply_timeout;
    outstanding_ = false;
    bump(Counter::kTimeouts);
    const std::uint8_t module = config_.modules[current_].module;
    report(Problem::kTimeout, module);
    if (++misses_[current_] == config_.misses_until_lost) {
      bump(Counter::kNodesLost);
      ++lost_modules_;
      report(Problem::kNodeLost, module);
    }
  }
  // A new round starts one poll period after the previous one; modules within a round follow
  // each other back to back.
  const bool round_done = current_ + 1 == config_.modules.size();
  if (round_done && now < round_start_ + config_.poll_period) {
    return round_start_ + config_.poll_period;
  }
  request_next(now);
  return now + config_.reply_timeout;
}

void PowerCubeJointSource::on_frame(const CanFrame& f) {
  const powercube::Message m = powercube::decode(f);
  if (m.kind == powercube::Kind::kBadLength) {
    bump(Counter::kBadLengths);
    return;
  }
  if (m.kind != powercube::Kind::kPositionReply) {
    bump(Counter::kUnknownIds);
    return;
  }
  const std::size_t i = current_;
  if (!outstanding_ || config_.modules[i].module != m.module) {
    bump(Counter::kDuplicates);  // late reply after its timeout, or unsolicited
    return;
  }
  outstanding_ = false;
  if (misses_[i] >= config_.misses_until_lost) --lost_modules_;
  misses_[i] = 0;
  const bool not_ok = (m.reply.state & powercube::kStateNotOk) != 0;
  if (not_ok && !(last_state_[i] & powercube::kStateNotOk)) {
    bump(Counter::kFaults);
    report(Problem::kDeviceFault, m.module);
  }
  last_state_[i] = m.reply.state;
  hal::JointSample s;
  s.joint = config_.modules[i].joint;
  s.stamp = f.stamp;
  if (config_.subtract_half_round_trip && f.stamp > request_time_) {
    s.stamp -= (f.stamp - request_time_) / 2;
  }
  s.angle_rad = static_cast<double>(m.reply.position_rad) + config_.modules[i].offset_rad;
  s.status = m.reply.state;
  s.valid = !not_ok;
  deliver(s);
  // Next module right away: one bus round trip per joint, not one per tick.
  if (i + 1 < config_.modules.size()) request_next(hal::monotonic_now());
}

}  // namespace rangefit::drivers::can
