#include "test/support/can_cia402_node.hpp"

#include <cmath>

namespace rangefit::sim {

using namespace drivers::can::cia402;  // NOLINT: codec names read better unqualified here
using drivers::can::CanFrame;
using drivers::can::CanTransport;

SimCia402Node::SimCia402Node(SimCia402Config config, std::function<double(hal::Timestamp)> angle)
    : config_(config),
      angle_(std::move(angle)),
      heartbeat_ms_(config.heartbeat_ms),
      serial_(config.serial != 0 ? config.serial : 402000u + config.node) {}

void SimCia402Node::boot(CanTransport& bus) {
  state_ = kBootUp;
  (void)bus.send(encode_heartbeat(config_.node, kBootUp));
  state_ = kPreOperational;  // CiA 301: pre-operational right after the boot-up message
}

hal::Timestamp SimCia402Node::tick(hal::Timestamp now, CanTransport& bus) {
  if (silent_) return now + std::chrono::milliseconds(10);
  if (reboot_.exchange(false)) {
    boot(bus);
    next_heartbeat_ = now + std::chrono::milliseconds(heartbeat_ms_.load());
  }
  if (const std::uint16_t code = emcy_code_.exchange(0)) {
    (void)bus.send(encode_emcy(config_.node, code, 0x01));
  }
  if (reschedule_heartbeat_.exchange(false)) next_heartbeat_ = now;
  const std::uint16_t period = heartbeat_ms_;
  if (period > 0 && now >= next_heartbeat_) {
    (void)bus.send(encode_heartbeat(config_.node, static_cast<NmtState>(state_.load())));
    next_heartbeat_ = now + std::chrono::milliseconds(period);
  }
  return std::min(now + std::chrono::milliseconds(10), next_heartbeat_);
}

void SimCia402Node::answer_sync(hal::Timestamp stamp, CanTransport& bus) {
  if (drop_tpdos_ > 0) {
    --drop_tpdos_;
    return;
  }
  const double angle = angle_ ? angle_(stamp) : angle_value_.load();
  const auto inc = static_cast<std::int32_t>(
      std::lround((angle - config_.offset_rad) / config_.rad_per_increment));
  std::uint16_t sw = config_.statusword;
  if (fault_) sw = static_cast<std::uint16_t>(sw | kStatusFault);
  CanFrame f = encode_tpdo1(config_.node, sw, inc);
  if (short_tpdo_.exchange(false)) f.len = 4;
  (void)bus.send(f);
  if (duplicate_tpdo_.exchange(false)) (void)bus.send(f);
  if (config_.tpdo2) (void)bus.send(encode_tpdo2(config_.node, 0));
  ++answered_;
}

void SimCia402Node::answer_sdo(const Message& m, CanTransport& bus) {
  if (sdo_is_download_request(m.sdo_command)) {
    if (m.sdo_index == 0x1017 && m.sdo_subindex == 0) {
      heartbeat_ms_ = static_cast<std::uint16_t>(m.sdo_data);
      reschedule_heartbeat_ = true;  // the new period applies from now, as on a real drive
      (void)bus.send(encode_sdo_download_ok(config_.node, m.sdo_index, m.sdo_subindex));
    } else {
      (void)bus.send(encode_sdo_abort(config_.node, m.sdo_index, m.sdo_subindex, 0x06020000));
    }
  } else if (m.sdo_command == kSdoUploadRequest) {
    if (m.sdo_index == 0x1018 && m.sdo_subindex == 4) {
      ++identity_requests_;
      if (config_.identity == SimIdentityReply::kSerial) {
        (void)bus.send(encode_sdo_upload_reply(config_.node, 0x1018, 4, serial_));
      } else if (config_.identity == SimIdentityReply::kAbort) {
        // 0x06090011: sub-index does not exist (CiA 301 abort codes).
        (void)bus.send(encode_sdo_abort(config_.node, 0x1018, 4, 0x06090011));
      }
    } else if (m.sdo_index == 0x1017) {
      (void)bus.send(encode_sdo_upload_reply(config_.node, 0x1017, 0, heartbeat_ms_));
    } else {
      (void)bus.send(encode_sdo_abort(config_.node, m.sdo_index, m.sdo_subindex, 0x06020000));
    }
  }
}

void SimCia402Node::on_frame(const CanFrame& f, CanTransport& bus) {
  if (silent_) return;
  const Message m = decode(f);
  switch (m.kind) {
    case Kind::kNmt:
      if (m.node != 0 && m.node != config_.node) return;
      if (m.nmt_command == kNmtStart)
        state_ = kOperational;
      else if (m.nmt_command == kNmtStop)
        state_ = kStopped;
      else if (m.nmt_command == kNmtPreOperational)
        state_ = kPreOperational;
      else if (m.nmt_command == kNmtResetNode || m.nmt_command == kNmtResetCommunication)
        boot(bus);
      break;
    case Kind::kSync:
      if (state_ == kOperational) answer_sync(f.stamp, bus);
      break;
    case Kind::kSdoRequest:
      if (m.node == config_.node && state_ != kStopped) answer_sdo(m, bus);
      break;
    default:
      break;
  }
}

}  // namespace rangefit::sim
