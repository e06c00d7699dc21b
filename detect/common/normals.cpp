#include "detect/common/normals.hpp"

#include <algorithm>
#include <cmath>

#include "detect/common/normals_grid.hpp"
#include "detect/common/pca.hpp"

namespace rangefit {
namespace {

// PCA normal of the accumulated patch, oriented toward the sensor; zero when rejected.
// The moments are of offsets from the query point (well conditioned far from the origin).
Eigen::Vector3d patch_normal(const pca::Moments& m, const Eigen::Vector3d& toward,
                             const NormalOptions& o) {
  if (m.count < std::max(3, o.min_neighbours)) return Eigen::Vector3d::Zero();
  // Eq. 4.4: the patch must be centred on the point, else it straddles an edge or boundary.
  if (m.mean().norm() >= o.max_centroid_offset * o.radius) return Eigen::Vector3d::Zero();
  // A patch's smallest eigenvalue is well separated unless it is degenerate: closed form.
  const pca::Eigen3 e = pca::eigen_symmetric_direct(m.covariance());
  // Collinear neighbours: the second eigenvalue is rounding noise of the largest (float offsets).
  if (!(e.values(1) > 1e-6 * e.values(2))) return Eigen::Vector3d::Zero();
  Eigen::Vector3d n = e.vectors.col(0);
  if (n.dot(toward) < 0.0) n = -n;
  return n;
}

Eigen::Vector3d toward_sensor(const Eigen::Vector3d& p, const NormalOptions& o) {
  return o.sensor_position ? Eigen::Vector3d(*o.sensor_position - p) : o.view_dir;
}

// Grid cell size as a share of R: smaller cells clip the ball's disc tighter but add rows.
constexpr double kCellShare = 0.5;

}  // namespace

NormalEstimate estimate_normals(std::span<const Eigen::Vector3d> points, const KdTree& tree,
                                std::span<const std::uint32_t> queries,
                                const NormalOptions& options) {
  NormalEstimate out;
  out.normals.assign(queries.size(), Eigen::Vector3d::Zero());
  std::vector<std::uint32_t> nb;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const Eigen::Vector3d& p = points[queries[i]];
    tree.radius_search(p, options.radius, nb);
    pca::Moments m;
    for (const std::uint32_t j : nb) m.add(points[j] - p);
    out.normals[i] = patch_normal(m, toward_sensor(p, options), options);
    if (!out.normals[i].isZero()) ++out.kept;
  }
  return out;
}

namespace {

// Both binned variants: the grid over every point, or over points[neighbours[i]] only.
NormalEstimate binned(std::span<const Eigen::Vector3d> points,
                      const std::span<const std::uint32_t>* neighbours,
                      std::span<const std::uint32_t> queries, const NormalOptions& options,
                      std::pmr::memory_resource* mr) {
  NormalEstimate out{std::pmr::vector<Eigen::Vector3d>(mr)};
  out.normals.assign(queries.size(), Eigen::Vector3d::Zero());
  if (queries.empty() || !(options.radius > 0.0)) return out;
  // Bin along the view (the sensor's position seen from the points' centre when given).
  Eigen::Vector3d dir = options.view_dir;
  if (options.sensor_position) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    if (neighbours) {
      std::size_t n = 0;
      for (const std::uint32_t i : *neighbours) {
        if (i < points.size()) c += points[i], ++n;
      }
      c /= static_cast<double>(std::max<std::size_t>(n, 1));
    } else {
      c = pca::centroid(points);
    }
    if (c.allFinite() && (*options.sensor_position - c).norm() > 1e-9) {
      dir = *options.sensor_position - c;
    }
  }
  if (!(dir.norm() > 1e-12) || !dir.allFinite()) dir = Eigen::Vector3d::UnitZ();
  const double cell = kCellShare * options.radius;
  const NeighbourGrid grid = neighbours ? NeighbourGrid(points, *neighbours, dir, cell, mr)
                                        : NeighbourGrid(points, dir, cell, mr);
  for (std::size_t i = 0; i < queries.size(); ++i) {
    if (queries[i] >= points.size()) continue;
    const Eigen::Vector3d& p = points[queries[i]];
    out.normals[i] = patch_normal(grid.ball(p, options.radius), toward_sensor(p, options), options);
    if (!out.normals[i].isZero()) ++out.kept;
  }
  return out;
}

}  // namespace

NormalEstimate estimate_normals_binned(std::span<const Eigen::Vector3d> points,
                                       std::span<const std::uint32_t> queries,
                                       const NormalOptions& options,
                                       std::pmr::memory_resource* mr) {
  return binned(points, nullptr, queries, options, mr);
}

NormalEstimate estimate_normals_binned(std::span<const Eigen::Vector3d> points,
                                       std::span<const std::uint32_t> neighbours,
                                       std::span<const std::uint32_t> queries,
                                       const NormalOptions& options,
                                       std::pmr::memory_resource* mr) {
  return binned(points, &neighbours, queries, options, mr);
}

NormalEstimate estimate_normals_organised(const PointCloud& cloud,
                                          std::span<const std::uint32_t> queries,
                                          const NormalOptions& options) {
  NormalEstimate out;
  out.normals.assign(queries.size(), Eigen::Vector3d::Zero());
  const GridLayout& g = cloud.grid;
  if (g.empty() || g.index.size() != static_cast<std::size_t>(g.rows) * g.cols) return out;
  // Cell of each point, and the median distance between horizontally adjacent cells.
  std::vector<std::int32_t> cell(cloud.size(), -1);
  std::vector<double> steps;
  for (int r = 0; r < g.rows; ++r) {
    for (int c = 0; c < g.cols; ++c) {
      const std::int32_t k = g.at(r, c);
      if (k < 0 || static_cast<std::size_t>(k) >= cloud.size()) continue;
      cell[k] = r * g.cols + c;
      if (c + 1 < g.cols && (r % 4) == 0) {
        const std::int32_t k2 = g.at(r, c + 1);
        if (k2 >= 0 && static_cast<std::size_t>(k2) < cloud.size()) {
          steps.push_back((cloud.points[k] - cloud.points[k2]).norm());
        }
      }
    }
  }
  if (steps.empty()) return out;
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  const double step = std::max(steps[steps.size() / 2], 1e-6);
  const int w = std::clamp(static_cast<int>(std::ceil(options.radius / step)), 1, 64);
  const double r2 = options.radius * options.radius;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const std::int32_t ci = cell[queries[i]];
    if (ci < 0) continue;
    const Eigen::Vector3d& p = cloud.points[queries[i]];
    const int row = ci / g.cols, col = ci % g.cols;
    // The window's moments in plain sums (n, x, y, z and six of the symmetric nine products,
    // as pca::Moments::from_sums takes them): this loop visits up to (2w+1)^2 cells per query.
    double s[10] = {};
    for (int r = std::max(0, row - w); r <= std::min(g.rows - 1, row + w); ++r) {
      for (int c = std::max(0, col - w); c <= std::min(g.cols - 1, col + w); ++c) {
        const std::int32_t k = g.at(r, c);
        if (k < 0 || static_cast<std::size_t>(k) >= cloud.size()) continue;
        const double* q = cloud.points[static_cast<std::size_t>(k)].data();
        const double x = q[0] - p.x(), y = q[1] - p.y(), z = q[2] - p.z();
        if (x * x + y * y + z * z > r2) continue;
        s[0] += 1.0;
        s[1] += x;
        s[2] += y;
        s[3] += z;
        s[4] += x * x;
        s[5] += x * y;
        s[6] += x * z;
        s[7] += y * y;
        s[8] += y * z;
        s[9] += z * z;
      }
    }
    const pca::Moments m = pca::Moments::from_sums(s);
    out.normals[i] = patch_normal(m, toward_sensor(p, options), options);
    if (!out.normals[i].isZero()) ++out.kept;
  }
  return out;
}

std::pmr::vector<std::uint32_t> subsample_evenly(std::span<const std::uint32_t> indices, double keep,
                                                 std::pmr::memory_resource* mr) {
  std::pmr::vector<std::uint32_t> out(mr);
  if (!(keep > 0.0)) return out;
  if (keep >= 1.0) {
    out.assign(indices.begin(), indices.end());
    return out;
  }
  out.reserve(static_cast<std::size_t>(static_cast<double>(indices.size()) * keep) + 1);
  double acc = 0.0;
  for (const std::uint32_t i : indices) {
    acc += keep;
    if (acc >= 1.0) {
      acc -= 1.0;
      out.push_back(i);
    }
  }
  return out;
}

}  // namespace rangefit
