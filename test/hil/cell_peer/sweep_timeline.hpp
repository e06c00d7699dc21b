#pragma once
// The back-and-forth sweep a cell program drives and the service records (the robot pivoting the
// CSS, eq. 4.21; the cell panning the head, eq. 5.7): from -half to +half at constant speed in
// forward_s (the stroke the service records), a stop at +half, back to -half in return_s, a dwell,
// and again, for ever. Pure: the angle as a function of the time since the first stroke began.

#include <algorithm>
#include <cmath>

namespace rangefit::hil {

struct SweepTimeline {
  double half_rad = 0.0;
  double forward_s = 6.0;
  double end_dwell_s = 0.3;  // at +half (so that every SYNC master sees the end)
  double return_s = 1.0;     // back to -half
  double dwell_s = 0.5;      // at -half before the next stroke

  double cycle_s() const { return forward_s + end_dwell_s + return_s + dwell_s; }
  // Angle about the sweep's zero `since` seconds after the first stroke began (cycle_s is the
  // period; callers may round it up, e.g. to whole sensor revolutions); -half before it.
  double angle_at(double since, double cycle) const {
    if (since < 0.0) return -half_rad;
    const double tau = std::fmod(since, cycle);
    if (tau < forward_s) return std::min(half_rad, -half_rad + 2.0 * half_rad * tau / forward_s);
    const double back = tau - forward_s - end_dwell_s;
    if (back < 0.0) return half_rad;
    if (back < return_s) return half_rad - 2.0 * half_rad * back / return_s;
    return -half_rad;
  }
};

}  // namespace rangefit::hil
