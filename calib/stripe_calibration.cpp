#include "calib/stripe_calibration.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <numbers>

#include "calib/stripe_refine.hpp"
#include "detect/common/normals.hpp"
#include "detect/common/point_cloud.hpp"

namespace rangefit::calib {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// The sweep's valid samples: ranger point, axis position, grid cell.
struct PlaneSamples {
  std::vector<Vector3d> q;
  std::vector<double> s;
  GridLayout grid;
};

PlaneSamples collect_plane_samples(const StripeCalibrationInput& in) {
  PlaneSamples raw;
  int cols = 0;
  for (const auto& p : in.profiles) cols = std::max(cols, static_cast<int>(p.z_mm.size()));
  raw.grid.rows = static_cast<int>(in.profiles.size());
  raw.grid.cols = cols;
  raw.grid.index.assign(static_cast<std::size_t>(raw.grid.rows) * static_cast<std::size_t>(cols),
                        -1);
  for (std::size_t r = 0; r < in.profiles.size(); ++r) {
    const auto& p = in.profiles[r];
    for (std::size_t k = 0; k < p.z_mm.size() && k < p.x_mm.size(); ++k) {
      if (!std::isfinite(p.z_mm[k]) || !std::isfinite(p.x_mm[k])) continue;
      raw.grid.index[r * static_cast<std::size_t>(cols) + k] =
          static_cast<std::int32_t>(raw.q.size());
      raw.q.emplace_back(p.x_mm[k], 0.0, p.z_mm[k]);
      raw.s.push_back(in.axis_mm[r]);
    }
  }
  return raw;
}

StripeState state_of(const hal::StripeCellGeometry& g) {
  return {g.T_cell_ranger(), g.axis_direction_cell.normalized()};
}

Vector3d to_table(const StripeState& st, const Vector3d& q, double s) {
  return st.T_cell_ranger * q - s * st.axis;
}

// Raw coordinates (x, z, s) of a table point under the estimate: the axis position at which it
// pierces the laser plane y_ranger = 0, and where in that plane.
Vector3d to_raw(const StripeState& st, const Vector3d& X) {
  const Vector3d n = st.T_cell_ranger.linear().col(1);
  const Vector3d t = st.T_cell_ranger.translation();
  const double s = n.dot(t - X) / n.dot(st.axis);
  const Vector3d q = st.T_cell_ranger.inverse() * (X + s * st.axis);
  return {q.x(), q.z(), s};
}

// The thesis's linear model from the corners' raw coordinates and true positions.
bool solve_linear(const std::array<Vector3d, 8>& raw, const std::array<Vector3d, 8>& X,
                  const StripeState& previous, StripeState& out) {
  // Camera-independent geometry: the piercing point X_c + s_c d is on n . P = h, so
  // n . X_c + s_c k - h = 0 with k = n . d; the null vector of the 8 x 5 system.
  Eigen::Matrix<double, 8, 5> A;
  for (int c = 0; c < 8; ++c) {
    A.row(c) << X[c].transpose(), raw[c].z(), -1.0;
  }
  const Eigen::JacobiSVD<Eigen::Matrix<double, 8, 5>> svd(A, Eigen::ComputeFullV);
  Eigen::Matrix<double, 5, 1> v = svd.matrixV().col(4);
  const double norm_n = v.head<3>().norm();
  if (!(norm_n > 1e-12)) return false;
  v /= norm_n;
  if (v.head<3>().dot(previous.T_cell_ranger.linear().col(1)) < 0.0) v = -v;
  const Vector3d n = v.head<3>();
  const double k = v[3], h = v[4];
  // In-plane basis, e1 near the previous laser line so M stays close to a rotation by 0.
  Vector3d e1 = previous.T_cell_ranger.linear().col(0);
  e1 = (e1 - e1.dot(n) * n).normalized();
  const Vector3d e2 = n.cross(e1);
  Eigen::Matrix<double, 3, 2> E;
  E << e1, e2;
  // Per camera: M (2 x 3) maps (x, z, 1) onto the plane coordinates of the piercing point
  // E^T (X_c + s_c a_perp); unknowns M and the in-plane part a of d, 16 equations.
  Eigen::Matrix<double, 16, 8> B = Eigen::Matrix<double, 16, 8>::Zero();
  Eigen::Matrix<double, 16, 1> b;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector2d u = E.transpose() * X[c];
    for (int i = 0; i < 2; ++i) {
      B(2 * c + i, 3 * i + 0) = raw[c].x();
      B(2 * c + i, 3 * i + 1) = raw[c].y();
      B(2 * c + i, 3 * i + 2) = 1.0;
      B(2 * c + i, 6 + i) = -raw[c].z();
      b[2 * c + i] = u[i];
    }
  }
  const Eigen::Matrix<double, 8, 1> m = B.colPivHouseholderQr().solve(b);
  if (!m.allFinite()) return false;
  Eigen::Matrix2d M;
  M << m[0], m[1], m[3], m[4];
  // Nearest rigid map: the ranger's x and z axes in the plane.
  const Eigen::JacobiSVD<Eigen::Matrix2d> s2(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix2d Q = s2.matrixU() * s2.matrixV().transpose();
  Matrix3d R;
  R.col(0) = E * Q.col(0);
  R.col(2) = E * Q.col(1);
  R.col(1) = R.col(2).cross(R.col(0));
  out.T_cell_ranger = Eigen::Isometry3d::Identity();
  out.T_cell_ranger.linear() = R;
  out.T_cell_ranger.translation() = h * n + E * Eigen::Vector2d(m[2], m[5]);
  out.axis = (k * n + E * Eigen::Vector2d(m[6], m[7])).normalized();
  return out.T_cell_ranger.matrix().allFinite() && out.axis.allFinite();
}

hal::StripeCellGeometry geometry_of(const hal::StripeCellGeometry& start, const StripeState& st) {
  hal::StripeCellGeometry g = start;
  g.ranger_position_cell_mm = st.T_cell_ranger.translation();
  g.ranger_rpy_cell_rad = rpy_of(st.T_cell_ranger.linear(), start.ranger_rpy_cell_rad);
  g.axis_direction_cell = st.axis;
  return g;
}

}  // namespace

Eigen::Vector3d rpy_of(const Eigen::Matrix3d& R, const Eigen::Vector3d& near) {
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  double roll = std::atan2(R(2, 1), R(2, 2));
  double yaw = std::atan2(R(1, 0), R(0, 0));
  constexpr double k2Pi = 2.0 * std::numbers::pi;
  while (roll - near.x() > std::numbers::pi) roll -= k2Pi;
  while (roll - near.x() < -std::numbers::pi) roll += k2Pi;
  while (yaw - near.z() > std::numbers::pi) yaw -= k2Pi;
  while (yaw - near.z() < -std::numbers::pi) yaw += k2Pi;
  return {roll, pitch, yaw};
}

StripeCalibrationResult calibrate_stripe_cell(const StripeCalibrationInput& input,
                                              const hal::StripeCellGeometry& start,
                                              const StripeCalibrationOptions& options) {
  StripeCalibrationResult result;
  result.geometry = start;
  if (input.profiles.size() != input.axis_mm.size()) {
    result.reason = "profiles and axis positions differ in number";
    return result;
  }
  const PlaneSamples raw = collect_plane_samples(input);
  if (raw.q.size() < 6 * options.planes.min_points) {
    result.reason = "too few points in the sweep (" + std::to_string(raw.q.size()) + ")";
    return result;
  }
  StripeState st = state_of(start);
  // The sensor looks at the cube from the ranger's side at mid-sweep; the true planes and
  // corners follow from the fixture's pose.
  const double mid = 0.5 * (input.axis_mm.front() + input.axis_mm.back());
  const Vector3d towards = to_table(st, Vector3d::Zero(), mid) - input.T_table_cube.translation();
  const std::array<CubePlane, 6> truth = visible_planes(input.cube, input.T_table_cube, towards);
  std::array<Vector3d, 8> X;
  for (int c = 0; c < 8; ++c) X[c] = corner_point(truth, c);

  PointCloud cloud;
  cloud.grid = raw.grid;
  // Only points near the cube take part: the rest (the table, the fixture) cost time and
  // offer RANSAC wrong planes. The start is off by a few cm at most.
  const double keep_radius = 0.5 * std::sqrt(3.0) * input.cube.edge_mm + options.crop_margin_mm;
  std::array<ExtractedPlane, 6> planes;
  for (int round = 0; round < options.rounds; ++round) {
    cloud.points.resize(raw.q.size());
    std::vector<std::uint32_t> near;
    for (std::size_t i = 0; i < raw.q.size(); ++i) {
      cloud.points[i] = to_table(st, raw.q[i], raw.s[i]);
      if ((cloud.points[i] - input.T_table_cube.translation()).norm() <= keep_radius) {
        near.push_back(static_cast<std::uint32_t>(i));
      }
    }
    NormalOptions no;
    no.radius = options.normal_radius_mm;
    no.view_dir = towards.normalized();
    const NormalEstimate estimate = estimate_normals_organised(cloud, near, no);
    std::vector<Vector3d> normals(raw.q.size(), Vector3d::Zero());
    for (std::size_t i = 0; i < near.size(); ++i) normals[near[i]] = estimate.normals[i];
    PlaneExtractionOptions po = options.planes;
    po.seed += static_cast<std::uint64_t>(round);
    planes = extract_cube_planes(cloud.points, normals, truth, po);
    StripeRound info;
    for (std::size_t j = 0; j < 6; ++j) {
      if (!planes[j].found) {
        result.reason = "round " + std::to_string(round + 1) + ": plane " + std::to_string(j) +
                        " (" + (truth[j].outer ? "outer" : "inner") + " face, cube axis " +
                        std::to_string(truth[j].axis) + ") not found";
        return result;
      }
      info.plane_points[j] = planes[j].inliers.size();
      info.plane_rms_mm[j] = planes[j].rms_mm;
    }
    std::array<Vector3d, 8> corners_raw;
    for (int c = 0; c < 8; ++c) {
      std::array<CubePlane, 6> measured;
      for (std::size_t j = 0; j < 6; ++j) {
        measured[j] = {planes[j].normal, planes[j].offset_mm, truth[j].axis, truth[j].outer};
      }
      corners_raw[c] = to_raw(st, corner_point(measured, c));
      if (!corners_raw[c].allFinite()) {
        result.reason = "corner " + std::to_string(c) + " not determined";
        return result;
      }
    }
    StripeState next;
    if (!solve_linear(corners_raw, X, st, next)) {
      result.reason = "round " + std::to_string(round + 1) + ": the linear model is singular";
      return result;
    }
    st = next;
    double sum = 0.0;
    for (int c = 0; c < 8; ++c) {
      const Vector3d& r = corners_raw[c];
      sum += (to_table(st, Vector3d(r.x(), 0.0, r.y()), r.z()) - X[c]).squaredNorm();
    }
    info.corner_rms_mm = std::sqrt(sum / 8.0);
    result.rounds.push_back(info);
  }

  std::vector<StripePlanePoint> pts;
  for (std::size_t j = 0; j < 6; ++j) {
    for (const std::uint32_t i : planes[j].inliers) {
      pts.push_back({raw.q[i], raw.s[i], static_cast<int>(j)});
    }
  }
  const StripeRefinement fit = refine_stripe(st, pts, truth, options.lm);
  const double n = static_cast<double>(pts.size());
  result.points = pts.size();
  result.initial_rms_mm = std::sqrt(2.0 * fit.initial_cost / n);
  result.rms_mm = std::sqrt(2.0 * fit.lin.cost / n);
  result.lm_iterations = fit.iterations;
  const double sigma2 = 2.0 * fit.lin.cost / std::max(1.0, n - 8.0);
  result.covariance = sigma2 * fit.lin.jtj.inverse();
  const Eigen::Matrix<double, 8, 1> sd = result.covariance.diagonal().cwiseSqrt();
  result.position_sigma_mm = sd.head<3>();
  result.rotation_sigma_rad = sd.segment<3>(3);
  result.axis_sigma_rad = sd.tail<2>();
  result.geometry = geometry_of(start, fit.x);
  result.ok = result.covariance.allFinite();
  if (!result.ok) result.reason = "the refinement's normal matrix is singular";
  return result;
}

}  // namespace rangefit::calib
