#include "daemon/service/bore_shape_json.hpp"
#include "daemon/service/json_codec.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rangefit::daemon {
namespace {

constexpr double kMaxHalfAngle = 80.0 * std::numbers::pi / 180.0;

}  // namespace

nlohmann::json bore_shape_json(const BoreShape& s) {
  nlohmann::json j;
  // The standard errors' keys carry their units, as a cylinder's do (bore_fit_json.hpp).
  nlohmann::json sigma = {{"radius_mm", s.sigma_radius},
                          {"entrance_mm", s.sigma_entrance},
                          {"axis_rad", s.sigma_axis}};
  j["model"] = s.cone ? "cone" : "ellipse";
  if (s.cone) {
    j["half_angle"] = s.half_angle;
    sigma["half_angle_rad"] = s.sigma_half_angle;
    if (s.cylinder_radius > 0.0) {
      j["cylinder_radius"] = s.cylinder_radius;
      sigma["cylinder_radius_mm"] = s.sigma_cylinder_radius;
    }
  } else {
    j["radius2"] = s.radius2;
    j["major_axis"] = json_vec(s.major_axis);
    sigma["radius2_mm"] = s.sigma_radius2;
    sigma["major_axis_rad"] = s.sigma_major_axis;
  }
  j["sigma"] = sigma;
  j["rms"] = s.rms;
  j["seeded_by_rsf"] = s.seeded_by_rsf;
  return j;
}

std::optional<BoreShape> bore_shape_from_json(const nlohmann::json& j) {
  if (!j.is_object() || !j.contains("model")) return std::nullopt;
  const std::string model = j.at("model").get<std::string>();
  if (model == "cylinder") return std::nullopt;  // `rangefit bore --json` of a plain bore
  if (model != "cone" && model != "ellipse") {
    throw std::invalid_argument("bore model \"" + model + "\" is not cylinder, cone or ellipse");
  }
  BoreShape s;
  s.cone = model == "cone";
  if (s.cone) {
    s.half_angle = j.at("half_angle").get<double>();
    s.cylinder_radius = j.value("cylinder_radius", 0.0);
    if (!(s.half_angle > 0.0 && s.half_angle < kMaxHalfAngle) || !(s.cylinder_radius >= 0.0)) {
      throw std::invalid_argument(
          "a cone needs 0 < half_angle < 80 deg (rad) and "
          "cylinder_radius >= 0");
    }
  } else {
    s.radius2 = j.at("radius2").get<double>();
    const auto& m = j.at("major_axis");
    s.major_axis = {m.at(0).get<double>(), m.at(1).get<double>(), m.at(2).get<double>()};
    if (!(s.radius2 > 0.0 && std::isfinite(s.radius2)) || !s.major_axis.allFinite() ||
        !(s.major_axis.norm() > 0.0)) {
      throw std::invalid_argument("an ellipse needs radius2 > 0 and a major_axis");
    }
    s.major_axis.normalize();
  }
  const nlohmann::json sigma = j.value("sigma", nlohmann::json::object());
  // A result written before the keys carried units ("radius", ...) reads the same.
  const auto error = [&](const char* key, const char* unit) {
    return sigma.value(std::string(key) + "_" + unit, sigma.value(key, 0.0));
  };
  s.sigma_radius = error("radius", "mm");
  s.sigma_entrance = error("entrance", "mm");
  s.sigma_axis = error("axis", "rad");
  s.sigma_half_angle = error("half_angle", "rad");
  s.sigma_cylinder_radius = error("cylinder_radius", "mm");
  s.sigma_radius2 = error("radius2", "mm");
  s.sigma_major_axis = error("major_axis", "rad");
  s.rms = j.value("rms", 0.0);
  s.seeded_by_rsf = j.value("seeded_by_rsf", false);
  return s;
}

}  // namespace rangefit::daemon
