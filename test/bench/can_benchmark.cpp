// The CAN receive path over a real vcan interface (runs in the HIL VM:
//   HIL_CMD="BUILD/test/bench/can_benchmark" bash test/hil/run_vm.sh BUILD).
// 1. Sustained load: a paced sender (classic: SYNC + 7 TPDO1 per cycle; FD: 18-frame ranger
//    profiles) at the rates (8,000 classic / 1,800 FD frames/s) and multiples of them;
//    received frames/s and drops through the driver (transport + loop + codec), against a plain
//    blocking recv() loop on the same interface in the same run (ratio = driver / recv).
// 2. Stamp jitter of the 4 ms SYNC cycle: deviation of successive SYNC-echo stamps from 4 ms,
//    p50/p99, against a clock_nanosleep(TIMER_ABSTIME) 4 ms loop's wake-up lateness in the same
//    run (the floor any user-space cyclic thread sits on in that machine).
// On a kernel without AF_CAN (the build machines) or without the interface it prints why and
// exits 0 without running anything.
#include <benchmark/benchmark.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "drivers/can/cia402_joint_source.hpp"
#include "drivers/can/ranger_source.hpp"
#include "drivers/can/socketcan_transport.hpp"
#include "test/support/can_bus.hpp"
#include "test/support/can_cia402_node.hpp"

namespace rangefit::drivers::can {
namespace {

using namespace std::chrono_literals;

constexpr int kJoints = 7;              // classic cycle: SYNC + 7 TPDO1 = 8 frames
constexpr std::uint8_t kRanger = 0x24;  // FD: one profile = 18 frames
constexpr int kReceiveBuffer = 1 << 20;

std::string interface() {
  const char* i = std::getenv("RANGEFIT_HIL_CAN");
  return i ? i : "vcan0";
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1))];
}

std::unique_ptr<SocketCanTransport> transport(FrameFilter filter, bool fd) {
  SocketCanConfig c;
  c.interface = interface();
  c.filter = std::move(filter);
  c.fd = fd;
  c.receive_buffer = kReceiveBuffer;
  return std::make_unique<SocketCanTransport>(c);
}

Cia402Config classic_config() {
  Cia402Config c;
  c.sync_master = false;
  c.start_nodes = false;
  c.queue_capacity = 1 << 16;
  for (int j = 1; j <= kJoints; ++j) {
    c.joints.push_back({static_cast<std::uint8_t>(j), static_cast<std::uint8_t>(j), 1e-6, 0.0});
  }
  return c;
}

RangerConfig fd_config() {
  RangerConfig c;
  c.node = kRanger;
  c.queue_capacity = 1024;
  return c;
}

// The frames of one cycle (classic) or one profile (FD) with sequence number k.
std::vector<CanFrame> group(bool fd, std::uint32_t k) {
  std::vector<CanFrame> frames;
  if (!fd) {
    frames.push_back(cia402::encode_sync(static_cast<std::uint8_t>(k % 240 + 1)));
    for (int j = 1; j <= kJoints; ++j) {
      frames.push_back(
          cia402::encode_tpdo1(static_cast<std::uint8_t>(j), 0x0637, static_cast<int>(k)));
    }
    return frames;
  }
  ranger::WireProfile p;
  p.sequence = k;
  p.device_time_us = k * 10'000;
  p.exposure_us = 500;
  p.point_count = 512;
  p.units_um = 4;
  for (std::size_t i = 0; i < 512; ++i) p.range[i] = static_cast<std::uint16_t>(1000 + i);
  frames.resize(ranger::kMaxSegments + 1);
  frames.resize(ranger::encode(kRanger, p, frames));
  return frames;
}

// Gives a prepared group sequence number k without encoding it again: the SYNC counter, or
// the profile sequence (every frame's byte 0, the header's U32) and device time.
void renumber(bool fd, std::uint32_t k, std::vector<CanFrame>& frames) {
  if (!fd) {
    frames[0].data[0] = static_cast<std::uint8_t>(k % 240 + 1);
    return;
  }
  for (CanFrame& f : frames) f.data[0] = static_cast<std::uint8_t>(k);
  put_u32(frames[0].data, 2, k);
  put_u32(frames[0].data, 6, k * 10'000);
}

struct StreamResult {
  double sent_per_s = 0;
  double received_per_s = 0;
  std::uint64_t sent = 0;
  std::uint64_t received = 0;
  std::uint64_t drops = 0;    // kernel overflow + frames that never arrived + ring drops
  std::uint64_t missing = 0;  // decoded samples/profiles short of what was sent
  bool ok = true;
};

// Sends whole groups paced to `rate` frames/s for `duration` from its own socket.
std::uint64_t send_paced(bool fd, double rate, hal::Duration duration, double& seconds) {
  auto tx = transport({}, fd);
  if (!tx->open().ok) return 0;
  std::vector<CanFrame> frames = group(fd, 0);
  const double group_rate = rate / static_cast<double>(frames.size());
  const hal::Timestamp t0 = hal::monotonic_now();
  std::uint64_t sent = 0, done = 0;
  for (;;) {
    const hal::Timestamp now = hal::monotonic_now();
    if (now - t0 >= duration) break;
    const auto due =
        static_cast<std::uint64_t>(group_rate * std::chrono::duration<double>(now - t0).count());
    for (; done < due; ++done) {
      renumber(fd, static_cast<std::uint32_t>(done), frames);
      for (const CanFrame& f : frames) {
        while (tx->send(f) == TxResult::kBufferFull) std::this_thread::sleep_for(20us);
        ++sent;
      }
    }
    std::this_thread::sleep_for(500us);
  }
  seconds = std::chrono::duration<double>(hal::monotonic_now() - t0).count();
  return sent;
}

// Baseline: a plain blocking recv() loop on a raw socket with the same filter.
StreamResult recv_baseline(bool fd, double rate, hal::Duration duration) {
  StreamResult r;
  const int s = socket(PF_CAN, SOCK_RAW, CAN_RAW);
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, interface().c_str(), IFNAMSIZ - 1);
  if (s < 0 || ioctl(s, SIOCGIFINDEX, &ifr) < 0) return {.ok = false};
  const int one = 1;
  if (fd) setsockopt(s, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &one, sizeof(one));
  const FrameFilter filter = fd ? ranger_filter(fd_config()) : cia402_filter(classic_config());
  std::vector<can_filter> filters;
  for (std::uint32_t id : filter.ids) filters.push_back({id, CAN_SFF_MASK | CAN_EFF_FLAG});
  setsockopt(s, SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(),
             static_cast<socklen_t>(filters.size() * sizeof(can_filter)));
  setsockopt(s, SOL_SOCKET, SO_RCVBUF, &kReceiveBuffer, sizeof(int));
  const timeval tv{0, 200'000};
  setsockopt(s, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof(tv));
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifr.ifr_ifindex;
  bind(s, reinterpret_cast<sockaddr*>(&addr), sizeof(addr));
  std::atomic<bool> sending{true};
  std::uint64_t received = 0;
  std::thread reader([&] {
    canfd_frame f;
    for (;;) {
      if (recv(s, &f, sizeof(f), 0) > 0)
        ++received;
      else if (!sending)
        break;  // timed out after the sender finished
    }
  });
  double seconds = 0;
  r.sent = send_paced(fd, rate, duration, seconds);
  std::this_thread::sleep_for(100ms);
  sending = false;
  reader.join();
  close(s);
  r.received = std::min(received, r.sent);
  r.drops = r.sent - r.received;
  r.sent_per_s = static_cast<double>(r.sent) / seconds;
  r.received_per_s = static_cast<double>(r.received) / seconds;
  return r;
}

// The driver path: the CiA 402 follower (classic) or the ranger (FD) on the paced stream.
template <class Driver, class Config>
StreamResult through_driver(const Config& config, bool fd, double rate, hal::Duration duration) {
  StreamResult r;
  const FrameFilter filter = fd ? ranger_filter(fd_config()) : cia402_filter(classic_config());
  Driver driver(config, transport(filter, fd));
  if (!driver.start().ok) return {.ok = false};
  double seconds = 0;
  r.sent = send_paced(fd, rate, duration, seconds);
  std::this_thread::sleep_for(100ms);
  const CanCounters c = driver.counters();
  driver.stop();
  r.received = c.transport.rx_frames;
  r.drops = c.transport.rx_overflow + c[Counter::kRingDropped] +
            (r.sent > r.received ? r.sent - r.received : 0);
  // The decoded output must be complete too: 7 samples a cycle, every profile (the last one
  // may still wait for the next frame), no CRC errors.
  const std::uint64_t groups = r.sent / (fd ? ranger::kMaxSegments + 1 : kJoints + 1);
  const std::uint64_t expected = fd ? groups : groups * kJoints;
  const std::uint64_t decoded = c[Counter::kSamples] + (fd ? 1 : 0);
  r.missing = (decoded < expected ? expected - decoded : 0) + c[Counter::kCrcErrors];
  r.sent_per_s = static_cast<double>(r.sent) / seconds;
  r.received_per_s = static_cast<double>(r.received) / seconds;
  return r;
}

// arg 0: classic (0) or FD (1); arg 1: multiple of the rate.
void BM_CanReceiveSustained(benchmark::State& state) {
  const bool fd = state.range(0) == 1;
  const double rate = (fd ? 1800.0 : 8000.0) * static_cast<double>(state.range(1));
  const hal::Duration duration = state.range(1) == 1 ? 1s : 500ms;
  StreamResult base, drv;
  for (auto _ : state) {
    base = recv_baseline(fd, rate, duration);
    drv = fd ? through_driver<RangerCanSource>(fd_config(), fd, rate, duration)
             : through_driver<Cia402JointSource>(classic_config(), fd, rate, duration);
  }
  if (!base.ok) return state.SkipWithError("baseline socket failed");
  if (!drv.ok) return state.SkipWithError("driver did not start");
  state.counters["target_frames_per_s"] = rate;
  state.counters["driver_frames_per_s"] = drv.received_per_s;
  state.counters["driver_drops"] = static_cast<double>(drv.drops);
  state.counters["driver_missing_decoded"] = static_cast<double>(drv.missing);
  state.counters["recv_frames_per_s"] = base.received_per_s;
  state.counters["recv_drops"] = static_cast<double>(base.drops);
  state.counters["ratio_driver_vs_recv"] =
      base.received_per_s > 0 ? drv.received_per_s / base.received_per_s : 0.0;
}
BENCHMARK(BM_CanReceiveSustained)
    ->ArgsProduct({{0, 1}, {1, 2, 4, 8}})
    ->ArgNames({"fd", "x_rate"})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

// SYNC stamps as an independent observer socket sees them (kernel stamps, converted by the
// same transport code) while `produce` runs.
template <class Produce>
std::vector<hal::Timestamp> observe_syncs(Produce produce) {
  auto observer = transport({{cia402::kSyncId}}, false);
  if (!observer->open().ok) return {};
  std::atomic<bool> observing{true};
  std::vector<hal::Timestamp> syncs;
  syncs.reserve(4096);
  std::thread watch([&] {
    std::array<CanFrame, 64> in{};
    while (observing) {
      const RxResult r = observer->receive(in, 20ms);
      for (std::size_t i = 0; i < r.frames; ++i) syncs.push_back(in[i].stamp);
    }
  });
  produce();
  std::this_thread::sleep_for(20ms);
  observing = false;
  watch.join();
  return syncs;
}

struct Jitter {
  double p50_us = 0, p99_us = 0, per_s = 0;
};

// |interval - 4 ms| of successive SYNCs after the first `skip`, and the SYNC rate.
Jitter sync_jitter(const std::vector<hal::Timestamp>& syncs, std::size_t skip) {
  Jitter j;
  std::vector<double> dev;
  for (std::size_t i = skip + 1; i < syncs.size(); ++i) {
    const double dt = std::chrono::duration<double, std::micro>(syncs[i] - syncs[i - 1]).count();
    dev.push_back(std::abs(dt - 4000.0));
  }
  if (dev.empty()) return j;
  j.p50_us = percentile(dev, 0.5);
  j.p99_us = percentile(dev, 0.99);
  j.per_s = static_cast<double>(dev.size()) /
            std::chrono::duration<double>(syncs.back() - syncs[skip]).count();
  return j;
}

// Baseline: the plainest SYNC master, a clock_nanosleep(TIMER_ABSTIME) 4 ms loop writing a SYNC
// on a raw socket each period.
void plain_sync_master(hal::Duration duration, bool fifo) {
  std::thread t([&] {
    if (fifo) (void)apply_realtime(RealtimeConfig{.fifo = true});
    auto tx = transport({}, false);
    if (!tx->open().ok) return;
    timespec next{};
    clock_gettime(CLOCK_MONOTONIC, &next);
    const hal::Timestamp end = hal::monotonic_now() + duration;
    for (std::uint8_t counter = 1; hal::monotonic_now() < end; counter = counter % 240 + 1) {
      next.tv_nsec += 4'000'000;
      if (next.tv_nsec >= 1'000'000'000) {
        next.tv_nsec -= 1'000'000'000;
        ++next.tv_sec;
      }
      clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
      (void)tx->send(cia402::encode_sync(counter));
    }
  });
  t.join();
}

// The driver as SYNC master every 4 ms (one simulated node answering on its own socket) against
// the plain master above, both watched by the same observer for 2 s. The driver's samples carry
// their SYNC's echo stamp: their deviation from the 4 ms grid and the cycles without a sample
// are reported too. arg: the masters' threads under SCHED_FIFO (root in the VM).
void BM_CanSyncStampJitter(benchmark::State& state) {
  const bool fifo = state.range(0) == 1;
  Jitter plain, drv;
  std::vector<double> grid_dev;
  double missed = 0, realtime_failed = 0, tx_frames = 0, rx_frames = 0;
  for (auto _ : state) {
    plain = sync_jitter(observe_syncs([&] { plain_sync_master(2s, fifo); }), 0);
    auto sim_socket = transport({}, false);
    if (!sim_socket->open().ok) return state.SkipWithError("socket failed");
    sim::SimCanBus bus(std::move(sim_socket));
    bus.add(std::make_shared<sim::SimCia402Node>(sim::SimCia402Config{1}));
    bus.start();
    Cia402Config c;
    c.joints = {{1, 1, 1e-6, 0.0}};
    c.loop.realtime.fifo = fifo;
    Cia402JointSource driver(c, transport(cia402_filter(c), false));
    std::vector<hal::JointSample> out;
    const auto syncs = observe_syncs([&] {
      if (!driver.start().ok) return;
      const auto end = hal::monotonic_now() + 2s;
      while (hal::monotonic_now() < end) driver.read(out, 20ms);
      driver.stop();
    });
    tx_frames = static_cast<double>(driver.counters().transport.tx_frames);
    rx_frames = static_cast<double>(driver.counters().transport.rx_frames);
    bus.stop();
    realtime_failed = driver.health().message.find("real-time") != std::string::npos ? 1 : 0;
    drv = sync_jitter(syncs, 10);  // skip start-up (NMT, SDO)
    for (std::size_t i = 11; i < out.size(); ++i) {
      const double dt =
          std::chrono::duration<double, std::micro>(out[i].stamp - out[i - 1].stamp).count();
      const double n = std::max(1.0, std::round(dt / 4000.0));
      grid_dev.push_back(std::abs(dt - n * 4000.0));
      missed += n - 1;
    }
  }
  if (plain.per_s == 0 || drv.per_s == 0 || grid_dev.empty()) {
    return state.SkipWithError("no SYNCs or samples");
  }
  state.counters["driver_syncs_per_s"] = drv.per_s;
  state.counters["driver_sync_jitter_p50_us"] = drv.p50_us;
  state.counters["driver_sync_jitter_p99_us"] = drv.p99_us;
  state.counters["sample_grid_dev_p50_us"] = percentile(grid_dev, 0.5);
  state.counters["sample_grid_dev_p99_us"] = percentile(grid_dev, 0.99);
  state.counters["cycles_without_sample"] = missed;
  state.counters["plain_syncs_per_s"] = plain.per_s;
  state.counters["plain_sync_jitter_p50_us"] = plain.p50_us;
  state.counters["plain_sync_jitter_p99_us"] = plain.p99_us;
  state.counters["ratio_p50_vs_plain"] = plain.p50_us > 0 ? drv.p50_us / plain.p50_us : 0.0;
  state.counters["ratio_p99_vs_plain"] = plain.p99_us > 0 ? drv.p99_us / plain.p99_us : 0.0;
  state.counters["realtime_failed"] = realtime_failed;
  state.counters["driver_tx_frames"] = tx_frames;
  state.counters["driver_rx_frames"] = rx_frames;
}
BENCHMARK(BM_CanSyncStampJitter)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("fifo")
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

// Why the benchmarks cannot run here, or empty when they can.
std::string unavailable() {
  const int s = socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (s < 0) {
    return std::string("no AF_CAN sockets on this kernel (") + std::strerror(errno) + ")";
  }
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, interface().c_str(), IFNAMSIZ - 1);
  const bool present = ioctl(s, SIOCGIFINDEX, &ifr) == 0;
  close(s);
  return present ? "" : "no interface " + interface();
}

}  // namespace
}  // namespace rangefit::drivers::can

int main(int argc, char** argv) {
  const std::string why = rangefit::drivers::can::unavailable();
  if (!why.empty()) {
    std::printf(
        "can_benchmark: skipped: %s. It needs vcan: run it in the HIL VM with\n"
        "  HIL_CMD=\"%s\" bash test/hil/run_vm.sh BUILD_DIR\n",
        why.c_str(), argv[0]);
    return 0;
  }
  // Plain output by default: the VM harness reads its exit marker from the same console.
  std::vector<char*> args(argv, argv + argc);
  char no_color[] = "--benchmark_color=false";
  args.insert(args.begin() + 1, no_color);
  int n = static_cast<int>(args.size());
  benchmark::Initialize(&n, args.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
