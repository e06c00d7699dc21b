#pragma once
// A loopback TCP proxy that injects link faults between a driver and a device (real or simulated):
// delayed replies, a dropped request, a reset mid-request, a black hole (half-open: nothing flows,
// nothing is closed) and a closed port (connection refused). Protocol-agnostic byte forwarding.

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "hal/device.hpp"
#include "hal/time.hpp"

namespace rangefit::sim {

class FaultProxy {
 public:
  FaultProxy(std::string upstream_host, int upstream_port);
  ~FaultProxy();
  FaultProxy(const FaultProxy&) = delete;
  FaultProxy& operator=(const FaultProxy&) = delete;

  // Listens on 127.0.0.1:listen_port (0 = any free port, see port()).
  hal::Status start(int listen_port = 0);
  void stop();
  int port() const { return port_; }

  // Replies (upstream -> client bytes) are held back this long.
  void set_reply_delay(hal::Duration d) { reply_delay_ns_ = d.count(); }
  // The next request chunk is swallowed (never reaches the device).
  void drop_next_request() { drop_next_ = true; }
  // The next request chunk makes the proxy reset (RST) both sides instead of forwarding it.
  void reset_next_request() { reset_next_ = true; }
  // On: bytes in both directions are swallowed while every connection stays open (half-open).
  void set_black_hole(bool on) { black_hole_ = on; }
  // Off: the listening port is closed (connect is refused) and live connections are reset.
  void set_listening(bool on) { listening_ = on; }

  int connections() const { return connections_; }
  std::uint64_t resets() const { return resets_; }
  // CLOCK_MONOTONIC instant of the last reset done by reset_next_request().
  hal::Timestamp last_reset_at() const { return hal::Timestamp(last_reset_ns_.load()); }

 private:
  void run();
  bool open_listener();

  std::string upstream_host_;
  int upstream_port_;
  int port_ = 0;
  int listen_fd_ = -1;
  std::atomic<long long> reply_delay_ns_{0};
  std::atomic<bool> drop_next_{false};
  std::atomic<bool> reset_next_{false};
  std::atomic<bool> black_hole_{false};
  std::atomic<bool> listening_{true};
  std::atomic<int> connections_{0};
  std::atomic<std::uint64_t> resets_{0};
  std::atomic<long long> last_reset_ns_{0};
  std::atomic<bool> running_{false};
  std::thread thread_;
};

}  // namespace rangefit::sim
