#include "drivers/can/powercube_joint_source.hpp"

#include <spdlog/spdlog.h>

namespace rangefit::drivers::can {

FrameFilter powercube_filter(const PowerCubeConfig& config) {
  FrameFilter f;
  for (const auto& m : config.modules) f.ids.push_back(powercube::reply_id(m.module));
  return f;
}

PowerCubeJointSource::PowerCubeJointSource(PowerCubeConfig config,
                                           std::unique_ptr<CanTransport> transport)
    : config_(std::move(config)),
      transport_(std::move(transport)),
      ring_(config_.queue_capacity),
      loop_(*transport_, *this, counters_, config_.loop),
      misses_(config_.modules.size(), 0),
      last_state_(config_.modules.size(), 0) {}

PowerCubeJointSource::~PowerCubeJointSource() { stop(); }

hal::Status PowerCubeJointSource::start() {
  if (started_) return hal::Status::Ok();
  if (config_.modules.empty()) return hal::Status::Error(config_.name + ": no modules configured");
  const hal::Status open = transport_->reopen();
  if (!open) spdlog::warn("{}: {} (retrying)", config_.name, open.message);
  current_ = config_.modules.size() - 1;  // the first poll goes to module 0
  round_start_ = hal::monotonic_now();
  loop_.start(open.ok);
  started_ = true;
  return hal::Status::Ok();
}

void PowerCubeJointSource::stop() {
  if (!started_) return;
  loop_.stop();
  started_ = false;
}

std::size_t PowerCubeJointSource::read(std::vector<hal::JointSample>& out, hal::Duration timeout) {
  return ring_.drain(out, timeout);
}

CanCounters PowerCubeJointSource::counters() const {
  CanCounters c = counters_.snapshot(transport_->counters());
  c.values[static_cast<std::size_t>(Counter::kRingDropped)] += ring_.dropped();
  return c;
}

hal::DeviceHealth PowerCubeJointSource::health() const {
  hal::DeviceHealth h;
  h.counters = counters().stream();
  if (!started_)
    h.state = hal::DeviceState::kReady;
  else if (!loop_.link_up())
    h.state = hal::DeviceState::kDisconnected;
  else if (loop_.bus_off() || lost_modules_ > 0)
    h.state = hal::DeviceState::kFault;
  else
    h.state = hal::DeviceState::kStreaming;
  h.message = to_string(problem_.load());
  return h;
}

void PowerCubeJointSource::on_link(bool up) {
  if (!up) problem_ = Problem::kLinkDown;
  outstanding_ = false;
}

void PowerCubeJointSource::request_next(hal::Timestamp now) {
  current_ = (current_ + 1) % config_.modules.size();
  if (current_ == 0) round_start_ = now;
  const TxResult r =
      transport_->send(powercube::encode_position_request(config_.modules[current_].module));
  if (r != TxResult::kOk) {
    if (r == TxResult::kBufferFull) counters_.bump(Counter::kTxBufferFull);
    return;
  }
  outstanding_ = true;
  request_time_ = now;
}

hal::Timestamp PowerCubeJointSource::on_tick(hal::Timestamp now) {
  if (outstanding_) {
    if (now - request_time_ < config_.reply_timeout) return request_time_ + config_.reply_timeout;
    outstanding_ = false;
    counters_.bump(Counter::kTimeouts);
    problem_ = Problem::kTimeout;
    if (++misses_[current_] == config_.misses_until_lost) {
      counters_.bump(Counter::kNodesLost);
      ++lost_modules_;
      problem_ = Problem::kNodeLost;
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
    counters_.bump(Counter::kBadLengths);
    return;
  }
  if (m.kind != powercube::Kind::kPositionReply) {
    counters_.bump(Counter::kUnknownIds);
    return;
  }
  const std::size_t i = current_;
  if (!outstanding_ || config_.modules[i].module != m.module) {
    counters_.bump(Counter::kDuplicates);  // late reply after its timeout, or unsolicited
    return;
  }
  outstanding_ = false;
  if (misses_[i] >= config_.misses_until_lost) --lost_modules_;
  misses_[i] = 0;
  const bool not_ok = (m.reply.state & powercube::kStateNotOk) != 0;
  if (not_ok && !(last_state_[i] & powercube::kStateNotOk)) {
    counters_.bump(Counter::kFaults);
    problem_ = Problem::kDeviceFault;
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
  if (ring_.push(s)) counters_.bump(Counter::kSamples);
  // Next module right away: one bus round trip per joint, not one per tick.
  if (i + 1 < config_.modules.size()) request_next(hal::monotonic_now());
}

}  // namespace rangefit::drivers::can
