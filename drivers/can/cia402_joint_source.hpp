#pragma once
// Robot (or pan-tilt) joints over CANopen CiA 402: this driver is the SYNC master (or follows
// another master's SYNC), starts the nodes with NMT, configures their heartbeat by expedited SDO,
// reads each node's serial number (identity object 0x1018:04) by expedited SDO upload, supervises
// heartbeats and turns each node's TPDO1 into a JointSample stamped with the receive stamp of the
// SYNC echo (the common sampling instant of all joints).
//
// One SDO transfer per node at a time (CiA 301: a node's SDO server serves one client request
// after the other): the 0x1017 download first, the 0x1018:04 upload after its answer or its
// timeout. A node that never answers the upload, or aborts it (sub-index 4 is optional in CiA
// 301), keeps the configured name as its diagnostics identity; the driver goes on streaming.
//
// TPDOs carry no counter, so a TPDO belongs to the last SYNC seen on the bus before it: frames
// are processed in bus order, and our own SYNC comes back as an echo in that order.

#include <memory>
#include <string>
#include <vector>

#include "drivers/can/can_source.hpp"
#include "drivers/can/cia402_codec.hpp"

namespace rangefit::drivers::can {

struct Cia402JointConfig {
  std::uint8_t node = 1;            // CANopen node id 1..127
  std::uint8_t joint = 1;           // JointSample::joint
  double rad_per_increment = 1e-6;  // position actual value scale, rad per increment
  double offset_rad = 0.0;          // angle = increments * scale + offset
};

struct Cia402Config {
  std::string name = "cia402";
  std::vector<Cia402JointConfig> joints;
  bool sync_master = true;  // false: follow a foreign SYNC
  hal::Duration sync_period = std::chrono::milliseconds(4);
  std::uint8_t sync_overflow = 240;           // 0x1019; 0 = SYNC without counter
  bool start_nodes = true;                    // NMT start (and again after boot-up)
  std::uint16_t heartbeat_producer_ms = 100;  // written to 0x1017; 0 = leave as is
  hal::Duration heartbeat_timeout = std::chrono::milliseconds(300);
  // SDO upload of 0x1018:04 at start-up and after a node's boot-up (only with start_nodes: the
  // default SDO channel is the managing master's).
  bool read_identity = true;
  hal::Duration sdo_timeout = std::chrono::milliseconds(200);  // per expedited SDO transfer
  std::size_t queue_capacity = 4096;
  LoopConfig loop;
};

// Transport filter the driver needs: its nodes' ids, SYNC (for the echo) and NMT.
FrameFilter cia402_filter(const Cia402Config& config);

class Cia402JointSource final : public CanSource<hal::JointSample> {
 public:
  Cia402JointSource(Cia402Config config, std::unique_ptr<CanTransport> transport);
  ~Cia402JointSource() override { stop(); }

  // Heartbeat state of a node as last seen (cia402::NmtState), or 0xFF when never heard.
  std::uint8_t node_state(std::uint8_t node) const;

  // What the driver knows of a node's serial number (0x1018:04).
  enum class Identity : std::uint8_t { kUnknown, kKnown, kNoAnswer, kAborted };
  Identity identity(std::uint8_t node) const;

 private:
  enum class SdoPending : std::uint8_t { kNone, kHeartbeat, kIdentity };
  struct Node {
    Cia402JointConfig config;
    hal::Timestamp last_heartbeat{};
    std::uint64_t answered_cycle = 0;  // cycle number of the last TPDO1 taken
    std::int32_t velocity = 0;         // last TPDO2
    SdoPending sdo = SdoPending::kNone;  // the node's SDO transfer in progress
    hal::Timestamp sdo_sent{};
    bool identity_wanted = false;  // ask 0x1018:04 once the SDO channel is free
    std::atomic<std::uint8_t> nmt_state{0xFF};
    std::atomic<bool> alive{true};
    // Written by the receive thread, read by health().
    std::atomic<std::uint32_t> serial{0};
    std::atomic<Identity> identity{Identity::kUnknown};
    std::atomic<std::uint32_t> abort_code{0};
    mutable std::atomic<bool> miss_logged{false};  // the missing serial was logged once
  };

  hal::Status check_config() const override;
  void on_start(hal::Timestamp now) override;
  bool devices_faulted() const override { return any_node_lost_; }
  std::string hardware_id() const override;
  hal::Timestamp on_tick(hal::Timestamp now) override;
  void on_frame(const CanFrame& frame) override;
  void on_link(bool up) override;
  Node* find(std::uint8_t node);
  void start_node(Node& n, hal::Timestamp now);
  void ask_identity(Node& n, hal::Timestamp now);
  void take_sdo_response(Node& n, const cia402::Message& m);
  void expire_sdo(Node& n, hal::Timestamp now);
  void begin_cycle(hal::Timestamp stamp);
  void take_tpdo1(Node& n, const cia402::Message& m);
  void take_sync(const CanFrame& f, const cia402::Message& m);

  Cia402Config config_;
  std::vector<std::unique_ptr<Node>> nodes_;
  // Receive-thread state.
  hal::Timestamp next_sync_{};
  std::uint8_t sync_counter_ = 0;     // last counter sent (master) or seen (follower)
  std::uint8_t pending_counter_ = 0;  // master: sent, echo not yet seen
  bool pending_echo_ = false;
  std::uint64_t cycle_ = 0;  // cycles begun; 0 = none yet
  hal::Timestamp cycle_stamp_{};
  std::atomic<bool> any_node_lost_{false};
};

}  // namespace rangefit::drivers::can
