#pragma once
// Ray casting against a Scene through Embree 3: triangle meshes natively, analytic primitives as
// Embree user geometry. Embree (float) finds which surface a ray meets first; the hit point is
// then recomputed in double against that triangle or primitive, so points on analytic surfaces
// are exact to ~1e-9 mm. Batches go through Embree's ray streams (rtcIntersect1M/rtcOccluded1M).
//
// Thread-safety: const methods may be called from several threads at once.
// Errors: the constructor throws std::runtime_error when Embree cannot be set up.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <span>

#include "sim/scene.hpp"

namespace rangefit::sim {

struct Ray {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // mm, scene frame
  Eigen::Vector3d dir = Eigen::Vector3d::UnitZ();    // unit
  double t_min = 0.0;                                // mm along dir
  double t_max = 1e9;
};

struct Hit {
  bool valid = false;
  double t = 0.0;                                    // mm along the ray
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   // mm, scene frame
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit, facing the ray's side not guaranteed
  int object = -1;                                   // index into Scene::objects
};

class RayCaster {
 public:
  explicit RayCaster(const Scene& scene);
  ~RayCaster();
  RayCaster(RayCaster&&) noexcept;
  RayCaster& operator=(RayCaster&&) noexcept;

  Hit cast(const Ray& ray) const;
  // hits.size() must equal rays.size(); extra entries are left untouched.
  void cast(std::span<const Ray> rays, std::span<Hit> hits) const;
  // True when something lies on the ray within (t_min, t_max).
  bool occluded(const Ray& ray) const;
  void occluded(std::span<const Ray> rays, std::span<std::uint8_t> blocked) const;

  // The same first hit without Embree: every triangle and primitive tested in turn. The baseline
  // the benchmark compares against, and a cross-check in tests.
  Hit cast_brute_force(const Ray& ray) const;

  std::size_t triangle_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rangefit::sim
