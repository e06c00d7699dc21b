#pragma once
// What every CAN source driver shares (CiA 402 joints, PowerCube joints, the FD ranger): the
// transport, the receive loop, the counters, the sample ring to the consumer, and the
// start/stop/read/counters/health plumbing around them. A driver derives from CanSource<Sample>,
// fills in the CanLoopHandler hooks with its codec logic and answers devices_faulted(); the same
// shape as spdlog's base_sink (the base owns the machinery, a small virtual hook does the work).
//
// The receive path stays allocation-, lock- and log-free: report(), deliver() and send() only
// touch atomics and the preallocated ring.
//
// A derived driver's destructor must call stop(): the loop thread calls its hooks, so it has to end
// before the derived members are destroyed.

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "drivers/can/can_loop.hpp"
#include "drivers/can/sample_ring.hpp"
#include "hal/source.hpp"

namespace rangefit::drivers::can {

// The non-template halves of CanSource (can_source.cpp).
// Opens the transport for start(); a failure is logged and the loop retries with back-off.
bool open_for_start(CanTransport& transport, const std::string& name);
// Disconnected while the link is down; fault while bus-off or a device is faulted; the message
// names the current bus state first, then the last problem (and its node when known), then a
// failure to apply the configured real-time settings.
hal::DeviceHealth compose_health(bool started, const CanLoop& loop, bool devices_faulted,
                                 Problem problem, std::uint8_t node, const CanCounters& counters);

template <class Sample>
class CanSource : public hal::SampleSource<Sample>, protected CanLoopHandler {
 public:
  ~CanSource() override { stop(); }
  CanSource(const CanSource&) = delete;
  CanSource& operator=(const CanSource&) = delete;

  std::string name() const override { return name_; }

  hal::Status start() override {
    if (started_) return hal::Status::Ok();
    if (hal::Status s = check_config(); !s) return s;
    const bool open = open_for_start(*transport_, name_);
    on_start(hal::monotonic_now());
    if (open) on_link(true);
    loop_.start(open);
    started_ = true;
    return hal::Status::Ok();
  }

  void stop() override {
    if (!started_) return;
    loop_.stop();
    started_ = false;
  }

  std::size_t read(std::vector<Sample>& out, hal::Duration timeout) override {
    return ring_.drain(out, timeout);
  }

  hal::DeviceHealth health() const override {
    hal::DeviceHealth h = compose_health(started_, loop_, devices_faulted(), problem_.load(),
                                         problem_node_.load(), counters());
    h.hardware_id = hardware_id();
    return h;
  }

  CanCounters counters() const {
    CanCounters c = counters_.snapshot(transport_->counters());
    c.values[static_cast<std::size_t>(Counter::kRingDropped)] += ring_.dropped();
    return c;
  }

 protected:
  CanSource(std::string name, std::unique_ptr<CanTransport> transport, std::size_t capacity,
            LoopConfig loop, const Sample& prototype = Sample{})
      : name_(std::move(name)),
        transport_(std::move(transport)),
        ring_(capacity, prototype),
        loop_(*transport_, *this, counters_, loop) {}

  // Refuses a configuration start() cannot run (called before anything is opened).
  virtual hal::Status check_config() const { return hal::Status::Ok(); }
  // Resets the receive-thread state before the loop starts (the loop is not running yet).
  virtual void on_start(hal::Timestamp now) = 0;
  // A device is lost or faulted (health() turns kFault); read from any thread.
  virtual bool devices_faulted() const = 0;
  // The devices' own identity (serial numbers) as far as they told it; empty when none did or
  // the protocol has none. Called by health() from the caller's thread, never the receive thread.
  virtual std::string hardware_id() const { return {}; }

  // Receive thread helpers.
  void report(Problem p, std::uint8_t node = 0) {
    problem_node_ = node;
    problem_ = p;
  }
  void deliver(const Sample& s) {
    if (ring_.push(s)) counters_.bump(Counter::kSamples);
  }
  TxResult send(const CanFrame& f) {
    const TxResult r = transport_->send(f);
    if (r == TxResult::kBufferFull) counters_.bump(Counter::kTxBufferFull);
    return r;
  }
  void bump(Counter c, std::uint64_t n = 1) { counters_.bump(c, n); }
  void on_batch_end() override { ring_.publish(); }

 private:
  std::string name_;
  std::unique_ptr<CanTransport> transport_;
  AtomicCanCounters counters_;
  SampleRing<Sample> ring_;
  CanLoop loop_;
  std::atomic<Problem> problem_{Problem::kNone};
  std::atomic<std::uint8_t> problem_node_{0};
  std::atomic<bool> started_{false};
};

}  // namespace rangefit::drivers::can
