#include "detect/common/normals_grid.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>

#include "detect/common/lanes.hpp"

namespace rangefit {
namespace {

// Float and int vectors of W lanes (a dependent vector_size is not allowed in a template).
template <int W>
struct Lanes;
template <>
struct Lanes<4> {
  using F = float __attribute__((vector_size(16)));
  using I = std::int32_t __attribute__((vector_size(16)));
};
template <>
struct Lanes<8> {
  using F = float __attribute__((vector_size(32)));
  using I = std::int32_t __attribute__((vector_size(32)));
};

// The ball query at W float lanes (GCC/Clang vector extensions: SSE2/NEON at 4, compiled again
// for AVX2 at 8 below; a 16-lane AVX-512 build measured 2.7x slower than AVX2 on this EPYC VM). q:
// the query in the centred (u, v, w) frame; out: n, sum (3), then the upper triangle of the
// outer-product sum (xx xy xz yy yz zz).
template <int W>
[[gnu::always_inline]] inline void ball_kernel(const NeighbourGrid::View& g, const double* q,
                                               double radius, double* out) {
  using F = typename Lanes<W>::F;
  using I = typename Lanes<W>::I;
  I lane{};
  for (int j = 0; j < W; ++j) lane[j] = j;
  const F px = F{} + static_cast<float>(q[0]), py = F{} + static_cast<float>(q[1]),
          pz = F{} + static_cast<float>(q[2]);
  const F r2 = F{} + static_cast<float>(radius * radius);
  const F one = F{} + 1.0f;
  F n{}, sx{}, sy{}, sz{}, sxx{}, sxy{}, sxz{}, syy{}, syz{}, szz{};
  const double u = q[0] - g.lo_u, v = q[1] - g.lo_v;
  // Cells by multiplying with 1 / cell as build() assigned them (monotone rounding: a point
  // within the ball never falls in a cell outside the range), no division per row.
  const int v0 = std::max(0, static_cast<int>(std::floor((v - radius) * g.inv_cell)));
  const int v1 = std::min(g.nv - 1, static_cast<int>(std::floor((v + radius) * g.inv_cell)));
  for (int iv = v0; iv <= v1; ++iv) {
    // Only the cells of this row that the ball's disc reaches: one contiguous span.
    const double dv = std::max({0.0, iv * g.cell - v, v - (iv + 1) * g.cell});
    if (dv > radius) continue;
    const double half = std::sqrt(radius * radius - dv * dv);
    const int u0 = std::max(0, static_cast<int>(std::floor((u - half) * g.inv_cell)));
    const int u1 = std::min(g.nu - 1, static_cast<int>(std::floor((u + half) * g.inv_cell)));
    if (u0 > u1) continue;
    const std::size_t row = static_cast<std::size_t>(iv) * static_cast<std::size_t>(g.nu);
    const std::size_t e = g.start[row + static_cast<std::size_t>(u1) + 1];
    for (std::size_t k = g.start[row + static_cast<std::size_t>(u0)]; k < e; k += W) {
      F x, y, z;
      std::memcpy(&x, g.x + k, sizeof x);
      std::memcpy(&y, g.y + k, sizeof y);
      std::memcpy(&z, g.z + k, sizeof z);
      x -= px;
      y -= py;
      z -= pz;
      const I in = (x * x + y * y + z * z <= r2) & (lane < I{} + static_cast<std::int32_t>(e - k));
      x = (F)((I)x & in);
      y = (F)((I)y & in);
      z = (F)((I)z & in);
      n += (F)((I)one & in);
      sx += x;
      sy += y;
      sz += z;
      sxx += x * x;
      sxy += x * y;
      sxz += x * z;
      syy += y * y;
      syz += y * z;
      szz += z * z;
    }
  }
  const F* sums[10] = {&n, &sx, &sy, &sz, &sxx, &sxy, &sxz, &syy, &syz, &szz};
  for (int s = 0; s < 10; ++s) {
    double acc = 0.0;
    for (int j = 0; j < W; ++j) acc += static_cast<double>((*sums[s])[j]);
    out[s] = acc;
  }
}

void ball4(const NeighbourGrid::View& g, const double* q, double r, double* out) {
  ball_kernel<4>(g, q, r, out);
}
#ifdef RANGEFIT_LANES_AVX2
[[gnu::target("avx2")]] void ball8(const NeighbourGrid::View& g, const double* q, double r,
                                   double* out) {
  ball_kernel<8>(g, q, r, out);
}
#endif

}  // namespace

int NeighbourGrid::lanes() { return rangefit::lanes::cpu_has_avx2() ? 8 : 4; }

NeighbourGrid::NeighbourGrid(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& dir,
                             double cell, std::pmr::memory_resource* mr)
    : start_(mr), x_(mr), y_(mr), z_(mr) {
  build(points, nullptr, points.size(), dir, cell);
}

NeighbourGrid::NeighbourGrid(std::span<const Eigen::Vector3d> points,
                             std::span<const std::uint32_t> subset, const Eigen::Vector3d& dir,
                             double cell, std::pmr::memory_resource* mr)
    : start_(mr), x_(mr), y_(mr), z_(mr) {
  build(points, subset.data(), subset.size(), dir, cell);
}

void NeighbourGrid::build(std::span<const Eigen::Vector3d> points, const std::uint32_t* subset,
                          std::size_t n, const Eigen::Vector3d& dir, double cell) {
  // The i-th point of the grid's set (an index past the cloud counts as non-finite).
  const Eigen::Vector3d nan = Eigen::Vector3d::Constant(std::nan(""));
  const auto point = [&](std::size_t i) -> const Eigen::Vector3d& {
    if (!subset) return points[i];
    return subset[i] < points.size() ? points[subset[i]] : nan;
  };
  const Eigen::Vector3d e3 = dir.normalized(), e1 = e3.unitOrthogonal();
  basis_ << e1, e3.cross(e1), e3;
  const Eigen::Matrix3d bt = basis_.transpose();
  // Three passes over the points (bounds, cells, scatter) and no copy of them in the grid's
  // frame: on a dense region the copy's allocation and page faults cost more than the
  // rotations computed again.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  std::size_t finite = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& p = point(i);
    if (!p.allFinite()) continue;
    const Eigen::Vector3d l = bt * p;
    lo = lo.cwiseMin(l);
    hi = hi.cwiseMax(l);
    ++finite;
  }
  if (finite == 0 || !(cell > 0.0)) return;
  const Eigen::Vector3d centre = 0.5 * (lo + hi);  // centred: the float offsets stay small
  origin_ = basis_ * centre;
  // Bound the cell count by the point count (a sparse cloud spread over metres).
  const double area = std::max(hi.x() - lo.x(), 1e-9) * std::max(hi.y() - lo.y(), 1e-9);
  cell_ = std::max({cell, std::sqrt(area / (4.0 * static_cast<double>(finite) + 64.0)), 1e-6});
  const double inv = 1.0 / cell_;
  nu_ = static_cast<int>((hi.x() - lo.x()) * inv) + 1;
  nv_ = static_cast<int>((hi.y() - lo.y()) * inv) + 1;
  lo_u_ = lo.x() - centre.x();
  lo_v_ = lo.y() - centre.y();
  // Counting sort by cell, rows of u-ordered cells one after another.
  constexpr std::uint32_t kNone = 0xffffffffu;
  std::pmr::vector<std::uint32_t> cell_of(n, kNone, start_.get_allocator());
  start_.assign(static_cast<std::size_t>(nu_) * static_cast<std::size_t>(nv_) + 1, 0);
  const auto local = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d { return bt * p - centre; };
  for (std::size_t i = 0; i < n; ++i) {
    if (!point(i).allFinite()) continue;
    const Eigen::Vector3d l = local(point(i));
    const int iu = std::clamp(static_cast<int>((l.x() - lo_u_) * inv), 0, nu_ - 1);
    const int iv = std::clamp(static_cast<int>((l.y() - lo_v_) * inv), 0, nv_ - 1);
    cell_of[i] = static_cast<std::uint32_t>(iv * nu_ + iu);
    ++start_[cell_of[i] + 1];
  }
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  std::pmr::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1, start_.get_allocator());
  x_.assign(finite + 16, 1e30f);  // padding lanes are masked off, never counted
  y_.assign(finite + 16, 1e30f);
  z_.assign(finite + 16, 1e30f);
  for (std::size_t i = 0; i < n; ++i) {
    if (cell_of[i] == kNone) continue;
    const Eigen::Vector3d l = local(point(i));
    const std::uint32_t k = fill[cell_of[i]]++;
    x_[k] = static_cast<float>(l.x());
    y_[k] = static_cast<float>(l.y());
    z_[k] = static_cast<float>(l.z());
  }
}

pca::Moments NeighbourGrid::ball(const Eigen::Vector3d& p, double radius) const {
  pca::Moments m;
  if (nu_ == 0 || !p.allFinite() || !(radius > 0.0)) return m;
  const Eigen::Vector3d q = basis_.transpose() * (p - origin_);
  const View g{x_.data(),   y_.data(), z_.data(), start_.data(), cell_,
               1.0 / cell_, lo_u_,     lo_v_,     nu_,           nv_};
  double s[10];
  static_assert(sizeof(q) == 3 * sizeof(double));
  const bool wide = lanes() == 8;  // never without RANGEFIT_LANES_AVX2
#ifdef RANGEFIT_LANES_AVX2
  if (wide) ball8(g, q.data(), radius, s);
#endif
  if (!wide) ball4(g, q.data(), radius, s);
  m = pca::Moments::from_sums(s);  // in the grid's basis: back to the cloud's axes
  m.sum = basis_ * m.sum;
  m.sum_outer = basis_ * m.sum_outer * basis_.transpose();
  return m;
}

}  // namespace rangefit
