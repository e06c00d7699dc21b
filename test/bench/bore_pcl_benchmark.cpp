// The peer users would pick instead: PCL's NormalEstimation + SACSegmentationFromNormals
// (SACMODEL_NORMAL_PLANE to remove the entrance plane, then SACMODEL_CYLINDER, as in PCL's
// cylinder-segmentation tutorial) on the same ~75,000-point scan and the same region as our
// bore pipeline, in the same run, with the accuracy of both as counters (axis_deg, radius_mm,
// entrance_mm). Optional: -DRANGEFIT_PCL_BENCHMARK=ON with Debian's libpcl-dev; not in CI.
//   taskset -c 0 build-pcl/test/bench/bore_pcl_benchmark --benchmark_repetitions=20
//       (add --benchmark_report_aggregates_only=true for the medians alone)
#include <benchmark/benchmark.h>
#include <pcl/features/normal_3d.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <cmath>
#include <numbers>

#include "detect/bore/bore_detector.hpp"
#include "detect/common/normals.hpp"
#include "test/bench/bore_bench_scan.hpp"
#include "test/support/synthetic_bore.hpp"

namespace rangefit {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using Normals = pcl::PointCloud<pcl::Normal>;

// The bore_benchmark scan and CAD prior; `region` is our pipeline's region of interest (points
// within 2 r of the expected entrance) and `pool` that plus the 2 mm normal radius.
struct Fixture {
  sim::SyntheticBoreScan scan;
  BorePrior prior;
  Cloud::Ptr whole{new Cloud}, region{new Cloud}, pool{new Cloud};
};

Cloud::Ptr to_pcl(const std::vector<Eigen::Vector3d>& pts) {
  Cloud::Ptr c(new Cloud);
  for (const auto& p : pts)
    c->push_back(pcl::PointXYZ(p.cast<float>().x(), p.cast<float>().y(), p.cast<float>().z()));
  return c;
}

const Fixture& fixture() {
  static Fixture x;
  if (!x.scan.cloud.empty()) return x;
  bench::BoreBenchScan b = bench::make_bore_bench_scan(false);
  x.scan = std::move(b.scan);
  x.prior = b.prior;
  std::vector<Eigen::Vector3d> region, pool;
  for (const auto& p : x.scan.cloud.points) {
    const double d = (p - x.prior.entrance).norm();
    if (d <= 12.0) pool.push_back(p);
    if (d <= 10.0) region.push_back(p);
  }
  x.whole = to_pcl(x.scan.cloud.points);
  x.region = to_pcl(region);
  x.pool = to_pcl(pool);
  return x;
}

void report(benchmark::State& state, const Eigen::Vector3d& point, Eigen::Vector3d axis,
            double radius, const Eigen::Vector4d& plane) {
  const auto& t = fixture().scan.truth;
  axis.normalize();
  state.counters["axis_deg"] =
      std::acos(std::min(1.0, std::abs(axis.dot(t.axis)))) * 180.0 / std::numbers::pi;
  state.counters["radius_mm"] = radius - t.radius;
  // Entrance: the axis meets the plane n . x + d = 0.
  const double denom = plane.head<3>().dot(axis);
  if (std::abs(denom) > 1e-6) {
    const double s = -(plane.head<3>().dot(point) + plane(3)) / denom;
    state.counters["entrance_mm"] = (point + s * axis - t.entrance).norm();
  }
}

// PCL normals of the region with neighbours from the pool (the same neighbourhoods as ours).
Normals::Ptr pcl_normals(const Cloud::Ptr& queries, const Cloud::Ptr& surface) {
  pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> ne;
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  ne.setSearchMethod(tree);
  ne.setInputCloud(queries);
  ne.setSearchSurface(surface);
  ne.setRadiusSearch(2.0);
  const Eigen::Vector3f v = fixture().scan.truth.view_dir.cast<float>() * 1e4f;
  ne.setViewPoint(v.x(), v.y(), v.z());
  Normals::Ptr normals(new Normals);
  ne.compute(*normals);
  return normals;
}

struct PclFit {
  pcl::ModelCoefficients plane, cylinder;
};

// PCL's cylinder-segmentation recipe: the dominant plane out, then the cylinder, both RANSAC
// with normals; fixed seed (SACSegmentation's default is not random).
PclFit pcl_fit(const Cloud::Ptr& cloud, const Normals::Ptr& normals) {
  PclFit fit;
  pcl::SACSegmentationFromNormals<pcl::PointXYZ, pcl::Normal> seg;
  pcl::PointIndices::Ptr plane_idx(new pcl::PointIndices);
  seg.setOptimizeCoefficients(true);
  seg.setModelType(pcl::SACMODEL_NORMAL_PLANE);
  seg.setNormalDistanceWeight(0.1);
  seg.setMethodType(pcl::SAC_RANSAC);
  seg.setMaxIterations(100);
  seg.setDistanceThreshold(0.2);
  seg.setInputCloud(cloud);
  seg.setInputNormals(normals);
  seg.segment(*plane_idx, fit.plane);
  // The rest: everything the plane did not take.
  std::vector<bool> in_plane(cloud->size(), false);
  for (const int i : plane_idx->indices) in_plane[static_cast<std::size_t>(i)] = true;
  pcl::PointIndices::Ptr rest(new pcl::PointIndices);
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    if (!in_plane[i]) rest->indices.push_back(static_cast<int>(i));
  }
  pcl::PointIndices cyl_idx;
  seg.setModelType(pcl::SACMODEL_CYLINDER);
  seg.setNormalDistanceWeight(0.1);
  seg.setMaxIterations(10000);
  seg.setDistanceThreshold(0.1);
  seg.setRadiusLimits(4.0, 6.0);
  seg.setIndices(rest);
  seg.segment(cyl_idx, fit.cylinder);
  return fit;
}

void report_pcl(benchmark::State& state, const PclFit& f) {
  if (f.cylinder.values.size() < 7 || f.plane.values.size() < 4) {
    state.SkipWithError("PCL found no cylinder or plane");
    return;
  }
  const auto& c = f.cylinder.values;
  const auto& p = f.plane.values;
  report(state, Eigen::Vector3d(c[0], c[1], c[2]), Eigen::Vector3d(c[3], c[4], c[5]), c[6],
         Eigen::Vector4d(p[0], p[1], p[2], p[3]));
}

void BM_PclNormalsRegion(benchmark::State& state) {
  const Fixture& f = fixture();
  for (auto _ : state) benchmark::DoNotOptimize(pcl_normals(f.region, f.pool));
}

void BM_OursNormalsRegion(benchmark::State& state) {
  const Fixture& f = fixture();
  std::vector<Eigen::Vector3d> pool;
  std::vector<std::uint32_t> queries;
  bench::region_normal_inputs(f.scan.cloud.points, f.prior.entrance, pool, queries);
  NormalOptions no;
  no.view_dir = f.scan.truth.view_dir;
  for (auto _ : state) benchmark::DoNotOptimize(estimate_normals_binned(pool, queries, no));
}

void BM_PclNormalsWholeScan(benchmark::State& state) {
  const Fixture& f = fixture();
  for (auto _ : state) benchmark::DoNotOptimize(pcl_normals(f.whole, f.whole));
}

void BM_OursNormalsWholeScan(benchmark::State& state) {
  const Fixture& f = fixture();
  std::vector<std::uint32_t> all(f.scan.cloud.size());
  for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  NormalOptions no;
  no.view_dir = f.scan.truth.view_dir;
  for (auto _ : state) {
    benchmark::DoNotOptimize(estimate_normals_binned(f.scan.cloud.points, all, no));
  }
}

// PCL's segmentation alone, on the region with its normals computed once outside the loop.
void BM_PclSegmentationRegion(benchmark::State& state) {
  const Fixture& f = fixture();
  const Normals::Ptr normals = pcl_normals(f.region, f.pool);
  PclFit fit;
  for (auto _ : state) {
    fit = pcl_fit(f.region, normals);
    benchmark::DoNotOptimize(fit);
  }
  report_pcl(state, fit);
}

// Everything PCL needs from the region: normals, plane, cylinder.
void BM_PclTotalRegion(benchmark::State& state) {
  const Fixture& f = fixture();
  PclFit fit;
  for (auto _ : state) {
    fit = pcl_fit(f.region, pcl_normals(f.region, f.pool));
    benchmark::DoNotOptimize(fit);
  }
  report_pcl(state, fit);
}

// Our whole pipeline from the full scan (region extraction included).
void BM_OursPipeline(benchmark::State& state) {
  const Fixture& f = fixture();
  BoreOptions opt;
  opt.view_dir = f.scan.truth.view_dir;
  BoreResult r;
  for (auto _ : state) {
    r = detect_bore(f.scan.cloud, f.prior, opt);
    benchmark::DoNotOptimize(r);
  }
  Eigen::Vector4d plane;
  plane << r.plane_normal, -r.plane_normal.dot(r.entrance);
  report(state, r.entrance, r.axis, r.radius, plane);
}

BENCHMARK(BM_OursPipeline)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PclTotalRegion)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PclSegmentationRegion)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OursNormalsRegion)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PclNormalsRegion)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OursNormalsWholeScan)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PclNormalsWholeScan)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rangefit

BENCHMARK_MAIN();
