// FHPP over Modbus TCP on loopback: poll round trip (p50/p99) and the stamp uncertainty it gives,
// against a bare TCP ping-pong of the same frame sizes measured in the same run (the floor any
// Modbus stack sits on); reconnect time after a reset, at the link and through the driver.
#include <arpa/inet.h>
#include <benchmark/benchmark.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <thread>
#include <vector>

#include "drivers/modbus/fhpp_axis.hpp"
#include "drivers/modbus/modbus_link.hpp"
#include "test/support/fault_proxy.hpp"
#include "test/support/modbus_axis_server.hpp"

namespace rangefit {
namespace {

using namespace std::chrono_literals;
namespace fhpp = drivers::fhpp;

double us(hal::Duration d) { return std::chrono::duration<double, std::micro>(d).count(); }

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1))];
}

sim::SimAxisConfig drive_config() {
  sim::SimAxisConfig c;
  c.comm_timeout = 0s;  // benchmarks pause between phases
  return c;
}

// Median round trip of a bare TCP ping-pong: 25-byte request (a 0x17 ADU), 17-byte reply.
double tcp_pingpong_p50_us(int rounds) {
  const int listener = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof a;
  ::bind(listener, reinterpret_cast<sockaddr*>(&a), sizeof a);
  ::listen(listener, 1);
  ::getsockname(listener, reinterpret_cast<sockaddr*>(&a), &len);
  std::thread echo([&] {
    const int s = ::accept(listener, nullptr, nullptr);
    const int on = 1;
    setsockopt(s, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
    char buf[64];
    while (::recv(s, buf, 25, MSG_WAITALL) == 25) ::send(s, buf, 17, MSG_NOSIGNAL);
    ::close(s);
  });
  const int c = ::socket(AF_INET, SOCK_STREAM, 0);
  ::connect(c, reinterpret_cast<sockaddr*>(&a), sizeof a);
  const int on = 1;
  setsockopt(c, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
  std::vector<double> rtts;
  char buf[64] = {};
  for (int i = 0; i < rounds; ++i) {
    const auto t0 = hal::monotonic_now();
    ::send(c, buf, 25, MSG_NOSIGNAL);
    if (::recv(c, buf, 17, MSG_WAITALL) != 17) break;
    rtts.push_back(us(hal::monotonic_now() - t0));
  }
  ::close(c);
  echo.join();
  ::close(listener);
  return percentile(rtts, 0.5);
}

// One 0x17 exchange per iteration, driver link against the simulated drive.
void BM_ModbusPollRoundTrip(benchmark::State& state) {
  const double baseline_us = tcp_pingpong_p50_us(2000);
  sim::SimFhppDrive drive(drive_config());
  sim::SimAxisServer server(drive, {});
  if (!server.start().ok) return state.SkipWithError("sim server did not start");
  hal::MonotonicClock clock;
  drivers::ModbusLinkConfig lc;
  lc.port = server.port();
  drivers::ModbusLink link(lc, clock);
  if (!link.open().ok()) return state.SkipWithError("connect failed");
  const fhpp::Registers out = fhpp::encode(fhpp::OutputTelegram{}, fhpp::ByteOrder::kLowByteFirst);
  fhpp::Registers in{};
  std::vector<double> rtts;
  for (auto _ : state) {
    const drivers::LinkResult r = link.exchange(out, in);
    if (!r.ok()) return state.SkipWithError(r.message.c_str());
    rtts.push_back(us(r.reply - r.request));
  }
  const double p50 = percentile(rtts, 0.5), p99 = percentile(rtts, 0.99);
  state.counters["rtt_p50_us"] = p50;
  state.counters["rtt_p99_us"] = p99;
  state.counters["stamp_pm_p99_us"] = p99 / 2;  // the stamp is the midpoint: +-rtt/2
  state.counters["tcp_pingpong_p50_us"] = baseline_us;
  state.counters["ratio_p50_vs_pingpong"] = baseline_us > 0 ? p50 / baseline_us : 0.0;
}
BENCHMARK(BM_ModbusPollRoundTrip)->Iterations(5000)->Unit(benchmark::kMicrosecond);

// A reset mid-request, then close + connect + first good exchange (the link's recovery path).
void BM_ModbusReconnectAfterReset(benchmark::State& state) {
  sim::SimFhppDrive drive(drive_config());
  sim::SimAxisServer server(drive, {});
  if (!server.start().ok) return state.SkipWithError("sim server did not start");
  sim::FaultProxy proxy("127.0.0.1", server.port());
  if (!proxy.start().ok) return state.SkipWithError("proxy did not start");
  hal::MonotonicClock clock;
  drivers::ModbusLinkConfig lc;
  lc.port = proxy.port();
  drivers::ModbusLink link(lc, clock);
  const fhpp::Registers out = fhpp::encode(fhpp::OutputTelegram{}, fhpp::ByteOrder::kLowByteFirst);
  fhpp::Registers in{};
  if (!link.open().ok() || !link.exchange(out, in).ok()) return state.SkipWithError("no link");
  std::vector<double> times;
  for (auto _ : state) {
    proxy.reset_next_request();
    if (link.exchange(out, in).error != drivers::LinkError::kConnectionLost) {
      return state.SkipWithError("reset not seen as a lost connection");
    }
    const auto t0 = hal::monotonic_now();
    if (!link.open().ok() || !link.exchange(out, in).ok())
      return state.SkipWithError("no reconnect");
    const auto dt = hal::monotonic_now() - t0;
    state.SetIterationTime(std::chrono::duration<double>(dt).count());
    times.push_back(us(dt));
  }
  state.counters["reconnect_p50_us"] = percentile(times, 0.5);
  state.counters["reconnect_p99_us"] = percentile(times, 0.99);
}
BENCHMARK(BM_ModbusReconnectAfterReset)
    ->Iterations(200)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

// The driver as the cell runs it (10 ms period): sample uncertainty, and the time from a reset
// mid-request (as the proxy did it) to the stamp of the next sample.
void BM_FhppAxisDriverAtTenMilliseconds(benchmark::State& state) {
  sim::SimFhppDrive drive(drive_config());
  sim::SimAxisServer server(drive, {});
  if (!server.start().ok) return state.SkipWithError("sim server did not start");
  sim::FaultProxy proxy("127.0.0.1", server.port());
  if (!proxy.start().ok) return state.SkipWithError("proxy did not start");
  drivers::FhppAxisConfig c;
  c.link.port = proxy.port();
  c.poll_period = 10ms;
  c.backoff_initial = 10ms;
  drivers::FhppAxis axis(c);
  if (!axis.start().ok) return state.SkipWithError("driver did not start");
  std::vector<double> uncertainty, recovery;
  std::vector<hal::AxisSample> samples;
  for (auto _ : state) {
    samples.clear();
    while (samples.size() < 100) axis.read(samples, 100ms);  // 1 s of polling
    for (const auto& s : samples) uncertainty.push_back(us(s.uncertainty));
    const auto reconnects = axis.health().counters.reconnects;
    proxy.reset_next_request();
    while (axis.health().counters.reconnects == reconnects) std::this_thread::sleep_for(100us);
    samples.clear();
    while (samples.empty()) axis.read(samples, 100ms);
    const auto t0 = proxy.last_reset_at();
    recovery.push_back(us(samples.front().stamp - t0));
  }
  state.counters["sample_uncertainty_p50_us"] = percentile(uncertainty, 0.5);
  state.counters["sample_uncertainty_p99_us"] = percentile(uncertainty, 0.99);
  state.counters["reset_to_next_sample_p50_us"] = percentile(recovery, 0.5);
}
BENCHMARK(BM_FhppAxisDriverAtTenMilliseconds)->Iterations(3)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rangefit

BENCHMARK_MAIN();
