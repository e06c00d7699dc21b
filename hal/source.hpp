#pragma once
// The stream contract between devices and the rest: a device delivers samples into a bounded
// buffer from its own thread; consumers pull them. Full buffers drop and count, never block the
// device thread.

#include <cstddef>
#include <vector>

#include "hal/device.hpp"
#include "hal/samples.hpp"

namespace rangefit::hal {

template <class Sample>
class SampleSource : public Device {
 public:
  // Appends every buffered sample to out, oldest first. Waits up to `timeout` for the first one;
  // returns how many were appended (0 on timeout). Never throws.
  virtual std::size_t read(std::vector<Sample>& out, Duration timeout) = 0;
};

using CssSource = SampleSource<CssRevolution>;
using JointSource = SampleSource<JointSample>;
using RangerSource = SampleSource<RangerProfile>;
using PanTiltSource = SampleSource<PanTiltSample>;

// The linear axis both reports positions and takes motion commands (thesis 5.2.1).
class LinearAxis : public SampleSource<AxisSample> {
 public:
  virtual Status enable() = 0;
  virtual Status home() = 0;
  // Absolute move to position_mm at speed_mm_s; returns once the command is accepted.
  virtual Status move_to(double position_mm, double speed_mm_s) = 0;
  virtual Status halt() = 0;
  virtual bool motion_complete() const = 0;
};

}  // namespace rangefit::hal
