#pragma once
// Robot (or pan-tilt) joints over CANopen CiA 402: this driver is the SYNC master (or follows
// another master's SYNC), starts the nodes with NMT, configures their heartbeat by expedited SDO,
// supervises heartbeats and turns each node's TPDO1 into a JointSample stamped with the receive
// stamp of the SYNC echo (the common sampling instant of all joints).
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

 private:
  struct Node {
    Cia402JointConfig config;
    hal::Timestamp last_heartbeat{};
    std::uint64_t answered_cycle = 0;  // cycle number of the last TPDO1 taken
    std::int32_t velocity = 0;         // last TPDO2
    std::atomic<std::uint8_t> nmt_state{0xFF};
    std::atomic<bool> alive{true};
  };

  hal::Status check_config() const override;
  void on_start(hal::Timestamp now) override;
  bool devices_faulted() const override { return any_node_lost_; }
  hal::Timestamp on_tick(hal::Timestamp now) override;
  void on_frame(const CanFrame& frame) override;
  void on_link(bool up) override;
  Node* find(std::uint8_t node);
  void start_node(std::uint8_t node);
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
