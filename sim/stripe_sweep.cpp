#include "sim/stripe_sweep.hpp"
#include "detect/common/angles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace rangefit::sim {
namespace {

constexpr double kHeadArmMm = 60.0;  // pan-tilt: the fan apex this far ahead of the turn axis
constexpr int kMaxRays = 2048;
constexpr int kMinRays = 16;

Eigen::Vector3d normal_of(const Eigen::Vector3d& line, const Eigen::Vector3d& centre) {
  return line.cross(centre).normalized();
}

}  // namespace

ProfilePose StripeSweep::pose(double s) const {
  ProfilePose p;
  // The head turns the whole ranger; the cell's table moves it without turning.
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  if (kind == SensorView::Kind::kRotarySweep) {
    R = Eigen::AngleAxisd(s, direction).toRotationMatrix();
    p.apex = pivot + R * (apex0 - pivot);
  } else {
    p.apex = apex0 + s * direction;
  }
  p.centre = R * centre0;
  p.line = R * line0;
  p.camera = p.apex + R * camera_offset0;
  if (second_camera_offset0.squaredNorm() > 0.0)
    p.second_camera = p.apex + R * second_camera_offset0;
  p.normal = normal_of(p.line, p.centre);
  return p;
}

double StripeSweep::position_of(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d n = normal_of(line0, centre0);
  if (kind != SensorView::Kind::kRotarySweep) {
    const double nd = n.dot(direction);
    return std::abs(nd) < 1e-12 ? std::numeric_limits<double>::quiet_NaN() : n.dot(p - apex0) / nd;
  }
  // R(t) n . (p - c) = n . (o - c), as in detect/sensor_view.cpp; the root nearest 0.
  const Eigen::Vector3d& a = direction;
  const Eigen::Vector3d q = p - pivot;
  const Eigen::Vector3d n_perp = n - n.dot(a) * a;
  const double A = n.dot(a) * a.dot(q), B = n_perp.dot(q), C = a.cross(n).dot(q);
  const double k = n.dot(apex0 - pivot), r = std::hypot(B, C);
  if (r < 1e-12 || std::abs(k - A) > r) return std::numeric_limits<double>::quiet_NaN();
  const double phi = std::atan2(C, B), delta = std::acos(std::clamp((k - A) / r, -1.0, 1.0));
  double best = std::numeric_limits<double>::quiet_NaN();
  for (double t : {phi + delta, phi - delta}) {
    t = std::remainder(t, 2.0 * std::numbers::pi);
    if (std::isnan(best) || std::abs(t) < std::abs(best)) best = t;
  }
  return best;
}

SensorView StripeSweep::view() const {
  SensorView v;
  v.kind = kind;
  v.origin = apex0;
  v.plane_normal = normal_of(line0, centre0);
  v.camera_offset = camera_offset0;
  v.second_camera_offset = second_camera_offset0;
  v.direction = direction;
  v.pivot = pivot;
  const double pad = 1e-9 * std::abs(sweep_step);
  v.sweep_min = std::min(position(0), position(profiles - 1)) - pad;
  v.sweep_max = std::max(position(0), position(profiles - 1)) + pad;
  return v;
}

StripeSweep make_sweep(const ScanSetup& setup, const Eigen::AlignedBox3d& cover) {
  StripeSweep w;
  const double H = setup.laser_height_mm, tilt = setup.laser_tilt_deg * kDeg;
  const double tri = setup.triangulation_deg * kDeg;
  const double side = setup.camera_side < 0 ? -1.0 : 1.0;
  const Eigen::Vector3d aim(cover.center().x(), cover.center().y(), 0.0);
  w.centre0 = Eigen::Vector3d(0.0, std::sin(tilt), -std::cos(tilt));
  w.line0 = Eigen::Vector3d::UnitX();
  double range_mm = H;  // apex to the scene centre
  if (setup.pan_tilt) {
    // The head looks at the scene centre from -y; its laser line lies along the turn axis (x),
    // so turning sweeps the plane (thesis eq. 5.7: pan about x). Camera beside the plane.
    range_mm = H / std::cos(tilt);
    w.kind = SensorView::Kind::kRotarySweep;
    w.apex0 = aim - range_mm * w.centre0;
    w.pivot = w.apex0 - kHeadArmMm * w.centre0;
    w.direction = Eigen::Vector3d::UnitX();
    w.camera_offset0 = side * range_mm * std::tan(tri) * normal_of(w.line0, w.centre0);
    if (setup.two_cameras) w.second_camera_offset0 = -w.camera_offset0;
    w.sweep_step = setup.step_mm / range_mm;
  } else {
    // The camera at the apex's height, its ray to the scene centre at `tri` from the laser's.
    w.kind = SensorView::Kind::kLinearSweep;
    w.apex0 = aim + Eigen::Vector3d(0.0, -H * std::tan(tilt), H);
    w.direction = Eigen::Vector3d::UnitY();
    const auto camera_at = [&](double on_side) {
      return Eigen::Vector3d(0.0, H * (std::tan(on_side * tri - tilt) + std::tan(tilt)), 0.0);
    };
    w.camera_offset0 = camera_at(side);
    if (setup.two_cameras) w.second_camera_offset0 = camera_at(-side);
    w.sweep_step = setup.step_mm;
  }
  // Sweep across the box: its extreme positions are at corners (planes of a linear sweep are
  // parallel, those of the head all hold its axis).
  double s_lo = std::numeric_limits<double>::infinity(), s_hi = -s_lo;
  for (int c = 0; c < 8; ++c) {
    const double s = w.position_of(cover.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)));
    if (std::isnan(s)) continue;
    s_lo = std::min(s_lo, s);
    s_hi = std::max(s_hi, s);
  }
  if (!(s_hi >= s_lo)) s_lo = s_hi = 0.0;
  w.sweep_start = s_lo;
  w.profiles = static_cast<int>(std::ceil((s_hi - s_lo) / w.sweep_step)) + 1;
  // Fan: the widest angle any point of the box's edges takes in the plane that reaches it.
  double widest = 0.0;
  for (int a = 0; a < 8; ++a) {
    for (int b = a + 1; b < 8; ++b) {
      const Eigen::Vector3d pa = cover.corner(static_cast<Eigen::AlignedBox3d::CornerType>(a));
      const Eigen::Vector3d pb = cover.corner(static_cast<Eigen::AlignedBox3d::CornerType>(b));
      if (((pa - pb).array() != 0.0).count() != 1) continue;  // not an edge
      for (int i = 0; i <= 8; ++i) {
        const Eigen::Vector3d p = pa + (pb - pa) * (i / 8.0);
        const double s = w.position_of(p);
        if (std::isnan(s)) continue;
        const ProfilePose pose = w.pose(s);
        const Eigen::Vector3d d = p - pose.apex;
        widest = std::max(widest, std::abs(std::atan2(pose.line.dot(d), pose.centre.dot(d))));
      }
    }
  }
  w.fan_rad = std::clamp(2.0 * widest + 1.0 * kDeg, 2.0 * kDeg, 170.0 * kDeg);
  w.rays = rays_for(setup, w.profiles);
  return w;
}

int rays_for(const ScanSetup& setup, int profiles) {
  const int cap = setup.points_per_profile > 0 ? setup.points_per_profile : kMaxRays;
  const double budget = std::floor(setup.max_points / std::max(1, profiles));
  return std::max(kMinRays, static_cast<int>(std::min<double>(cap, budget)));
}

}  // namespace rangefit::sim
