#pragma once
// Seeded noise and faults a simulated device can inject. All default to
// off; a device draws every random decision of frame k from an RNG seeded by (seed, device, k),
// so a scan is reproducible for a seed however its consumer chunks its reads.

#include <cstdint>
#include <random>

#include "hal/time.hpp"

namespace rangefit::sim {

struct FaultOptions {
  double range_noise_sigma_mm = 0.0;    // Gaussian noise along the beam (CSS: 0.06, thesis 4.2.1)
  double outlier_probability = 0.0;     // per sample: salt (random range) or pepper (no return)
  double ghost_probability = 0.0;       // per sample: specular ghost, the mirrored path's length
  double drop_probability = 0.0;        // per frame: revolution / profile / sample lost
  hal::Duration stamp_jitter_sigma{0};  // Gaussian jitter of frame stamps
  double stale_probability = 0.0;       // per sample: the previous reading repeated (axis, joints)
  hal::Duration disconnect_after{-1};   // after start: link lost (negative: never)
  hal::Duration disconnect_for{0};      // ... and back after this long
};

// RNG for one frame of one device; independent of read order.
inline std::mt19937_64 frame_rng(std::uint64_t seed, std::uint64_t device, std::uint64_t frame) {
  // splitmix64 over the three inputs.
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (device + 1) + 0xBF58476D1CE4E5B9ull * frame;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return std::mt19937_64(z ^ (z >> 31));
}

}  // namespace rangefit::sim
