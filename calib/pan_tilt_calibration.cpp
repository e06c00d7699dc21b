#include "calib/pan_tilt_calibration.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "calib/axis_rotations.hpp"
#include "detect/common/normals.hpp"
#include "detect/common/point_cloud.hpp"

namespace rangefit::calib {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kMinTiltSpreadRad = 0.1 * 3.14159265358979323846 / 180.0;

struct HeadState {
  Vector3d t_s = Vector3d::Zero(), t_w = Vector3d::Zero();
  double pan_zero = 0.0, tilt_zero = 0.0;
};

// A valid sample: ranger point and reported angles.
struct RawPoint {
  Vector3d q;
  double pan = 0.0, tilt = 0.0;
};

struct Sweep {
  std::vector<RawPoint> pts;
  GridLayout grid;
};

struct PlanePoint {
  RawPoint raw;
  int plane = 0;
};

Sweep collect_head_sweep(const PanTiltSweep& in) {
  Sweep s;
  int cols = 0;
  for (const auto& p : in.profiles) cols = std::max(cols, static_cast<int>(p.z_mm.size()));
  s.grid.rows = static_cast<int>(in.profiles.size());
  s.grid.cols = cols;
  s.grid.index.assign(static_cast<std::size_t>(s.grid.rows) * static_cast<std::size_t>(cols), -1);
  for (std::size_t r = 0; r < in.profiles.size(); ++r) {
    const auto& p = in.profiles[r];
    const hal::PanTiltSample& a = in.angles[r];
    if (!a.valid || !std::isfinite(a.pan_rad) || !std::isfinite(a.tilt_rad)) continue;
    for (std::size_t k = 0; k < p.z_mm.size() && k < p.x_mm.size(); ++k) {
      if (!std::isfinite(p.z_mm[k]) || !std::isfinite(p.x_mm[k])) continue;
      s.grid.index[r * static_cast<std::size_t>(cols) + k] =
          static_cast<std::int32_t>(s.pts.size());
      s.pts.push_back({Vector3d(p.x_mm[k], 0.0, p.z_mm[k]), a.pan_rad, a.tilt_rad});
    }
  }
  return s;
}

// Eq. 5.7.
Vector3d to_world(const HeadState& s, const RawPoint& p) {
  return rot_x(p.pan - s.pan_zero) * rot_y(p.tilt - s.tilt_zero) * (p.q + s.t_s) + s.t_w;
}

LmLinearisation<8> linearise(const HeadState& s, const std::vector<PlanePoint>& pts,
                             const std::array<CubePlane, 6>& planes) {
  LmRowSum<8> sum;
  for (const PlanePoint& p : pts) {
    const CubePlane& pl = planes[static_cast<std::size_t>(p.plane)];
    const Vector3d& n = pl.normal;
    const Matrix3d Rx = rot_x(p.raw.pan - s.pan_zero);
    const Matrix3d Ry = rot_y(p.raw.tilt - s.tilt_zero);
    const Vector3d u = Ry * (p.raw.q + s.t_s);  // after the tilt
    const Vector3d v = Rx * u;                  // after the pan
    const double r = n.dot(v + s.t_w) - pl.offset_mm;
    LmVector<8> j;
    j.head<3>() = (Rx * Ry).transpose() * n;
    j.segment<3>(3) = n;
    // d R_x(a) / da = [e_x]x R_x(a), and a = pan - pan_zero; the same for the tilt inside.
    j[6] = -n.dot(Vector3d::UnitX().cross(v));
    j[7] = -n.dot(Rx * Vector3d::UnitY().cross(u));
    sum.add(j, r);
  }
  return sum.take();
}

HeadState head_step(const HeadState& s, const LmVector<8>& h) {
  HeadState o = s;
  o.t_s += h.head<3>();
  o.t_w += h.segment<3>(3);
  o.pan_zero += h[6];
  o.tilt_zero += h[7];
  return o;
}

// Median distance between neighbouring profiles' points (same fan ray): a pan step of a few
// tenths of a degree is several mm at the cube, and a patch smaller than that has no normal.
double profile_spacing(const PointCloud& c) {
  std::vector<double> d;
  for (int r = 0; r + 1 < c.grid.rows; ++r) {
    for (int k = 0; k < c.grid.cols; k += 8) {
      const std::int32_t a = c.grid.at(r, k), b = c.grid.at(r + 1, k);
      if (a >= 0 && b >= 0) d.push_back((c.points[a] - c.points[b]).norm());
    }
  }
  if (d.empty()) return 0.0;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

// The six planes of one sweep under the estimate, as points tagged with their true plane;
// `missing` counts the planes not found.
std::vector<PlanePoint> plane_points(const Sweep& sw, const HeadState& st,
                                     const PanTiltCalibrationInput& in,
                                     const std::array<CubePlane, 6>& truth, const Vector3d& towards,
                                     const PanTiltCalibrationOptions& o, std::uint64_t seed,
                                     int& missing) {
  PointCloud cloud;
  cloud.grid = sw.grid;
  cloud.points.resize(sw.pts.size());
  const double keep_radius = 0.5 * std::sqrt(3.0) * in.cube.edge_mm + o.crop_margin_mm;
  std::vector<std::uint32_t> near;
  for (std::size_t i = 0; i < sw.pts.size(); ++i) {
    cloud.points[i] = to_world(st, sw.pts[i]);
    if ((cloud.points[i] - in.T_world_cube.translation()).norm() <= keep_radius) {
      near.push_back(static_cast<std::uint32_t>(i));
    }
  }
  NormalOptions no;
  no.radius = std::max(o.normal_radius_mm, 1.5 * profile_spacing(cloud));
  no.view_dir = towards.normalized();
  const NormalEstimate estimate = estimate_normals_organised(cloud, near, no);
  std::vector<Vector3d> normals(sw.pts.size(), Vector3d::Zero());
  for (std::size_t i = 0; i < near.size(); ++i) normals[near[i]] = estimate.normals[i];
  PlaneExtractionOptions po = o.planes;
  po.seed = seed;
  const auto planes = extract_cube_planes(cloud.points, normals, truth, po);
  std::vector<PlanePoint> out;
  for (std::size_t j = 0; j < 6; ++j) {
    if (!planes[j].found) {
      ++missing;
      continue;
    }
    for (const std::uint32_t i : planes[j].inliers) out.push_back({sw.pts[i], static_cast<int>(j)});
  }
  return out;
}

}  // namespace

PanTiltCalibrationResult calibrate_pan_tilt(const PanTiltCalibrationInput& input,
                                            const hal::PanTiltGeometry& start,
                                            const PanTiltCalibrationOptions& options) {
  PanTiltCalibrationResult result;
  result.geometry = start;
  std::vector<Sweep> sweeps;
  std::size_t total = 0;
  for (std::size_t k = 0; k < input.sweeps.size(); ++k) {
    const PanTiltSweep& s = input.sweeps[k];
    if (s.profiles.size() != s.angles.size()) {
      result.reason = "sweep " + std::to_string(k + 1) + ": profiles and angles differ in number";
      return result;
    }
    sweeps.push_back(collect_head_sweep(s));
    total += sweeps.back().pts.size();
  }
  if (sweeps.size() < 2) {
    result.reason =
        "need sweeps at two or more tilt angles (got " + std::to_string(sweeps.size()) + ")";
    return result;
  }
  // Tilts a tenth of a degree apart or less are one tilt.
  double tilt_lo = std::numeric_limits<double>::infinity(), tilt_hi = -tilt_lo;
  for (const Sweep& sw : sweeps) {
    for (const RawPoint& p : sw.pts) {
      tilt_lo = std::min(tilt_lo, p.tilt);
      tilt_hi = std::max(tilt_hi, p.tilt);
    }
  }
  if (total > 0 && !(tilt_hi - tilt_lo > kMinTiltSpreadRad)) {
    result.reason = "all sweeps at one tilt angle: need sweeps at two or more tilt angles";
    return result;
  }
  if (total < 6 * options.planes.min_points) {
    result.reason = "too few points in the sweeps (" + std::to_string(total) + ")";
    return result;
  }
  HeadState st{start.t_s_mm, start.t_w_mm, start.pan_zero_rad, start.tilt_zero_rad};
  // The head turns about its centre, so every sweep sees the cube from there.
  const Vector3d towards = st.t_w - input.T_world_cube.translation();
  const std::array<CubePlane, 6> truth = visible_planes(input.cube, input.T_world_cube, towards);

  std::vector<PlanePoint> pts;
  LmOutcome<8, HeadState> fit{st, {}};
  for (int round = 0; round < options.rounds; ++round) {
    pts.clear();
    int missing = 0;
    for (std::size_t k = 0; k < sweeps.size(); ++k) {
      const auto seed = options.planes.seed + 1000u * static_cast<std::uint64_t>(round) + k;
      const auto more = plane_points(sweeps[k], st, input, truth, towards, options, seed, missing);
      pts.insert(pts.end(), more.begin(), more.end());
    }
    // A plane may be hidden in one sweep, but far fewer than six a sweep leave the fit loose.
    if (missing > static_cast<int>(sweeps.size()) * 2 ||
        pts.size() < 6 * options.planes.min_points) {
      result.reason = "round " + std::to_string(round + 1) + ": " + std::to_string(missing) +
                      " of " + std::to_string(6 * sweeps.size()) +
                      " cube planes not found (is the cube where --cube-pose says, and in view?)";
      return result;
    }
    fit = levenberg_marquardt<8>(
        st, options.lm, [&](const HeadState& s) { return linearise(s, pts, truth); }, head_step,
        [](const HeadState& s) { return s.t_s.norm() + s.t_w.norm() + 1.0; });
    const double n = static_cast<double>(pts.size());
    if (round == 0) result.initial_rms_mm = std::sqrt(2.0 * fit.initial_cost / n);
    result.lm_iterations += fit.iterations;
    result.rounds.push_back({pts.size(), std::sqrt(2.0 * fit.lin.cost / n)});
    st = fit.x;
  }
  const double n = static_cast<double>(pts.size());
  result.points = pts.size();
  result.rms_mm = std::sqrt(2.0 * fit.lin.cost / n);
  result.geometry.t_s_mm = st.t_s;
  result.geometry.t_w_mm = st.t_w;
  result.geometry.pan_zero_rad = st.pan_zero;
  result.geometry.tilt_zero_rad = st.tilt_zero;
  // Inverted with unit diagonal: the angles' rows are ~(750 mm)^2 times the translations', too
  // far apart for a rank test on the raw matrix.
  const LmVector<8> d = fit.lin.jtj.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  const PanTiltMatrix8d scaled = d.asDiagonal() * fit.lin.jtj * d.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<PanTiltMatrix8d> eig(scaled);
  if (eig.info() != Eigen::Success || !(eig.eigenvalues()[0] > 1e-12 * eig.eigenvalues()[7])) {
    result.reason = "the sweeps do not determine the head (sweep at two or more tilt angles)";
    return result;
  }
  const double sigma2 = 2.0 * fit.lin.cost / std::max(1.0, n - 8.0);
  result.covariance = sigma2 * d.asDiagonal() * scaled.inverse() * d.asDiagonal();
  const LmVector<8> sd = result.covariance.diagonal().cwiseSqrt();
  result.t_s_sigma_mm = sd.head<3>();
  result.t_w_sigma_mm = sd.segment<3>(3);
  result.zero_sigma_rad = sd.tail<2>();
  result.ok = result.covariance.allFinite();
  if (!result.ok) result.reason = "the refinement's normal matrix is singular";
  return result;
}

}  // namespace rangefit::calib
