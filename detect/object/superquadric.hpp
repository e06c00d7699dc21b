#pragma once
// The tapered superquadric part model (thesis 2.1.3) and its inside-outside function.
//
// Part frame: the superquadric centre is the origin, z is its main axis (a3 along z). A part in a
// scene is this model plus a pose T_world_part. Tapering (eq. 2.19-2.23) scales x and y linearly
// along z, so kx = ky = -1 turns a cylinder into a cone whose tip is at z = +a3.
//
// F (eq. 2.15) is < 1 inside, 1 on the surface, > 1 outside (eq. 2.16-2.18). The fit metric is
// G = F^eps1 (eq. 5.1): for eps2 = 1 it is the squared normalised radius, so G - 1 behaves like a
// distance for every shape (G grows like the squared distance far away). The evaluation is
// scaled so that eps near 0.1 (exponents of 20) cannot overflow, and points on the axis, at the
// poles, at the centre or far away give finite values and finite gradients.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <span>

namespace rangefit {

// A part's faces are straight along a direction when its exponent there is at most this (a
// cylinder's side wall along its axis: eps1; a box's sides across it: eps2).
inline constexpr double kFlatExponent = 0.5;

struct Superquadric {
  double a1 = 1.0, a2 = 1.0, a3 = 1.0;  // half sizes along x, y, z of the part frame, mm
  double eps1 = 1.0;                    // north-south shape exponent, valid [0.1, 2]
  double eps2 = 1.0;                    // east-west shape exponent, valid [0.1, 2]
  double kx = 0.0, ky = 0.0;            // taper along z (eq. 2.22-2.23), valid (-1, 1]

  double min_size() const;
  double max_size() const;
  // True when sizes are positive and finite, eps in [0.1, 2] and taper in [-1, 1].
  bool valid() const;
  // True for a ball (equal sizes, eps 1, no taper): its pose has no orientation.
  bool ball() const;
  // True when either taper factor is non-zero.
  bool has_taper() const { return kx != 0.0 || ky != 0.0; }
};

// Precomputed exponents of one part for fast repeated evaluation (the pose fit calls this per
// point and iteration). Uses the homogeneity F(s p) = s^(2/eps1) F(p) of the untapered function:
// the point is scaled so its largest normalised coordinate is 1, which keeps every power in
// [0, 1] (no overflow for eps = 0.1), and integer exponents (eps = 0.1, 0.5, 1, 2) are
// multiplied out instead of calling pow().
class SuperquadricMetric {
 public:
  explicit SuperquadricMetric(const Superquadric& sq);
  double value(const Eigen::Vector3d& p_part) const;
  double value_and_gradient(const Eigen::Vector3d& p_part, Eigen::Vector3d& gradient) const;
  const Superquadric& model() const { return sq_; }

  // G (and with kGradient its gradient) at one point (V = double) or at four (V = lanes::V4d),
  // with the same arithmetic on every lane, so the pose fit's vectorised loop and value() agree
  // bit for bit. Defined in detect/superquadric_eval.hpp.
  template <class V, bool kGradient>
  V evaluate(V x, V y, V z, V* gx, V* gy, V* gz) const;

  // G at the points `indices` of `points`, moved into the part frame by T_part_from: out[k] =
  // value(T_part_from * points[indices[k]]). Four points per lane vector (AVX2 when the CPU
  // has it); the verification and refinement scans of the object detector run through here.
  void values(const Eigen::Isometry3d& T_part_from, std::span<const Eigen::Vector3d> points,
              std::span<const std::uint32_t> indices, std::span<double> out) const;

 private:
  struct Power {
    double e = 1.0;
    int n = -1;  // >= 0: e is this integer
    template <class V>
    V operator()(V x) const;
  };

  Superquadric sq_;
  Power p_xy_, p_a_, p_z_, p_g_;  // 2/eps2, eps2/eps1, 2/eps1, eps1
  double inv_a1_ = 1.0, inv_a2_ = 1.0, inv_a3_ = 1.0;
  bool tapered_ = false;
};

// The support of the untapered part along a part-frame unit direction m: the largest m . x over
// its surface. The surface is the unit sphere of nested norms, ((|x| / a1)^(2 / eps2) +
// (|y| / a2)^(2 / eps2))^(eps2 / eps1) + (|z| / a3)^(2 / eps1), so its support is the nested dual
// norm with exponents 2 / (2 - eps): a box's a1 |mx| + a2 |my| + a3 |mz|, an ellipsoid's
// sqrt(sum (a_i m_i)^2). Tapering is ignored.
double support(const Superquadric& sq, const Eigen::Vector3d& m);

// The same with the taper (eq. 2.19-2.21), to ~0.01 % of the size: the part's cross-section at
// height z = a3 t is the superellipse of half sizes a_i c(t) (1 + k_i t), c(t) = (1 -
// |t|^(2 / eps1))^(eps1 / 2), whose support along m is the dual norm in x and y; plus m_z z,
// maximised over t by a grid and a golden-section search about its best node. support() for an
// untapered part.
double tapered_support(const Superquadric& sq, const Eigen::Vector3d& m);

// The ellipsoid of the part's half sizes (eps1 = eps2 = 1, taper kept): inscribed in a box or a
// can, smooth where their support has kinks.
Superquadric ellipsoid_of(const Superquadric& sq);

// G = F^eps1 (eq. 2.15 with tapering undone, raised to eps1 as in eq. 5.1) at a point given in
// the part frame, mm. Finite for every finite input; G < 1 inside, = 1 on the surface.
double metric(const Superquadric& sq, const Eigen::Vector3d& p_part);

// Distance of a part-frame point from the surface to first order, (G - 1) / |grad G| (mm);
// accurate near it. The radial distance |x| (1 - G^-1/2) of thesis 2.1.3 grows without bound
// along a thin part (a point on a shaft's side far from its centre is reached by a ray that
// grazes the surface).
double surface_distance(const SuperquadricMetric& m, const Eigen::Vector3d& p_part);

// G and its gradient dG/dp_part (1/mm). The gradient is finite everywhere (zero at the centre).
double metric_and_gradient(const Superquadric& sq, const Eigen::Vector3d& p_part,
                           Eigen::Vector3d& gradient);

// F itself (eq. 2.15, tapering undone), saturated at 1e300 instead of overflowing.
double inside_outside(const Superquadric& sq, const Eigen::Vector3d& p_part);

// The explicit surface point (eq. 2.14, then tapered with eq. 2.19-2.21) at latitude eta in
// [-pi/2, pi/2] and longitude omega in [-pi, pi), in the part frame, mm.
Eigen::Vector3d surface_point(const Superquadric& sq, double eta, double omega);

// Conservative axis-aligned bounds of the tapered part in its own frame, mm.
Eigen::AlignedBox3d part_bounds(const Superquadric& sq);

// Metric of a world point for a posed part: metric(sq, T_world_part^-1 * p_world).
inline double metric_world(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                           const Eigen::Vector3d& p_world) {
  return metric(sq, T_world_part.inverse() * p_world);
}

}  // namespace rangefit
