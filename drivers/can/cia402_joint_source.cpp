#include "drivers/can/cia402_joint_source.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace rangefit::drivers::can {

using namespace cia402;  // NOLINT: codec names read better unqualified here

FrameFilter cia402_filter(const Cia402Config& config) {
  FrameFilter f;
  f.ids.push_back(kSyncId);
  for (const auto& j : config.joints) {
    for (std::uint32_t id : {emcy_id(j.node), tpdo1_id(j.node), tpdo2_id(j.node),
                             sdo_response_id(j.node), heartbeat_id(j.node)}) {
      f.ids.push_back(id);
    }
  }
  f.own_frames = config.sync_master;
  return f;
}

Cia402JointSource::Cia402JointSource(Cia402Config config, std::unique_ptr<CanTransport> transport)
    : CanSource(config.name, std::move(transport), config.queue_capacity, config.loop),
      config_(std::move(config)) {
  for (const auto& j : config_.joints) {
    nodes_.push_back(std::make_unique<Node>());
    nodes_.back()->config = j;
  }
}

hal::Status Cia402JointSource::check_config() const {
  if (nodes_.empty()) return hal::Status::Error(config_.name + ": no joints configured");
  return hal::Status::Ok();
}

void Cia402JointSource::on_start(hal::Timestamp now) {
  for (auto& n : nodes_) n->last_heartbeat = now;
  next_sync_ = now;
}

std::uint8_t Cia402JointSource::node_state(std::uint8_t node) const {
  for (const auto& n : nodes_) {
    if (n->config.node == node) return n->nmt_state.load();
  }
  return 0xFF;
}

Cia402JointSource::Identity Cia402JointSource::identity(std::uint8_t node) const {
  for (const auto& n : nodes_) {
    if (n->config.node == node) return n->identity.load();
  }
  return Identity::kUnknown;
}

// At open and after a boot-up: the node may be another device now (swapped while off or while
// the link was down), so its serial is asked again and reported only once it answered.
void Cia402JointSource::start_node(Node& n, hal::Timestamp now) {
  n.identity = Identity::kUnknown;
  // The node's default SDO channel belongs to the master that manages it: a driver that leaves
  // the nodes to another master (start_nodes = false) does not talk on it.
  n.identity_wanted = config_.read_identity && config_.start_nodes;
  n.sdo = SdoPending::kNone;  // a transfer in progress died with the node's (or our) reset
  if (config_.start_nodes) {
    if (config_.heartbeat_producer_ms > 0 &&
        send(encode_sdo_download(n.config.node, 0x1017, 0, config_.heartbeat_producer_ms, 2)) ==
            TxResult::kOk) {
      n.sdo = SdoPending::kHeartbeat;
      n.sdo_sent = now;
    }
    send(encode_nmt(kNmtStart, n.config.node));
  }
  if (n.sdo == SdoPending::kNone && n.identity_wanted) ask_identity(n, now);
}

void Cia402JointSource::ask_identity(Node& n, hal::Timestamp now) {
  // Not sent (tx queue full, link down): asked again from the next tick.
  if (send(encode_sdo_upload_request(n.config.node, 0x1018, 4)) != TxResult::kOk) return;
  n.identity_wanted = false;
  n.sdo = SdoPending::kIdentity;
  n.sdo_sent = now;
}

// Frees the node's SDO channel when its transfer found no answer in time (the node then has no
// serial to report) and starts the next transfer that waits for the channel.
void Cia402JointSource::expire_sdo(Node& n, hal::Timestamp now) {
  if (n.sdo != SdoPending::kNone && now - n.sdo_sent > config_.sdo_timeout) {
    if (n.sdo == SdoPending::kIdentity && n.identity != Identity::kKnown) {
      n.identity = Identity::kNoAnswer;
    }
    n.sdo = SdoPending::kNone;
  }
  if (n.sdo == SdoPending::kNone && n.identity_wanted) ask_identity(n, now);
}

void Cia402JointSource::take_sdo_response(Node& n, const Message& m) {
  const bool identity_reply = m.sdo_index == 0x1018 && m.sdo_subindex == 4;
  if (identity_reply && sdo_is_upload_reply(m.sdo_command)) {
    if ((m.sdo_command & 0x02) != 0) {  // expedited: the value is in the frame
      // Size indicated (bit 0): 4 - n data bytes, n = bits 2-3; the rest is not data.
      const unsigned unused = (m.sdo_command & 0x01) != 0 ? (m.sdo_command >> 2) & 0x03 : 0;
      n.serial = unused == 0 ? m.sdo_data : m.sdo_data & ((1u << (8 * (4 - unused))) - 1);
      n.identity = Identity::kKnown;
    } else {
      n.abort_code = 0;  // a segmented upload of a U32: not a serial this driver reads
      n.identity = Identity::kAborted;
    }
  } else if (identity_reply && m.sdo_command == kSdoAbort) {
    // Sub-index 4 is optional (CiA 301 7.5.2.27): no serial, not a fault.
    n.abort_code = m.sdo_data;
    n.identity = Identity::kAborted;
  } else if (m.sdo_command == kSdoAbort) {
    bump(Counter::kFaults);
  }
  const bool ends_transfer = (n.sdo == SdoPending::kIdentity && identity_reply) ||
                             (n.sdo == SdoPending::kHeartbeat && m.sdo_index == 0x1017);
  if (ends_transfer) {
    n.sdo = SdoPending::kNone;
    if (n.identity_wanted) ask_identity(n, hal::monotonic_now());
  }
}

// One node: its serial in decimal (as CANopen tools print 0x1018:04). Several nodes (pan-tilt):
// "node:serial" of each node that told it, space separated. A node that gave none is logged
// once here, on the caller's thread (the receive path never logs).
std::string Cia402JointSource::hardware_id() const {
  std::string id;
  const bool several = nodes_.size() > 1;
  for (const auto& n : nodes_) {
    const Identity state = n->identity.load();
    if (state == Identity::kKnown) {
      if (!id.empty()) id += ' ';
      if (several) id += std::to_string(n->config.node) + ':';
      id += std::to_string(n->serial.load());
    } else if (state != Identity::kUnknown && !n->miss_logged.exchange(true)) {
      spdlog::warn("{}: node {} gave no serial number (0x1018:04 {}); diagnostics name it '{}'",
                   config_.name, n->config.node,
                   state == Identity::kAborted
                       ? fmt::format("refused, SDO abort 0x{:08X}", n->abort_code.load())
                       : fmt::format("not answered within {} ms",
                                     std::chrono::duration_cast<std::chrono::milliseconds>(
                                         config_.sdo_timeout)
                                         .count()),
                   config_.name);
    }
  }
  return id;
}

void Cia402JointSource::on_link(bool up) {
  if (!up) {
    report(Problem::kLinkDown);
    return;
  }
  const hal::Timestamp now = hal::monotonic_now();
  for (auto& n : nodes_) {
    n->last_heartbeat = now;  // fresh grace period after (re)opening
    start_node(*n, now);
  }
  pending_echo_ = false;
}

Cia402JointSource::Node* Cia402JointSource::find(std::uint8_t node) {
  for (auto& n : nodes_) {
    if (n->config.node == node) return n.get();
  }
  return nullptr;
}

hal::Timestamp Cia402JointSource::on_tick(hal::Timestamp now) {
  bool lost = false;
  for (auto& n : nodes_) {
    if (n->alive && now - n->last_heartbeat > config_.heartbeat_timeout) {
      n->alive = false;
      bump(Counter::kNodesLost);
      report(Problem::kNodeLost, n->config.node);
    }
    lost = lost || !n->alive;
    expire_sdo(*n, now);
  }
  any_node_lost_ = lost;
  hal::Timestamp next = now + std::chrono::milliseconds(10);
  if (!config_.sync_master) return next;
  if (now >= next_sync_) {
    const std::uint8_t counter =
        config_.sync_overflow == 0 ? 0 : next_sync_counter(sync_counter_, config_.sync_overflow);
    if (send(encode_sync(counter)) == TxResult::kOk) {
      sync_counter_ = counter;
      pending_counter_ = counter;
      pending_echo_ = true;
    }
    // Fell behind: skip the missed slots but keep the grid. Restarting the grid at `now` made a
    // timer that fires on scheduler ticks (a loaded or tickless-less VM) lose every other SYNC.
    next_sync_ += config_.sync_period;
    if (next_sync_ <= now) {
      next_sync_ += ((now - next_sync_) / config_.sync_period + 1) * config_.sync_period;
    }
  }
  return std::min(next, next_sync_);
}

void Cia402JointSource::begin_cycle(hal::Timestamp stamp) {
  if (cycle_ > 0) {
    for (auto& n : nodes_) {
      if (n->alive && n->answered_cycle != cycle_) bump(Counter::kGaps);
    }
  }
  ++cycle_;
  cycle_stamp_ = stamp;
}

void Cia402JointSource::take_sync(const CanFrame& f, const Message& m) {
  if (f.flags & kFrameEcho) {
    if (pending_echo_ && m.sync_counter == pending_counter_) {
      pending_echo_ = false;
      begin_cycle(f.stamp);
    }
    return;
  }
  if (config_.sync_master) {  // a second SYNC producer on the bus
    bump(Counter::kDuplicates);
    return;
  }
  const std::uint8_t ovf = config_.sync_overflow;
  if (ovf != 0 && cycle_ > 0 && m.sync_counter != 0) {
    if (m.sync_counter == sync_counter_) {
      bump(Counter::kDuplicates);
      return;
    }
    const int expected = next_sync_counter(sync_counter_, ovf);
    const int ahead = (m.sync_counter - expected + ovf) % ovf;
    if (ahead > ovf / 2) {
      bump(Counter::kReordered);
      return;
    }
    if (ahead > 0) bump(Counter::kGaps, static_cast<std::uint64_t>(ahead));
  }
  sync_counter_ = m.sync_counter;
  begin_cycle(f.stamp);
}

void Cia402JointSource::take_tpdo1(Node& n, const Message& m) {
  if (cycle_ == 0) return;  // no SYNC seen yet: nothing to stamp it with
  if (n.answered_cycle == cycle_) {
    bump(Counter::kDuplicates);
    return;
  }
  n.answered_cycle = cycle_;
  const bool fault = (m.statusword & kStatusFault) != 0;
  if (fault) bump(Counter::kFaults);
  hal::JointSample s;
  s.joint = n.config.joint;
  s.stamp = cycle_stamp_;
  s.angle_rad = m.position * n.config.rad_per_increment + n.config.offset_rad;
  s.velocity_rad_s = n.velocity * n.config.rad_per_increment;
  s.status = m.statusword;
  s.valid = !fault;
  deliver(s);
}

void Cia402JointSource::on_frame(const CanFrame& f) {
  const Message m = decode(f);
  Node* n = (m.kind == Kind::kSync || m.kind == Kind::kNmt) ? nullptr : find(m.node);
  switch (m.kind) {
    case Kind::kSync:
      take_sync(f, m);
      return;
    case Kind::kBadLength:
      bump(Counter::kBadLengths);
      return;
    case Kind::kNmt:
    case Kind::kTime:
    case Kind::kSdoRequest:
      return;  // other masters' traffic
    default:
      break;
  }
  if (n == nullptr) {
    bump(Counter::kUnknownIds);
    return;
  }
  switch (m.kind) {
    case Kind::kTpdo1:
      take_tpdo1(*n, m);
      break;
    case Kind::kTpdo2:
      n->velocity = m.velocity;
      break;
    case Kind::kHeartbeat:
      n->last_heartbeat = f.stamp;
      n->alive = true;
      n->nmt_state = m.nmt_state;
      if (m.nmt_state == kBootUp) {
        bump(Counter::kReboots);
        report(Problem::kNodeReboot, n->config.node);
        start_node(*n, hal::monotonic_now());
      }
      break;
    case Kind::kEmcy:
      if (m.emcy_code != 0) {
        bump(Counter::kFaults);
        report(Problem::kEmcy, n->config.node);
      }
      break;
    case Kind::kSdoResponse:
      take_sdo_response(*n, m);
      break;
    default:
      bump(Counter::kUnknownIds);
      break;
  }
}

}  // namespace rangefit::drivers::can
