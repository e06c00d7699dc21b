#include "detect/object/object_stability.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace rangefit {
namespace {

constexpr int kLatitudes = 48, kLongitudes = 96;  // surface samples: ~0.01 of a radius apart
constexpr int kDirections = 8;                    // level turning axes tried each step
constexpr double kStepRad = 4.0 * std::numbers::pi / 180.0;
// A turn lowers the centroid when by more than this share of the part's size (the samples'
// own spread on a rolling can's side is ~1e-4 of its radius).
constexpr double kLowerShare = 1e-3;

std::vector<Eigen::Vector3d> surface_samples(const Superquadric& part) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(static_cast<std::size_t>((kLatitudes + 1) * kLongitudes));
  for (int i = 0; i <= kLatitudes; ++i) {
    const double eta = -std::numbers::pi / 2.0 + std::numbers::pi * i / kLatitudes;
    for (int j = 0; j < kLongitudes; ++j) {
      const double omega = -std::numbers::pi + 2.0 * std::numbers::pi * j / kLongitudes;
      out.push_back(surface_point(part, eta, omega));
    }
  }
  return out;
}

// The centroid's height above the table when the part at R rests its lowest point on it.
double centroid_height(const std::vector<Eigen::Vector3d>& samples, const Eigen::Vector3d& g,
                       const Eigen::Matrix3d& R, const Eigen::Vector3d& up) {
  const Eigen::Vector3d local_up = R.transpose() * up;
  double lowest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& s : samples) lowest = std::min(lowest, s.dot(local_up));
  return g.dot(local_up) - lowest;
}

}  // namespace

Eigen::Vector3d part_centroid(const Superquadric& part) {
  // Cross-sections across z scale by r(t) = (1 - |t|^(2/eps1))^(eps1/2), t = z / a3, and by the
  // taper's (1 + kx t)(1 + ky t); their shape is the same at every t.
  constexpr int kSlices = 400;
  double volume = 0.0, moment = 0.0;
  for (int i = 0; i < kSlices; ++i) {
    const double t = -1.0 + (2.0 * i + 1.0) / kSlices;
    const double r =
        std::pow(std::max(0.0, 1.0 - std::pow(std::abs(t), 2.0 / part.eps1)), part.eps1 / 2.0);
    const double area = r * r * std::abs((1.0 + part.kx * t) * (1.0 + part.ky * t));
    volume += area;
    moment += area * t;
  }
  return Eigen::Vector3d(0.0, 0.0, volume > 0.0 ? part.a3 * moment / volume : 0.0);
}

double settle_angle_rad(const Superquadric& part, const Eigen::Matrix3d& R_world_part,
                        const Eigen::Vector3d& up, double limit_rad) {
  const std::vector<Eigen::Vector3d> samples = surface_samples(part);
  const Eigen::Vector3d g = part_centroid(part);
  const Eigen::Vector3d n = up.normalized();
  const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  const double lower = kLowerShare * part.max_size();
  Eigen::Matrix3d R = R_world_part;
  double height = centroid_height(samples, g, R, n);
  double turned = 0.0;
  while (turned <= limit_rad) {
    Eigen::Matrix3d best = R;
    double best_height = height - lower;
    for (int k = 0; k < kDirections; ++k) {
      const double a = 2.0 * std::numbers::pi * k / kDirections;
      const Eigen::Vector3d axis = std::cos(a) * e1 + std::sin(a) * e2;
      const Eigen::Matrix3d turned_R = Eigen::AngleAxisd(kStepRad, axis).toRotationMatrix() * R;
      const double h = centroid_height(samples, g, turned_R, n);
      if (h < best_height) best = turned_R, best_height = h;
    }
    if (best_height >= height - lower) break;
    R = best, height = best_height, turned += kStepRad;
  }
  return turned;
}

}  // namespace rangefit
