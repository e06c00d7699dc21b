#include "calib/stripe_refine.hpp"

#include <cmath>

namespace rangefit::calib {

using Eigen::Vector3d;

void axis_tangents(const Vector3d& d, Vector3d& u1, Vector3d& u2) {
  const Vector3d helper = std::abs(d.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY();
  u1 = d.cross(helper).normalized();
  u2 = d.cross(u1).normalized();
}

namespace {

LmLinearisation<8> linearise(const StripeState& s, const std::vector<StripePlanePoint>& pts,
                             const std::array<CubePlane, 6>& planes) {
  LmLinearisation<8> lin;
  const Eigen::Matrix3d R = s.T_cell_ranger.linear();
  const Vector3d t = s.T_cell_ranger.translation();
  Vector3d u1, u2;
  axis_tangents(s.axis, u1, u2);
  for (const StripePlanePoint& p : pts) {
    const CubePlane& pl = planes[static_cast<std::size_t>(p.plane)];
    const Vector3d& n = pl.normal;
    const double r = n.dot(R * p.q + t - p.axis_mm * s.axis) - pl.offset_mm;
    LmVector<8> j;
    j.head<3>() = n;
    j.segment<3>(3) = p.q.cross(R.transpose() * n);  // R exp([w]x) q ~ R (q + w x q)
    j[6] = -p.axis_mm * n.dot(u1);
    j[7] = -p.axis_mm * n.dot(u2);
    lin.cost += 0.5 * r * r;
    lin.jtj.noalias() += j * j.transpose();
    lin.g.noalias() += j * r;
  }
  return lin;
}

StripeState stripe_step(const StripeState& s, const LmVector<8>& h) {
  StripeState out = s;
  out.T_cell_ranger.translation() += h.head<3>();
  const Vector3d w = h.segment<3>(3);
  const double angle = w.norm();
  if (angle > 0.0) {
    out.T_cell_ranger.linear() =
        s.T_cell_ranger.linear() * Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
  }
  Vector3d u1, u2;
  axis_tangents(s.axis, u1, u2);
  out.axis = (s.axis + h[6] * u1 + h[7] * u2).normalized();
  return out;
}

}  // namespace

StripeRefinement refine_stripe(const StripeState& start, const std::vector<StripePlanePoint>& pts,
                               const std::array<CubePlane, 6>& planes, const LmOptions& options) {
  return levenberg_marquardt<8>(
      start, options, [&](const StripeState& s) { return linearise(s, pts, planes); }, stripe_step,
      [](const StripeState& s) { return s.T_cell_ranger.translation().norm(); });
}

}  // namespace rangefit::calib
