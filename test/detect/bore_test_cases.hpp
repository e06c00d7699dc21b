#pragma once
// The synthetic bore cases shared by the bore tests and the benchmark.

#include <Eigen/Geometry>
#include <random>
#include <string>
#include <vector>

#include "detect/bore_detector.hpp"
#include "test/support/synthetic_bore.hpp"

namespace rangefit::test {

struct BoreCase {
  std::string name;
  sim::SyntheticBoreOptions scan;
};

// A seeded rigid pose, so no case is axis-aligned in the world frame.
inline Eigen::Isometry3d random_pose(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.6 * u(rng), axis).toRotationMatrix();
  T.translation() = Eigen::Vector3d(100 * u(rng), 100 * u(rng), 300 + 50 * u(rng));
  return T;
}

// A CAD prior off the truth by about half a millimetre and two degrees.
inline BorePrior perturbed_prior(const sim::SyntheticBoreTruth& truth, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  BorePrior prior;
  prior.entrance = truth.entrance + 0.3 * Eigen::Vector3d(u(rng), u(rng), u(rng));
  const Eigen::Vector3d tilt = truth.axis.cross(Eigen::Vector3d(u(rng), u(rng), u(rng)));
  prior.axis = (truth.axis + 0.035 * tilt.normalized()).normalized();
  prior.radius = truth.radius;
  prior.plane_normal = truth.plane_normal;
  return prior;
}

inline std::vector<BoreCase> bore_cases() {
  using sim::BoreEdge;
  using sim::TopSurface;
  std::vector<BoreCase> cases;
  auto add = [&](std::string name, auto&& tweak) {
    BoreCase c{std::move(name), {}};
    tweak(c.scan);
    c.scan.seed = 100 + cases.size();
    c.scan.T_world_part = random_pose(200 + cases.size());
    cases.push_back(std::move(c));
  };
  add("plate_r5", [](auto&) {});
  add("plate_r2", [](auto& s) { s.radius = 2.0; });
  add("plate_r10", [](auto& s) { s.radius = 10.0; });
  add("plate_r25", [](auto& s) {
    s.radius = 25.0;
    s.extent = 37.5;
    s.spacing = 0.4;
  });
  add("slant30", [](auto& s) { s.slant_deg = 30.0; });
  add("slant45", [](auto& s) { s.slant_deg = 45.0; });
  add("slant45_r10", [](auto& s) {
    s.slant_deg = 45.0;
    s.radius = 10.0;
  });
  add("chamfer", [](auto& s) { s.edge = BoreEdge::kChamfer; });
  add("chamfer_r2", [](auto& s) {
    s.edge = BoreEdge::kChamfer;
    s.radius = 2.0;
    s.edge_size = 0.4;
  });
  add("rounded", [](auto& s) {
    s.edge = BoreEdge::kRounded;
    s.edge_size = 1.5;
  });
  add("notches", [](auto& s) { s.notches = 3; });
  add("notches_r12", [](auto& s) {
    s.notches = 3;
    s.radius = 12.0;
  });
  add("neighbour", [](auto& s) { s.neighbour = true; });
  add("neighbour_behind", [](auto& s) {
    s.neighbour = true;
    s.neighbour_azimuth_deg = 180;
  });
  add("curved", [](auto& s) { s.surface = TopSurface::kCurved; });
  add("bumpy", [](auto& s) { s.surface = TopSurface::kBumpy; });
  add("bumpy_chamfer_slant30", [](auto& s) {
    s.surface = TopSurface::kBumpy;
    s.edge = BoreEdge::kChamfer;
    s.slant_deg = 30.0;
  });
  add("organised", [](auto& s) { s.organised = true; });
  add("organised_slant30_r8", [](auto& s) {
    s.organised = true;
    s.slant_deg = 30;
    s.radius = 8;
  });
  add("steep_view", [](auto& s) { s.view_tilt_deg = 40.0; });
  return cases;
}

}  // namespace rangefit::test
