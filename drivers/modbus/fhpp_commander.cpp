#include "drivers/modbus/fhpp_commander.hpp"

#include <cmath>
#include <string>

namespace rangefit::drivers::fhpp {

void Commander::observe(const InputTelegram& in) {
  last_ = in;
  const bool ack = in.spos & kSposAck;
  switch (edge_) {
    case Edge::kWaitAckLow:
      if (!ack) edge_ = Edge::kRaised;  // raised in the next telegram
      break;
    case Edge::kRaised:
      if (ack) {
        edge_ = Edge::kWaitAckDrop;
        if (pending_ == Pending::kEdge) accepted_id_ = pending_id_, pending_ = Pending::kNone;
      }
      break;
    case Edge::kWaitAckDrop:
      if (!ack) edge_ = Edge::kIdle;
      break;
    case Edge::kIdle:
      break;
  }
  if (in.scon & kSconFault) {
    // A fault aborts any handshake in flight; the request that raised it is not accepted.
    if (pending_ == Pending::kEdge) pending_ = Pending::kNone;
    edge_ = Edge::kIdle;
  }
  if (pending_ == Pending::kEnable && (in.scon & kSconEnabled) && (in.scon & kSconOpen)) {
    accepted_id_ = pending_id_, pending_ = Pending::kNone;
  }
  if (pending_ == Pending::kHalt && !(in.spos & kSposHalt)) {
    accepted_id_ = pending_id_, pending_ = Pending::kNone;
  }
  if (pending_ == Pending::kReset && !(in.scon & kSconFault)) {
    accepted_id_ = pending_id_, pending_ = Pending::kNone;
  }
}

void Commander::forget() {
  last_.reset();
  edge_ = Edge::kIdle;
  reset_cycles_ = 0;
  pending_ = Pending::kNone;
}

OutputTelegram Commander::next_output() {
  OutputTelegram out;
  out.ccon = kCconModeDirect;
  if (enable_) out.ccon |= kCconEnable | kCconStop;
  if (reset_cycles_ > 0) {
    out.ccon |= kCconReset;
    --reset_cycles_;
  }
  out.cpos = halt_ ? 0 : kCposHalt;
  if (edge_ == Edge::kRaised) out.cpos |= edge_bit_;
  out.velocity_pct = velocity_pct_;
  out.position_inc = target_inc_;
  return out;
}

hal::Status Commander::refuse_if_unusable(const char* what) const {
  if (!last_)
    return hal::Status::Error(std::string(what) + " refused: no status from the drive yet");
  const std::string status = describe_status(last_->scon, last_->spos);
  if (last_->scon & kSconFault) {
    return hal::Status::Error(std::string(what) + " refused: drive in FAULT (reset it first); " +
                              status);
  }
  if (last_->scon & kSconFctMmi) {
    return hal::Status::Error(std::string(what) +
                              " refused: another master (FCT/MMI or another client) controls the "
                              "drive; " +
                              status);
  }
  return hal::Status::Ok();
}

hal::Status Commander::request_enable(Ticket& t) {
  if (auto s = refuse_if_unusable("enable"); !s) return s;
  enable_ = true;
  halt_ = false;
  pending_id_ = issue(t);
  pending_ = Pending::kEnable;
  if ((last_->scon & kSconEnabled) && (last_->scon & kSconOpen)) observe(*last_);
  return hal::Status::Ok();
}

void Commander::request_disable() {
  enable_ = false;
  edge_ = Edge::kIdle;
}

hal::Status Commander::request_home(Ticket& t) {
  if (auto s = refuse_if_unusable("home"); !s) return s;
  if (!(last_->scon & kSconOpen)) {
    return hal::Status::Error("home refused: drive not enabled; " +
                              describe_status(last_->scon, last_->spos));
  }
  halt_ = false;
  edge_bit_ = kCposHome;
  edge_ = (last_->spos & kSposAck) ? Edge::kWaitAckLow : Edge::kRaised;
  pending_id_ = issue(t);
  pending_ = Pending::kEdge;
  return hal::Status::Ok();
}

hal::Status Commander::request_move(double position_mm, double speed_mm_s, double min_mm,
                                    double max_mm, Ticket& t) {
  if (auto s = refuse_if_unusable("move"); !s) return s;
  const std::string status = describe_status(last_->scon, last_->spos);
  if (!std::isfinite(position_mm) || position_mm < min_mm || position_mm > max_mm) {
    return hal::Status::Error("move refused: target " + std::to_string(position_mm) +
                              " mm outside travel [" + std::to_string(min_mm) + ", " +
                              std::to_string(max_mm) + "] mm");
  }
  if (!(speed_mm_s > 0.0) || !std::isfinite(speed_mm_s)) {
    return hal::Status::Error("move refused: speed must be positive (mm/s)");
  }
  if (!(last_->scon & kSconOpen))
    return hal::Status::Error("move refused: drive not enabled; " + status);
  if (!(last_->spos & kSposReferenced)) {
    return hal::Status::Error("move refused: axis not referenced (home first); " + status);
  }
  halt_ = false;
  target_inc_ = scale_.to_increments(position_mm);
  velocity_pct_ = scale_.mm_s_to_pct(speed_mm_s);
  edge_bit_ = kCposStart;
  edge_ = (last_->spos & kSposAck) ? Edge::kWaitAckLow : Edge::kRaised;
  pending_id_ = issue(t);
  pending_ = Pending::kEdge;
  return hal::Status::Ok();
}

hal::Status Commander::request_halt(Ticket& t) {
  if (!last_) return hal::Status::Error("halt refused: no status from the drive yet");
  halt_ = true;  // allowed in any state: stopping is always safe
  if (pending_ == Pending::kEdge) pending_ = Pending::kNone;
  edge_ = Edge::kIdle;
  pending_id_ = issue(t);
  pending_ = Pending::kHalt;
  return hal::Status::Ok();
}

hal::Status Commander::request_reset(Ticket& t) {
  if (!last_) return hal::Status::Error("reset refused: no status from the drive yet");
  reset_cycles_ = kResetCycles;
  edge_ = Edge::kIdle;
  pending_id_ = issue(t);
  pending_ = Pending::kReset;
  if (!(last_->scon & kSconFault)) accepted_id_ = pending_id_, pending_ = Pending::kNone;
  return hal::Status::Ok();
}

bool Commander::motion_complete() const {
  if (!last_ || edge_ == Edge::kRaised || edge_ == Edge::kWaitAckLow) return false;
  if (pending_ == Pending::kEdge) return false;
  return (last_->spos & kSposMotionComplete) && !(last_->spos & kSposMoving);
}

}  // namespace rangefit::drivers::fhpp
