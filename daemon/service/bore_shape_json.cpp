#include "daemon/service/bore_shape_json.hpp"

namespace rangefit::daemon {
namespace {

nlohmann::json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

nlohmann::json bore_shape_json(const BoreShape& s) {
  nlohmann::json j;
  nlohmann::json sigma = {
      {"radius", s.sigma_radius}, {"entrance", s.sigma_entrance}, {"axis", s.sigma_axis}};
  j["model"] = s.cone ? "cone" : "ellipse";
  if (s.cone) {
    j["half_angle"] = s.half_angle;
    sigma["half_angle"] = s.sigma_half_angle;
    if (s.cylinder_radius > 0.0) {
      j["cylinder_radius"] = s.cylinder_radius;
      sigma["cylinder_radius"] = s.sigma_cylinder_radius;
    }
  } else {
    j["radius2"] = s.radius2;
    j["major_axis"] = vec(s.major_axis);
    sigma["radius2"] = s.sigma_radius2;
    sigma["major_axis"] = s.sigma_major_axis;
  }
  j["sigma"] = sigma;
  j["rms"] = s.rms;
  j["seeded_by_rsf"] = s.seeded_by_rsf;
  return j;
}

}  // namespace rangefit::daemon
