// CSS receive hot path throughput: bulk-transfer bytes -> parsed, CRC-checked, clock-translated
// hal::CssRevolution, in revolutions per second on one core. Baseline in the same run: a bare
// CRC-32 pass over the same bytes (the work no parser can avoid), so the ratio shows the overhead.
//   build-*/test/bench/css_usb_benchmark --benchmark_repetitions=3

#include <benchmark/benchmark.h>

#include <vector>

#include "drivers/usb/revolution_translator.hpp"

namespace rangefit::drivers::css_usb {
namespace {

constexpr std::uint32_t kRevolutions = 256;

std::vector<std::uint8_t> stream() {
  std::vector<std::uint8_t> bytes;
  for (std::uint32_t k = 0; k < kRevolutions; ++k) {
    WireRevolution r;
    r.sequence = k;
    r.device_time_us = 1'000'000 + k * 142'857ull;
    r.period_us = 142'857;
    for (std::size_t i = 0; i < kSamples; ++i) {
      r.samples[i] = {static_cast<std::uint16_t>(i * 31 + k), 7, 9};
    }
    encode_revolution(r, bytes);
  }
  return bytes;
}

RevolutionTranslator synced_translator() {
  RevolutionTranslator t;
  const hal::Timestamp host = std::chrono::seconds(100);
  for (int k = 0; k < 8; ++k) {
    t.add_exchange(host + std::chrono::seconds(k), 1'000'000 + 1'000'000ull * k,
                   host + std::chrono::seconds(k) + std::chrono::microseconds(100));
  }
  return t;
}

void BM_Crc32Baseline(benchmark::State& state) {
  const auto bytes = stream();
  for (auto _ : state) {
    for (std::size_t f = 0; f < kRevolutions; ++f) {
      benchmark::DoNotOptimize(crc32(std::span(bytes).subspan(f * kFrameBytes, kFrameBytes - 4)));
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * kRevolutions);
}
BENCHMARK(BM_Crc32Baseline);

// One transfer per revolution (the normal case) or 512-byte short transfers (worst case).
void BM_ParseAndTranslate(benchmark::State& state) {
  const auto bytes = stream();
  const auto chunk = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) {
    state.PauseTiming();
    RevolutionTranslator translator = synced_translator();
    state.ResumeTiming();
    std::uint64_t n = 0;
    for (std::size_t at = 0; at < bytes.size(); at += chunk) {
      const auto part = std::span(bytes).subspan(at, std::min(chunk, bytes.size() - at));
      translator.feed(part, hal::Timestamp{}, [&](const hal::CssRevolution& r, const auto&) {
        benchmark::DoNotOptimize(r.stamp);
        ++n;
      });
    }
    if (n != kRevolutions) state.SkipWithError("lost revolutions");
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * kRevolutions);
}
BENCHMARK(BM_ParseAndTranslate)->Arg(static_cast<int>(kFrameBytes))->Arg(512);

}  // namespace
}  // namespace rangefit::drivers::css_usb

BENCHMARK_MAIN();
