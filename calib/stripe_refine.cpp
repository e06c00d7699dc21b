#include "calib/stripe_refine.hpp"

#include <cmath>
#include <vector>

namespace rangefit::calib {

using Eigen::Matrix3d;
using Eigen::Vector3d;

void axis_tangents(const Vector3d& d, Vector3d& u1, Vector3d& u2) {
  const Vector3d helper = std::abs(d.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY();
  u1 = d.cross(helper).normalized();
  u2 = d.cross(u1).normalized();
}

Eigen::Isometry3d nearest_in_plane(const Eigen::Isometry3d& T) {
  // A map of the plane y = 0 onto itself turns about y, after a flip (about x) when it
  // reverses the plane's normal.
  Matrix3d flip = Matrix3d::Identity();
  if (T.linear()(1, 1) < 0.0) flip.diagonal() << 1.0, -1.0, -1.0;
  const Matrix3d turn = flip * T.linear();
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() =
      flip * Eigen::AngleAxisd(std::atan2(turn(0, 2), turn(0, 0)), Vector3d::UnitY()).matrix();
  out.translation() = Vector3d(T.translation().x(), 0.0, T.translation().z());
  return out;
}

namespace {

// Camera 0's 8 parameters and one further camera's 3: the parameters a point depends on.
using Local = Eigen::Matrix<double, 11, 1>;

Eigen::Index first_in_plane(std::size_t camera) {
  return 8 + 3 * (static_cast<Eigen::Index>(camera) - 1);
}

LmLinearisation<Eigen::Dynamic> linearise(const StripeRig& s,
                                          const std::vector<StripePlanePoint>& pts,
                                          std::span<const std::array<CubePlane, 6>> planes) {
  const std::size_t cameras = s.in_plane.size();
  // Each camera's rows sum into its own 11 x 11 system (camera 0's further 3 stay zero), which
  // is then spread into the rig's.
  std::vector<LmRowSum<11>> sums(cameras);
  LmLinearisation<Eigen::Dynamic> lin(s.parameters());
  const Matrix3d R = s.T_cell_ranger0.linear();
  const Vector3d t = s.T_cell_ranger0.translation();
  Vector3d u1, u2;
  axis_tangents(s.axis, u1, u2);
  for (const StripePlanePoint& p : pts) {
    const std::size_t k = static_cast<std::size_t>(p.camera);
    const Eigen::Isometry3d& P = s.in_plane[k];
    const CubePlane& pl = planes[k][static_cast<std::size_t>(p.plane)];
    const Vector3d& n = pl.normal;
    const Vector3d q0 = P * p.q;  // camera 0's frame
    const double r = n.dot(R * q0 + t - p.axis_mm * s.axis) - pl.offset_mm;
    const Vector3d m = R.transpose() * n;
    Local j = Local::Zero();
    j.head<3>() = n;
    j.segment<3>(3) = q0.cross(m);  // R exp([w]x) q ~ R (q + w x q)
    j[6] = -p.axis_mm * n.dot(u1);
    j[7] = -p.axis_mm * n.dot(u2);
    if (k > 0) {  // P <- P (turn about y by a, shift by (b, 0, c)): q -> q + a y x q + (b, 0, c)
      const Vector3d mk = P.linear().transpose() * m;
      j[8] = mk.x();
      j[9] = mk.z();
      j[10] = mk.dot(Vector3d(p.q.z(), 0.0, -p.q.x()));
    }
    sums[k].add(j, r);
  }
  for (std::size_t k = 0; k < cameras; ++k) {
    const LmLinearisation<11> l = sums[k].take();
    lin.cost += l.cost;
    lin.jtj.topLeftCorner<8, 8>() += l.jtj.topLeftCorner<8, 8>();
    lin.g.head<8>() += l.g.head<8>();
    if (k == 0) continue;
    const Eigen::Index o = first_in_plane(k);
    lin.jtj.block<8, 3>(0, o) += l.jtj.topRightCorner<8, 3>();
    lin.jtj.block<3, 8>(o, 0) += l.jtj.bottomLeftCorner<3, 8>();
    lin.jtj.block<3, 3>(o, o) += l.jtj.bottomRightCorner<3, 3>();
    lin.g.segment<3>(o) += l.g.tail<3>();
  }
  return lin;
}

StripeRig stripe_step(const StripeRig& s, const Eigen::VectorXd& h) {
  StripeRig out = s;
  out.T_cell_ranger0.translation() += h.head<3>();
  const Vector3d w = h.segment<3>(3);
  const double angle = w.norm();
  if (angle > 0.0) {
    out.T_cell_ranger0.linear() =
        s.T_cell_ranger0.linear() * Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
  }
  Vector3d u1, u2;
  axis_tangents(s.axis, u1, u2);
  out.axis = (s.axis + h[6] * u1 + h[7] * u2).normalized();
  for (std::size_t k = 1; k < s.in_plane.size(); ++k) {
    const Eigen::Index o = first_in_plane(k);
    Eigen::Isometry3d d = Eigen::Isometry3d::Identity();
    d.linear() = Eigen::AngleAxisd(h[o + 2], Vector3d::UnitY()).toRotationMatrix();
    d.translation() = Vector3d(h[o], 0.0, h[o + 1]);
    out.in_plane[k] = s.in_plane[k] * d;
  }
  return out;
}

Matrix3d skew(const Vector3d& v) {
  Matrix3d S;
  S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return S;
}

}  // namespace

StripeRefinement refine_stripe(const StripeRig& start, const std::vector<StripePlanePoint>& pts,
                               std::span<const std::array<CubePlane, 6>> planes,
                               const LmOptions& options) {
  return levenberg_marquardt<Eigen::Dynamic>(
      start, options, [&](const StripeRig& s) { return linearise(s, pts, planes); }, stripe_step,
      [](const StripeRig& s) { return s.T_cell_ranger0.translation().norm(); });
}

Eigen::MatrixXd camera_jacobian(const StripeRig& rig, std::size_t k) {
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(8, rig.parameters());
  G.leftCols<8>().setIdentity();
  if (k == 0) return G;
  // T_k = T_0 P_k: t_k = t_0 + R_0 p_k and R_k = R_0 R_p, so a rotation w_0 of camera 0 moves
  // t_k by -R_0 [p_k]x w_0 and turns camera k by R_p^T w_0.
  const Matrix3d R0 = rig.T_cell_ranger0.linear();
  const Matrix3d Rp = rig.in_plane[k].linear();
  const Eigen::Index o = first_in_plane(k);
  G.block<3, 3>(0, 3) = -R0 * skew(rig.in_plane[k].translation());
  G.block<3, 1>(0, o) = R0 * Rp.col(0);
  G.block<3, 1>(0, o + 1) = R0 * Rp.col(2);
  G.block<3, 3>(3, 3) = Rp.transpose();
  G(4, o + 2) = 1.0;
  return G;
}

}  // namespace rangefit::calib
