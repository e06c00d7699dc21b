#include "drivers/modbus/fhpp_axis.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace rangefit::drivers {
namespace {

using std::chrono::duration_cast;
using std::chrono::milliseconds;

long long to_ms(hal::Duration d) { return duration_cast<milliseconds>(d).count(); }

}  // namespace

FhppAxis::FhppAxis(FhppAxisConfig config, hal::Clock* clock)
    : config_(std::move(config)),
      own_clock_(clock ? nullptr : std::make_unique<hal::MonotonicClock>()),
      clock_(clock ? clock : own_clock_.get()),
      link_(config_.link, *clock_),
      queue_(config_.queue_capacity),
      commander_(config_.scale) {}

FhppAxis::~FhppAxis() { stop(); }

hal::Status FhppAxis::start() {
  if (running_) return hal::Status::Ok();
  const auto& c = config_;
  if (c.poll_period <= hal::Duration::zero() || c.poll_period * 2 > c.drive_comm_timeout) {
    return hal::Status::Error("poll period " + std::to_string(to_ms(c.poll_period)) +
                              " ms must be positive and below half the drive's connection "
                              "timeout (" +
                              std::to_string(to_ms(c.drive_comm_timeout)) + " ms)");
  }
  if (c.link.response_timeout <= hal::Duration::zero() ||
      c.backoff_initial <= hal::Duration::zero()) {
    return hal::Status::Error("response timeout and back-off must be positive");
  }
  if (!(c.scale.increments_per_mm > 0.0) || !(c.scale.max_speed_mm_s > 0.0) ||
      !(c.travel.min_mm < c.travel.max_mm)) {
    return hal::Status::Error("axis scale (increments per mm, max speed) and travel must be valid");
  }
  {
    std::lock_guard lock(mutex_);
    health_.state = hal::DeviceState::kConnecting;
  }
  running_ = true;
  thread_ = std::thread([this] { run(); });
  return hal::Status::Ok();
}

void FhppAxis::stop() {
  if (!running_.exchange(false)) return;
  if (thread_.joinable()) thread_.join();
  std::lock_guard lock(mutex_);
  connected_ = false;
  commander_.forget();
  health_.state = hal::DeviceState::kDisconnected;
  cv_.notify_all();
}

void FhppAxis::run() {
  hal::Timestamp next = clock_->now();
  while (running_) {
    cycle();
    // Absolute-time schedule: the period does not drift with the exchange time. After an overrun
    // (a timeout, a reconnect) the missed slots are skipped and counted instead of burst-polled.
    next += config_.poll_period;
    const hal::Timestamp now = clock_->now();
    if (next < now) {
      std::lock_guard lock(mutex_);
      health_.counters.gaps += static_cast<std::uint64_t>((now - next) / config_.poll_period) + 1;
      next = now;
    }
    clock_->sleep_until(next);
  }
  link_.close();
}

void FhppAxis::schedule_retry(hal::Timestamp now) {
  // First failure: retry at once (a single lost reply is common); then capped exponential.
  ++failures_;
  hal::Duration delay{0};
  if (failures_ > 1) {
    delay = config_.backoff_initial;
    for (int i = 2; i < failures_ && delay < config_.backoff_max; ++i) delay *= 2;
    delay = std::min(delay, config_.backoff_max);
  }
  retry_at_ = now + delay;
}

void FhppAxis::cycle() {
  // A connection lost mid-request (reset, closed) fails at once: retry within the same slot, so a
  // reset costs one reconnect rather than a period. Timeouts have used up their slot already.
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (clock_->now() < retry_at_) return;
    if (!link_.is_open()) {
      const LinkResult r = link_.open();
      std::lock_guard lock(mutex_);
      ++stats_.connect_attempts;
      if (!r.ok()) {
        report(hal::DeviceState::kDisconnected, r.message + " (retrying with back-off)");
        schedule_retry(clock_->now());
        return;
      }
      if (ever_connected_) ++health_.counters.reconnects;
      ever_connected_ = true;
      connected_ = true;
      spdlog::info("{}: connected to {}", config_.name, link_.endpoint());
    }
    fhpp::OutputTelegram out;
    {
      std::lock_guard lock(mutex_);
      out = commander_.next_output();
    }
    fhpp::Registers in{};
    const LinkResult r = link_.exchange(fhpp::encode(out, config_.byte_order), in);
    if (r.ok()) return on_reply(r, *fhpp::decode_input(in, config_.byte_order));
    on_link_error(r);
    if (r.error != LinkError::kConnectionLost) return;
  }
}

void FhppAxis::on_link_error(const LinkResult& r) {
  std::lock_guard lock(mutex_);
  commander_.forget();  // the drive's status is unknown until the next good reply
  cv_.notify_all();
  if (r.error == LinkError::kException) {
    ++stats_.exceptions;
    // Busy/acknowledge: the device is fine, ask again next period.
    if (r.exception_code == 5 || r.exception_code == 6) {
      report(health_.state, r.message + ": drive busy, retrying next period");
      return;
    }
    // Anything else means our request is wrong for this device: reconnecting cannot help.
    if (!config_error_) ++health_.counters.faults;
    config_error_ = true;
    report(hal::DeviceState::kFault, "configuration error: " + r.message +
                                         " (check unit id, register address and function codes;"
                                         " not reconnecting)");
    schedule_retry(clock_->now());
    return;
  }
  if (r.error == LinkError::kTimeout) ++health_.counters.timeouts;
  if (r.error == LinkError::kBadReply) ++stats_.bad_replies;
  // Close so that a reply still on its way dies with this socket and cannot be taken for the
  // answer to a later request.
  link_.close();
  connected_ = false;
  report(hal::DeviceState::kDisconnected, r.message + "; reconnecting");
  schedule_retry(clock_->now());
}

void FhppAxis::on_reply(const LinkResult& r, const fhpp::InputTelegram& in) {
  const hal::Duration round_trip = r.reply - r.request;
  hal::AxisSample s;
  s.stamp = r.request + round_trip / 2;
  s.uncertainty = round_trip;
  s.position_mm = config_.scale.to_mm(in.position_inc);
  s.velocity_mm_s = config_.scale.pct_to_mm_s(in.velocity_pct);
  s.scon = in.scon;
  s.spos = in.spos;

  std::unique_lock lock(mutex_);
  failures_ = 0;
  ++stats_.exchanges;
  stats_.fell_back_to_03_10 = link_.fell_back();
  const std::string implausible = check_position(config_.travel, s.position_mm, s.stamp, previous_);
  if (previous_ && s.position_mm < previous_->position_mm) s.velocity_mm_s = -s.velocity_mm_s;
  previous_ = PositionReference{s.position_mm, s.stamp};
  s.valid = implausible.empty() && round_trip <= config_.max_round_trip;
  if (round_trip > config_.max_round_trip) ++stats_.late_round_trips;
  if (!implausible.empty()) ++stats_.implausible;
  const hal::Duration silent = last_ok_ ? r.request - *last_ok_ : hal::Duration::zero();
  last_ok_ = r.reply;
  config_error_ = false;
  commander_.observe(in);

  std::string problem;
  hal::DeviceState state = hal::DeviceState::kStreaming;
  if (in.scon & fhpp::kSconFault) {
    state = hal::DeviceState::kFault;
    if (!in_fault_) {
      ++health_.counters.faults;
      // The telegram carries no fault number; a FAULT seen after a silence longer than the drive's
      // connection timeout is that timeout (47h/48h), and polling again has removed its cause.
      comm_fault_ = silent > config_.drive_comm_timeout;
      if (comm_fault_) ++stats_.comm_timeout_faults;
      if (comm_fault_ && config_.auto_reset_comm_fault) {
        fhpp::Commander::Ticket t;
        (void)commander_.request_reset(t);
      }
    }
    in_fault_ = true;
    problem = comm_fault_
                  ? "drive FAULT: connection timeout after " + std::to_string(to_ms(silent)) +
                        " ms without a request (drive timeout " +
                        std::to_string(to_ms(config_.drive_comm_timeout)) + " ms)"
                  : "drive FAULT";
    problem += "; " + fhpp::describe_status(in.scon, in.spos);
  } else {
    in_fault_ = false;
    comm_fault_ = false;
    if (in.scon & fhpp::kSconFctMmi) {
      state = hal::DeviceState::kFault;
      if (!taken_over_) ++stats_.takeovers;
      taken_over_ = true;
      problem =
          "another master (FCT/MMI or another Modbus client) has taken control of the "
          "drive; commands refused until it releases it; " +
          fhpp::describe_status(in.scon, in.spos);
    } else {
      taken_over_ = false;
      if (!implausible.empty()) problem = implausible;
    }
  }
  report(state, problem);
  latest_ = s;
  ++health_.counters.samples;
  lock.unlock();
  cv_.notify_all();
  queue_.push(s);
}

void FhppAxis::report(hal::DeviceState state, const std::string& message) {
  if (state != health_.state && state == hal::DeviceState::kStreaming) {
    spdlog::info("{}: streaming", config_.name);
  }
  health_.state = state;
  if (message == health_.message) return;
  health_.message = message;
  if (message.empty()) return;
  spdlog::warn("{}: {}", config_.name, message);
  events_.push_back(message);
  if (events_.size() > kMaxEvents) events_.pop_front();
}

hal::DeviceHealth FhppAxis::health() const {
  std::lock_guard lock(mutex_);
  hal::DeviceHealth h = health_;
  h.counters.dropped = queue_.dropped();
  return h;
}

std::size_t FhppAxis::read(std::vector<hal::AxisSample>& out, hal::Duration timeout) {
  return queue_.drain(out, timeout);
}

FhppAxisStats FhppAxis::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

std::vector<std::string> FhppAxis::events() const {
  std::lock_guard lock(mutex_);
  return {events_.begin(), events_.end()};
}

std::optional<hal::AxisSample> FhppAxis::latest() const {
  std::lock_guard lock(mutex_);
  return latest_;
}

}  // namespace rangefit::drivers
