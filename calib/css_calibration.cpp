#include "calib/css_calibration.hpp"
#include "calib/axis_rotations.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace rangefit::calib {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

struct CssState {
  double omega_zero = 0.0;
  Matrix3d R_m = Matrix3d::Identity();
  Vector3d t_m = Vector3d::Zero();  // x stays 0
  Vector3d centre = Vector3d::Zero();
};

// A sample with its robot pose and axis angle: the joint turns the sensor by R_y(omega -
// omega_zero) = R_y(omega) R_y(-omega_zero), so the part that depends on the sample alone,
// R_base_joint R_y(omega), is taken once and each state adds its R_y(-omega_zero).
struct Prepared {
  Matrix3d B;  // R_base_joint R_y(omega)
  Vector3d t_base_joint;
  Vector3d s;      // sensor-frame point
  Vector3d beam;   // sensor-frame unit beam direction
  double c = 1.0;  // share of the range noise normal to the surface (see set_weights)
};

LmLinearisation<9> linearise(const CssState& st, const std::vector<Prepared>& pts, double radius) {
  LmRowSum<9> sum;
  const Matrix3d Rz = rot_y(-st.omega_zero);
  for (const Prepared& p : pts) {
    const Matrix3d A = p.B * Rz;
    const Vector3d m = st.R_m * p.s + st.t_m;
    const Vector3d x = A * m + p.t_base_joint;
    const Vector3d d = x - st.centre;
    const double len = d.norm();
    if (!(len > 1e-9)) continue;
    const Vector3d u = d / len;
    const double c = p.c;
    const double r = (len - radius) / c;
    const Vector3d Atu = A.transpose() * u;
    LmVector<9> j;
    j[0] = -Atu.dot(Vector3d::UnitY().cross(m));  // d/d omega_zero of R_y(omega - omega_zero)
    j[1] = Atu.y();
    j[2] = Atu.z();
    j.segment<3>(3) = p.s.cross(st.R_m.transpose() * Atu);  // R_m exp([w]x)
    j.tail<3>() = -u;
    j /= c;
    sum.add(j, r);
  }
  return sum.take();
}

// The noise is along the beam; its share normal to the surface is |u . beam|, so each residual
// is scaled back to a range error (held at most 5x) and the fit is the maximum-likelihood one for
// range noise, with a sigma estimate that holds for every parameter. The shares are taken at a
// fixed state, so the cost the loop minimises is a plain sum of squares.
void set_weights(const CssState& st, std::vector<Prepared>& pts) {
  const Matrix3d Rz = rot_y(-st.omega_zero);
  for (Prepared& p : pts) {
    const Matrix3d A = p.B * Rz;
    const Vector3d x = A * (st.R_m * p.s + st.t_m) + p.t_base_joint;
    const Vector3d u = (x - st.centre).normalized();
    p.c = std::max(0.2, std::abs(u.dot(A * (st.R_m * p.beam))));
    if (!std::isfinite(p.c)) p.c = 1.0;
  }
}

// Moves the samples within 4 robust sigma of the sphere at st to the front, in order; returns
// how many. A floor of 1 um keeps noise-free scans whole.
std::size_t trim_off_sphere(const CssState& st, std::vector<Prepared>& pts, double radius) {
  std::vector<double> r(pts.size());
  const Matrix3d Rz = rot_y(-st.omega_zero);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Prepared& p = pts[i];
    const Matrix3d A = p.B * Rz;
    r[i] = std::abs((A * (st.R_m * p.s + st.t_m) + p.t_base_joint - st.centre).norm() - radius);
  }
  std::vector<double> sorted = r;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                   sorted.end());
  const double limit = std::max(1e-3, 4.0 * 1.4826 * sorted[sorted.size() / 2]);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (r[i] <= limit) pts[kept++] = pts[i];
  }
  return kept;
}

CssState css_step(const CssState& s, const LmVector<9>& h) {
  CssState o = s;
  o.omega_zero += h[0];
  o.t_m.y() += h[1];
  o.t_m.z() += h[2];
  const Vector3d w = h.segment<3>(3);
  if (w.norm() > 0.0)
    o.R_m = s.R_m * Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
  o.centre += h.tail<3>();
  return o;
}

}  // namespace

Eigen::Isometry3d nominal_mount(const hal::CssGeometry& g) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(g.eta_rad, Vector3d::UnitX()).toRotationMatrix();
  T.translation() = Vector3d(0.0, 0.0, g.pivot_radius_mm);
  return T;
}

CssCalibrationResult calibrate_css_mount(std::span<const CssSphereScan> scans,
                                         const hal::CssGeometry& start, double omega_zero_start,
                                         const CssCalibrationOptions& options) {
  CssCalibrationResult result;
  std::vector<Prepared> pts;
  for (const CssSphereScan& scan : scans) {
    for (const CssSample& s : scan.samples) {
      if (!std::isfinite(s.omega_rad) || !std::isfinite(s.beam_rad) || !std::isfinite(s.range_mm)) {
        continue;
      }
      pts.push_back({scan.T_base_joint.linear() * rot_y(s.omega_rad),
                     scan.T_base_joint.translation(), start.sensor_point(s.beam_rad, s.range_mm),
                     start.beam_direction(s.beam_rad), 1.0});
    }
  }
  if (scans.size() < 3 || pts.size() < 50) {
    result.reason = "need scans from at least 3 robot poses with 50 samples in all (got " +
                    std::to_string(scans.size()) + " scans, " + std::to_string(pts.size()) +
                    " samples)";
    return result;
  }
  CssState st;
  const Eigen::Isometry3d T0 = nominal_mount(start);
  st.omega_zero = omega_zero_start;
  st.R_m = T0.linear();
  st.t_m = T0.translation();
  st.t_m.x() = 0.0;
  // Start centre: the mean of every sample under the start mount, pushed back by the radius
  // along the mean viewing direction (the samples lie on the near cap).
  Vector3d mean = Vector3d::Zero(), view = Vector3d::Zero();
  const Matrix3d Rz0 = rot_y(-st.omega_zero);
  for (const Prepared& p : pts) {
    const Matrix3d A = p.B * Rz0;
    mean += A * (st.R_m * p.s + st.t_m) + p.t_base_joint;
    view += A * st.R_m.col(2);
  }
  mean /= static_cast<double>(pts.size());
  st.centre = mean - options.sphere_radius_mm * view.normalized();
  // First unweighted from the start, then weighted at that fit (calib: set_weights).
  // A fit from a state that is already the optimum of a nearby problem (fewer samples, other
  // weights) starts almost undamped: with the start's damping it would creep there in ~18 steps.
  LmOptions near = options.lm;
  near.tau = std::min(near.tau, 1e-9);
  auto solve = [&](const std::vector<Prepared>& set, const CssState& from, const LmOptions& lm) {
    return levenberg_marquardt<9>(
        from, lm, [&](const CssState& s) { return linearise(s, set, options.sphere_radius_mm); },
        css_step, [](const CssState& s) { return s.t_m.norm() + s.centre.norm(); });
  };
  // The far start is brought in on an even spread of ~4,000 samples, whose optimum lies within
  // the noise of the whole set's; the whole set then takes a few undamped steps from there.
  const double start_cost = linearise(st, pts, options.sphere_radius_mm).cost;
  std::vector<Prepared> spread;
  const std::size_t stride = std::max<std::size_t>(1, pts.size() / 4000);
  for (std::size_t i = 0; i < pts.size(); i += stride) spread.push_back(pts[i]);
  const auto coarse = solve(spread, st, options.lm);
  auto first = solve(pts, coarse.x, near);
  first.iterations += coarse.iterations;
  // Samples that are not on the sphere (its stand, the table, a stray reflection) would pull the
  // fit: up to three times, the samples beyond 4 robust sigma (1.4826 MAD) of the fit are left
  // out and, when they were more than the noise's own tail (0.1 %), the fit is redone from
  // where it was.
  for (int pass = 0; pass < 3; ++pass) {
    const std::size_t before = pts.size();
    const std::size_t kept = trim_off_sphere(first.x, pts, options.sphere_radius_mm);
    result.rejected += before - kept;
    pts.resize(kept);
    if (pts.size() < 50) {
      result.reason = "too few samples on the sphere (" + std::to_string(pts.size()) + ")";
      return result;
    }
    if ((before - kept) * 1000 <= before) break;
    first = solve(pts, first.x, near);
  }
  set_weights(first.x, pts);
  auto fit = solve(pts, first.x, near);
  fit.initial_cost = start_cost;
  fit.iterations += first.iterations;
  const double n = static_cast<double>(pts.size());
  result.samples = pts.size();
  result.initial_rms_mm = std::sqrt(2.0 * fit.initial_cost / n);
  result.rms_mm = std::sqrt(2.0 * fit.lin.cost / n);
  result.iterations = fit.iterations;
  const CssState& e = fit.x;
  result.omega_zero_rad = e.omega_zero;
  result.T_joint_css.linear() = e.R_m;
  result.T_joint_css.translation() = e.t_m;
  result.sphere_centre_mm = e.centre;
  const double sigma2 = 2.0 * fit.lin.cost / std::max(1.0, n - 9.0);
  const Eigen::FullPivLU<Matrix9d> lu(fit.lin.jtj);
  if (!lu.isInvertible()) {
    result.reason =
        "the poses do not determine the mount (turn the robot's wrist between the scans)";
    return result;
  }
  result.covariance = sigma2 * lu.inverse();
  // What a bore measurement at omega = 0 inherits: sensor origin o = R_y(-omega_zero) t_m and
  // axis a = R_y(-omega_zero) R_m e_z in the joint frame, linearised in the parameters.
  const Matrix3d Rz = rot_y(-e.omega_zero);
  Eigen::Matrix<double, 3, 9> Jo = Eigen::Matrix<double, 3, 9>::Zero();
  Eigen::Matrix<double, 3, 9> Ja = Eigen::Matrix<double, 3, 9>::Zero();
  Jo.col(0) = -Rz * Vector3d::UnitY().cross(e.t_m);
  Jo.col(1) = Rz.col(1);
  Jo.col(2) = Rz.col(2);
  const Vector3d a = Rz * e.R_m.col(2);
  Ja.col(0) = -Vector3d::UnitY().cross(a);
  for (int k = 0; k < 3; ++k) {
    Ja.col(3 + k) = Rz * e.R_m * Vector3d::Unit(k).cross(Vector3d::UnitZ());
  }
  result.origin_sigma_mm = (Jo * result.covariance * Jo.transpose()).diagonal().cwiseSqrt();
  result.axis_sigma_rad = std::sqrt((Ja * result.covariance * Ja.transpose()).trace());
  // Nearest form of eq. 4.17: eta from the turn of the sensor's z about x, R = |t_m|.
  const Vector3d z = e.R_m.col(2);
  result.eta_rad = std::atan2(-z.y(), z.z());
  result.pivot_radius_mm = e.t_m.norm();
  result.mount_off_form_mm = (e.t_m - Vector3d(0.0, 0.0, result.pivot_radius_mm)).norm();
  const Matrix3d R_form = Eigen::AngleAxisd(result.eta_rad, Vector3d::UnitX()).toRotationMatrix();
  result.mount_off_form_rad = Eigen::AngleAxisd(R_form.transpose() * e.R_m).angle();
  result.ok = result.covariance.allFinite();
  if (!result.ok) result.reason = "the covariance is not finite";
  return result;
}

}  // namespace rangefit::calib
