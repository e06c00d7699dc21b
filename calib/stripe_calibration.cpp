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

PlaneSamples collect_plane_samples(const StripeCameraInput& in) {
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

using Corners = std::array<Vector3d, 8>;

// The thesis's linear model from the corners' raw coordinates (x, z, s) and true positions X,
// per camera: one laser plane and axis for all of them, M per camera. With one camera this is
// one camera's calibration; the caller averages s over the cameras for the joint round.
bool solve_linear(std::span<const Corners> raw, std::span<const Corners> X,
                  const StripeState& previous, std::vector<StripeState>& out) {
  const Eigen::Index m = static_cast<Eigen::Index>(raw.size());
  // Camera-independent geometry: the piercing point X_c + s_c d is on n . P = h, so
  // n . X_c + s_c k - h = 0 with k = n . d; the null vector of the 8m x 5 system.
  Eigen::MatrixXd A(8 * m, 5);
  for (Eigen::Index j = 0; j < m; ++j) {
    for (int c = 0; c < 8; ++c) A.row(8 * j + c) << X[j][c].transpose(), raw[j][c].z(), -1.0;
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  Eigen::Matrix<double, 5, 1> v = svd.matrixV().col(4);
  const double norm_n = v.head<3>().norm();
  if (!(norm_n > 1e-12)) return false;
  v /= norm_n;
  if (v.head<3>().dot(previous.T_cell_ranger.linear().col(1)) < 0.0) v = -v;
  const Vector3d n = v.head<3>();
  const double k = v[3], h = v[4];
  // In-plane basis, e1 near camera 0's laser line so its M stays close to a rotation by 0.
  Vector3d e1 = previous.T_cell_ranger.linear().col(0);
  e1 = (e1 - e1.dot(n) * n).normalized();
  const Vector3d e2 = n.cross(e1);
  Eigen::Matrix<double, 3, 2> E;
  E << e1, e2;
  // Per camera: M (2 x 3) maps (x, z, 1) onto the plane coordinates of the piercing point
  // E^T (X_c + s_c a_perp); unknowns M of each camera and the in-plane part a of d.
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(16 * m, 6 * m + 2);
  Eigen::VectorXd b(16 * m);
  for (Eigen::Index j = 0; j < m; ++j) {
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector2d u = E.transpose() * X[j][c];
      for (int i = 0; i < 2; ++i) {
        const Eigen::Index row = 16 * j + 2 * c + i;
        B(row, 6 * j + 3 * i + 0) = raw[j][c].x();
        B(row, 6 * j + 3 * i + 1) = raw[j][c].y();
        B(row, 6 * j + 3 * i + 2) = 1.0;
        B(row, 6 * m + i) = -raw[j][c].z();
        b[row] = u[i];
      }
    }
  }
  const Eigen::VectorXd sol = B.colPivHouseholderQr().solve(b);
  if (!sol.allFinite()) return false;
  out.assign(raw.size(), {});
  for (Eigen::Index j = 0; j < m; ++j) {
    const auto mj = sol.segment<6>(6 * j);
    Eigen::Matrix2d M;
    M << mj[0], mj[1], mj[3], mj[4];
    // Nearest orthogonal map: the ranger's x and z axes in the plane (a reflection when the
    // camera's frame has the plane's normal the other way).
    const Eigen::JacobiSVD<Eigen::Matrix2d> s2(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Matrix2d Q = s2.matrixU() * s2.matrixV().transpose();
    Matrix3d R;
    R.col(0) = E * Q.col(0);
    R.col(2) = E * Q.col(1);
    R.col(1) = R.col(2).cross(R.col(0));
    StripeState& st = out[static_cast<std::size_t>(j)];
    st.T_cell_ranger = Eigen::Isometry3d::Identity();
    st.T_cell_ranger.linear() = R;
    st.T_cell_ranger.translation() = h * n + E * Eigen::Vector2d(mj[2], mj[5]);
    st.axis = (k * n + E * sol.tail<2>()).normalized();
    if (!st.T_cell_ranger.matrix().allFinite() || !st.axis.allFinite()) return false;
  }
  return true;
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

namespace {

// One camera through the rounds.
struct Camera {
  PlaneSamples raw;
  StripeState st;
  std::array<CubePlane, 6> truth;  // the planes it sees
  Corners X;                       // their corners
  Vector3d towards;                // from the cube towards laser and camera
  std::array<ExtractedPlane, 6> planes;
  Corners corners_raw;
  StripeCalibrationResult result;
};

// Maps the camera's points with its estimate, extracts the six planes and takes their corners
// back to raw coordinates. Empty, or why not.
std::string extract_corners(Camera& cam, const StripeRigInput& in,
                            const StripeCalibrationOptions& options, int round) {
  PointCloud cloud;
  cloud.grid = cam.raw.grid;
  // Only points near the cube take part: the rest (the table, the fixture) cost time and
  // offer RANSAC wrong planes. The start is off by a few cm at most.
  const double keep_radius = 0.5 * std::sqrt(3.0) * in.cube.edge_mm + options.crop_margin_mm;
  cloud.points.resize(cam.raw.q.size());
  std::vector<std::uint32_t> near;
  for (std::size_t i = 0; i < cam.raw.q.size(); ++i) {
    cloud.points[i] = to_table(cam.st, cam.raw.q[i], cam.raw.s[i]);
    if ((cloud.points[i] - in.T_table_cube.translation()).norm() <= keep_radius) {
      near.push_back(static_cast<std::uint32_t>(i));
    }
  }
  NormalOptions no;
  no.radius = options.normal_radius_mm;
  no.view_dir = cam.towards;
  const NormalEstimate estimate = estimate_normals_organised(cloud, near, no);
  std::vector<Vector3d> normals(cam.raw.q.size(), Vector3d::Zero());
  for (std::size_t i = 0; i < near.size(); ++i) normals[near[i]] = estimate.normals[i];
  PlaneExtractionOptions po = options.planes;
  po.seed += static_cast<std::uint64_t>(round);
  cam.planes = extract_cube_planes(cloud.points, normals, cam.truth, po);
  StripeRound info;
  for (std::size_t j = 0; j < 6; ++j) {
    if (!cam.planes[j].found) {
      return "round " + std::to_string(round + 1) + ": plane " + std::to_string(j) + " (" +
             (cam.truth[j].outer ? "outer" : "inner") + " face, cube axis " +
             std::to_string(cam.truth[j].axis) + ") not found";
    }
    info.plane_points[j] = cam.planes[j].inliers.size();
    info.plane_rms_mm[j] = cam.planes[j].rms_mm;
  }
  std::array<CubePlane, 6> measured;
  for (std::size_t j = 0; j < 6; ++j) {
    measured[j] = {cam.planes[j].normal, cam.planes[j].offset_mm, cam.truth[j].axis,
                   cam.truth[j].outer};
  }
  for (int c = 0; c < 8; ++c) {
    cam.corners_raw[c] = to_raw(cam.st, corner_point(measured, c));
    if (!cam.corners_raw[c].allFinite()) return "corner " + std::to_string(c) + " not determined";
  }
  cam.result.rounds.push_back(info);
  return {};
}

// The rms distance of the raw corners, mapped with the camera's new estimate, to the true ones.
double corner_rms(const Camera& cam) {
  double sum = 0.0;
  for (int c = 0; c < 8; ++c) {
    const Vector3d& r = cam.corners_raw[c];
    sum += (to_table(cam.st, Vector3d(r.x(), 0.0, r.y()), r.z()) - cam.X[c]).squaredNorm();
  }
  return std::sqrt(sum / 8.0);
}

// The joint round: each corner's axis position averaged over the cameras that see that corner
// (the same true point), then one laser plane and axis for all.
bool solve_averaged(std::vector<Camera>& cams) {
  std::vector<Corners> raw, X;
  for (const Camera& cam : cams) {
    Corners r = cam.corners_raw;
    for (int c = 0; c < 8; ++c) {
      double sum = 0.0;
      int count = 0;
      for (const Camera& other : cams) {
        for (int o = 0; o < 8; ++o) {
          if ((other.X[o] - cam.X[c]).norm() < 1e-6) {
            sum += other.corners_raw[o].z();
            ++count;
          }
        }
      }
      r[c].z() = sum / count;
    }
    raw.push_back(r);
    X.push_back(cam.X);
  }
  std::vector<StripeState> next;
  if (!solve_linear(raw, X, cams[0].st, next)) return false;
  for (std::size_t k = 0; k < cams.size(); ++k) cams[k].st = next[k];
  return true;
}

}  // namespace

StripeCalibrationResult calibrate_stripe_cell(const StripeCalibrationInput& input,
                                              const hal::StripeCellGeometry& start,
                                              const StripeCalibrationOptions& options) {
  StripeRigInput rig;
  rig.cameras.push_back({input.profiles, input.axis_mm, start});
  rig.cube = input.cube;
  rig.T_table_cube = input.T_table_cube;
  StripeRigResult r = calibrate_stripe_rig(rig, options);
  if (r.cameras.empty()) {
    StripeCalibrationResult out;
    out.geometry = start;
    out.reason = r.reason;
    return out;
  }
  StripeCalibrationResult out = std::move(r.cameras[0]);
  out.ok = r.ok;
  out.reason = r.reason;
  return out;
}

StripeRigResult calibrate_stripe_rig(const StripeRigInput& input,
                                     const StripeCalibrationOptions& options) {
  StripeRigResult result;
  if (input.cameras.empty()) {
    result.reason = "no camera";
    return result;
  }
  const bool several = input.cameras.size() > 1;
  const auto fail = [&](std::size_t k, const std::string& why) {
    result.reason = several ? "camera " + std::to_string(k + 1) + ": " + why : why;
    return result;
  };
  std::vector<Camera> cams(input.cameras.size());
  for (std::size_t k = 0; k < cams.size(); ++k) {
    const StripeCameraInput& in = input.cameras[k];
    Camera& cam = cams[k];
    cam.result.geometry = in.start;
    if (in.profiles.size() != in.axis_mm.size()) {
      return fail(k, "profiles and axis positions differ in number");
    }
    cam.raw = collect_plane_samples(in);
    if (cam.raw.q.size() < 6 * options.planes.min_points) {
      return fail(k, "too few points in the sweep (" + std::to_string(cam.raw.q.size()) + ")");
    }
    cam.st = state_of(in.start);
    // The camera sees the faces that both the laser and it face, at mid-sweep; the true planes
    // and corners follow from the fixture's pose.
    const double mid = 0.5 * (in.axis_mm.front() + in.axis_mm.back());
    const Vector3d centre = input.T_table_cube.translation();
    const Vector3d laser = to_table(cam.st, Vector3d::Zero(), mid) - centre;
    const Vector3d camera = to_table(cam.st, in.start.ranger.camera_point(), mid) - centre;
    cam.towards = (laser.normalized() + camera.normalized()).normalized();
    cam.truth = visible_planes(input.cube, input.T_table_cube, cam.towards);
    for (int c = 0; c < 8; ++c) cam.X[c] = corner_point(cam.truth, c);
    for (int round = 0; round < options.rounds; ++round) {
      if (std::string why = extract_corners(cam, input, options, round); !why.empty()) {
        return fail(k, why);
      }
      std::vector<StripeState> next;
      if (!solve_linear(std::span(&cam.corners_raw, 1), std::span(&cam.X, 1), cam.st, next)) {
        return fail(k, "round " + std::to_string(round + 1) + ": the linear model is singular");
      }
      cam.st = next[0];
      cam.result.rounds.back().corner_rms_mm = corner_rms(cam);
    }
  }
  if (several) {
    for (std::size_t k = 0; k < cams.size(); ++k) {
      if (std::string why = extract_corners(cams[k], input, options, options.rounds);
          !why.empty()) {
        return fail(k, why);
      }
    }
    if (!solve_averaged(cams)) {
      result.reason = "averaged round: the linear model is singular";
      return result;
    }
    for (Camera& cam : cams) cam.result.rounds.back().corner_rms_mm = corner_rms(cam);
  }

  StripeRig rig;
  rig.T_cell_ranger0 = cams[0].st.T_cell_ranger;
  rig.axis = cams[0].st.axis;
  for (std::size_t k = 1; k < cams.size(); ++k) {
    rig.in_plane.push_back(
        nearest_in_plane(rig.T_cell_ranger0.inverse() * cams[k].st.T_cell_ranger));
  }
  std::vector<StripePlanePoint> pts;
  std::vector<std::array<CubePlane, 6>> truths;
  for (std::size_t k = 0; k < cams.size(); ++k) {
    truths.push_back(cams[k].truth);
    for (std::size_t j = 0; j < 6; ++j) {
      for (const std::uint32_t i : cams[k].planes[j].inliers) {
        pts.push_back(
            {cams[k].raw.q[i], cams[k].raw.s[i], static_cast<int>(j), static_cast<int>(k)});
      }
    }
  }
  const StripeRefinement fit = refine_stripe(rig, pts, truths, options.lm);
  const double n = static_cast<double>(pts.size());
  const double parameters = static_cast<double>(fit.x.parameters());
  result.points = pts.size();
  result.initial_rms_mm = std::sqrt(2.0 * fit.initial_cost / n);
  result.rms_mm = std::sqrt(2.0 * fit.lin.cost / n);
  result.lm_iterations = fit.iterations;
  const double sigma2 = 2.0 * fit.lin.cost / std::max(1.0, n - parameters);
  result.covariance = sigma2 * fit.lin.jtj.inverse();
  result.ok = result.covariance.allFinite();
  if (!result.ok) result.reason = "the refinement's normal matrix is singular";

  // Per camera: its share of the covariance and the residuals of its own points.
  std::vector<double> sum0(cams.size(), 0.0), sum(cams.size(), 0.0);
  std::vector<std::size_t> count(cams.size(), 0);
  for (const StripePlanePoint& p : pts) {
    const auto k = static_cast<std::size_t>(p.camera);
    const CubePlane& pl = truths[k][static_cast<std::size_t>(p.plane)];
    sum0[k] += std::pow(pl.distance(to_table(rig.camera(k), p.q, p.axis_mm)), 2);
    sum[k] += std::pow(pl.distance(to_table(fit.x.camera(k), p.q, p.axis_mm)), 2);
    ++count[k];
  }
  for (std::size_t k = 0; k < cams.size(); ++k) {
    StripeCalibrationResult& r = cams[k].result;
    r.ok = result.ok;
    r.points = count[k];
    r.initial_rms_mm = std::sqrt(sum0[k] / static_cast<double>(count[k]));
    r.rms_mm = std::sqrt(sum[k] / static_cast<double>(count[k]));
    r.lm_iterations = fit.iterations;
    const Eigen::MatrixXd G = camera_jacobian(fit.x, k);
    r.covariance = G * result.covariance * G.transpose();
    const Eigen::Matrix<double, 8, 1> sd = r.covariance.diagonal().cwiseSqrt();
    r.position_sigma_mm = sd.head<3>();
    r.rotation_sigma_rad = sd.segment<3>(3);
    r.axis_sigma_rad = sd.tail<2>();
    r.geometry = geometry_of(input.cameras[k].start, fit.x.camera(k));
    result.cameras.push_back(std::move(r));
  }
  return result;
}

}  // namespace rangefit::calib
