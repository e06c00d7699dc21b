#pragma once
// What every assembler hands out: the world-frame cloud of one scan plus the scan's metadata,
// above all the time-alignment faults that were met while building it. Faults
// are counted, never smoothed over silently; past the configured limit the scan is marked bad.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "detect/common/point_cloud.hpp"
#include "hal/time.hpp"

namespace rangefit::fusion {

// Time-alignment faults of one scan. "Frame" is a CSS revolution or a ranger profile; the
// "reference" stream is what gives each frame its pose: robot joint angles (CSS), linear-axis
// positions (stripe cell) or pan/tilt angles (mobile head).
struct TimeFaults {
  // Frames or reference samples whose stamp (or frame sequence) did not increase; dropped.
  std::uint32_t out_of_order = 0;
  // Lost frames (sequence skipped) or reference samples further apart than the configured limit.
  std::uint32_t gaps = 0;
  // Frames fused with a pose extrapolated beyond the first or last reference sample (or, for
  // the eq. 4.21 fallback, beyond the scan's end stamp).
  std::uint32_t extrapolated = 0;
  // Frame stamps whose step disagrees with the device's period (or the nominal profile period)
  // by more than the configured tolerance, although no frame was lost.
  std::uint32_t clock_jumps = 0;

  std::uint32_t total() const { return out_of_order + gaps + extrapolated + clock_jumps; }
};

// Per row of the organised cloud: which frame produced it.
struct FrameInfo {
  std::uint32_t sequence = 0;  // device counter of the frame
  hal::Timestamp stamp{};      // frame stamp (CSS: sample 0; ranger: exposure centre)
  bool extrapolated = false;   // pose was extrapolated for at least one sample of the frame
  // Profile scans: the pose channels the frame was placed with, interpolated at its stamp
  // (stripe cell: axis position mm, 0; pan-tilt head: pan, tilt rad as reported). CSS: zero.
  std::array<double, 2> pose{};
};

struct FusedScan {
  PointCloud cloud;               // frame_id "world", mm, per-point stamps, organised grid
  std::vector<FrameInfo> frames;  // one per grid row, in row order
  TimeFaults faults;
  std::uint32_t dropped_frames = 0;      // frames not fused (out of order, malformed)
  std::uint32_t rejected_reference = 0;  // reference samples flagged invalid by the device
  bool bad = false;                      // faults.total() exceeded the configured limit
  std::string reason;                    // why the scan is bad; empty when it is not

  // Empties the scan for a new one of about `rows` rows of `cols` cells, reserving memory up
  // front so fusing never reallocates mid-scan.
  void reset(std::size_t rows, int cols) {
    const std::size_t cells = rows * static_cast<std::size_t>(cols);
    cloud.frame_id = "world";
    cloud.points.clear();
    cloud.normals.clear();
    cloud.stamps.clear();
    cloud.points.reserve(cells);
    cloud.stamps.reserve(cells);
    cloud.grid.rows = 0;
    cloud.grid.cols = cols;
    cloud.grid.index.clear();
    cloud.grid.index.reserve(cells);
    frames.clear();
    frames.reserve(rows);
    faults = {};
    dropped_frames = 0;
    rejected_reference = 0;
    bad = false;
    reason.clear();
  }
};

}  // namespace rangefit::fusion
