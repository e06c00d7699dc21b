#include "drivers/can/cia402_joint_source.hpp"

#include <algorithm>

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

void Cia402JointSource::start_node(std::uint8_t node) {
  if (!config_.start_nodes) return;
  if (config_.heartbeat_producer_ms > 0) {
    send(encode_sdo_download(node, 0x1017, 0, config_.heartbeat_producer_ms, 2));
  }
  send(encode_nmt(kNmtStart, node));
}

void Cia402JointSource::on_link(bool up) {
  if (!up) {
    report(Problem::kLinkDown);
    return;
  }
  const hal::Timestamp now = hal::monotonic_now();
  for (auto& n : nodes_) {
    n->last_heartbeat = now;  // fresh grace period after (re)opening
    start_node(n->config.node);
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
        start_node(n->config.node);
      }
      break;
    case Kind::kEmcy:
      if (m.emcy_code != 0) {
        bump(Counter::kFaults);
        report(Problem::kEmcy, n->config.node);
      }
      break;
    case Kind::kSdoResponse:
      if (m.sdo_command == kSdoAbort) bump(Counter::kFaults);
      break;
    default:
      bump(Counter::kUnknownIds);
      break;
  }
}

}  // namespace rangefit::drivers::can
