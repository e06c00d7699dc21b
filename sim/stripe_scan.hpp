#pragma once
// A laser-stripe scan of posed superquadric parts on a table (table frame, z up, surface z = 0,
// mm): for every profile of a StripeSweep and every fan ray, the first surface the ray meets (the
// exact intersection of sim/superquadric_raycast.hpp, culled by bounding spheres) is lit; it is
// measured only when it faces the camera and the segment to the camera is clear of every part,
// so laser and camera shadows both fall out. The range then gets Gaussian noise along the laser
// ray and a small share of outliers on the same ray (a wrong peak on the chip), so every point
// stays in the laser plane of the profile that measured it.

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "detect/common/point_cloud.hpp"
#include "sim/stripe_sweep.hpp"
#include "sim/superquadric_raycast.hpp"

namespace rangefit::sim {

inline constexpr std::int32_t kTableLabel = -1;
inline constexpr std::int32_t kOutlierLabel = -2;

// The parts and the table as rays see them. Holds a copy of the parts.
class PartCaster {
 public:
  // table: the table top's extent (z = 0); rays past it get no return.
  explicit PartCaster(std::vector<ScenePart> parts,
                      Eigen::AlignedBox2d table = Eigen::AlignedBox2d(Eigen::Vector2d(-1e4, -1e4),
                                                                      Eigen::Vector2d(1e4, 1e4)));

  struct Hit {
    std::int32_t label = kTableLabel;  // part index or kTableLabel
    double t = 0.0;                    // origin + t * dir
  };
  // Nearest surface in (0, t_max] along origin + t dir among the table and the parts listed in
  // `candidates` (all parts when null).
  std::optional<Hit> first_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                               double t_max, const std::vector<int>* candidates = nullptr) const;
  // True when a part other than `skip` crosses the open segment a -> b (ends excluded by 1e-3 mm).
  bool blocked(const Eigen::Vector3d& a, const Eigen::Vector3d& b, int skip = -1) const;
  // Outward unit normal of the surface hit by `label` at p.
  Eigen::Vector3d normal(std::int32_t label, const Eigen::Vector3d& p) const;

  const std::vector<ScenePart>& parts() const { return parts_; }
  const Eigen::Vector3d& sphere_centre(int i) const { return centres_[i]; }
  double sphere_radius(int i) const { return radii_[i]; }

 private:
  std::vector<ScenePart> parts_;
  std::vector<Eigen::Vector3d> centres_;  // a sphere holding each part (stripe_scan.cpp)
  std::vector<double> radii_;
  Eigen::AlignedBox2d table_;
};

// The cameras of a profile that see a lit point: it faces them and no other part is between.
struct SeenBy {
  std::array<Eigen::Vector3d, 2> camera{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  int count = 0;
};
SeenBy cameras_seeing(const PartCaster& caster, const ProfilePose& pose, const Eigen::Vector3d& p,
                      std::int32_t label);

// What fan ray `dir` of the profile at `pose` measures before noise: the lit surface, if a camera
// sees it. range_mm is along the unit ray from the apex.
struct Measurement {
  std::int32_t label = kTableLabel;
  double range_mm = 0.0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  SeenBy seen_by;
};
std::optional<Measurement> measure_ray(const PartCaster& caster, const ProfilePose& pose,
                                       const Eigen::Vector3d& dir, double max_range_mm = 1e5,
                                       const std::vector<int>* candidates = nullptr);

struct ScanNoise {
  double sigma_mm = 0.0;       // along the laser ray
  double outlier_share = 0.0;  // of the measured points, moved to 0.6-1.05 of their range
  std::uint64_t seed = 1;
};

struct StripeScan {
  // Table frame; organised: grid rows are profiles, columns fan rays (-1 where no return).
  PointCloud cloud;
  std::vector<std::int32_t> label;    // per point: part index, kTableLabel or kOutlierLabel
  std::vector<std::int32_t> profile;  // per point: the profile (sweep.position(profile)) it is on
};

// threads 0: all cores. The result does not depend on the thread count (noise is drawn per
// profile from the seed).
StripeScan scan_stripe(const PartCaster& caster, const StripeSweep& sweep, const ScanNoise& noise,
                       int threads = 0);

}  // namespace rangefit::sim
