#include "sim/daily_objects.hpp"

#include <numbers>

namespace rangefit::sim {

std::vector<DailyObject> daily_life_objects() {
  // Table 5.6: a1 a2 a3 (mm), eps1 eps2, kx ky.
  const auto one = [](const char* name, const Superquadric& sq) {
    return DailyObject{name, "5.6", single(name, sq)};
  };
  std::vector<DailyObject> out = {
      one("cuboid", {15, 25, 35, 0.1, 0.1, 0.0, 0.0}),
      one("sphere", {25, 25, 25, 1.0, 1.0, 0.0, 0.0}),
      one("cylinder", {25, 25, 35, 0.1, 1.0, 0.0, 0.0}),
      one("pyramid", {8, 8, 22, 0.1, 0.1, -0.9, -0.9}),
      one("bowl", {60, 60, 20, 0.4, 1.0, 0.3, 0.3}),
      one("mouse", {45, 35, 20, 0.8, 0.5, -0.3, 0.0}),
      one("mug", {40, 40, 50, 0.1, 1.0, 0.0, 0.0}),
      one("cup", {34, 34, 68, 0.1, 1.0, 0.2, 0.2}),
      one("sponge", {42, 25, 11, 0.1, 0.1, 0.0, 0.0}),
  };
  // Table 5.7: body 38 38 48 e 0.1 1; handle 30 23 8 e 0.5 1; 90 deg, 50 mm.
  ObjectModel mug;
  mug.name = "mug-2";
  mug.parts = {{"body", {38, 38, 48, 0.1, 1.0, 0.0, 0.0}},
               {"handle", {30, 23, 8, 0.5, 1.0, 0.0, 0.0}}};
  mug.links = {{0, 1, std::numbers::pi / 2.0, 50.0,
                std::array<double, 2>{std::numbers::pi / 2.0, std::numbers::pi / 2.0}}};
  out.push_back({"mug-2", "5.7", mug});
  return out;
}

TableObject standing_mug(const std::string& name, const ObjectModel& mug) {
  const Superquadric& body = mug.parts.at(0).shape;
  const double d = mug.links.at(0).distance_mm;
  Eigen::Isometry3d Tb = Eigen::Isometry3d::Identity();
  Tb.translation() = Eigen::Vector3d(0.0, 0.0, body.a3);
  Eigen::Isometry3d Th = Eigen::Isometry3d::Identity();
  // Columns: x away from the body, y up, z across (x cross y).
  Th.linear().col(0) = Eigen::Vector3d::UnitX();
  Th.linear().col(1) = Eigen::Vector3d::UnitZ();
  Th.linear().col(2) = -Eigen::Vector3d::UnitY();
  Th.translation() = Eigen::Vector3d(d, 0.0, body.a3);
  return TableObject{name,
                     {ScenePart{name + "/body", body, Tb},
                      ScenePart{name + "/handle", mug.parts.at(1).shape, Th}}};
}

TableObject resting_daily_object(const DailyObject& object, double x, double y,
                                 std::mt19937_64& rng, double p_standing) {
  std::uniform_real_distribution<double> yaw(0.0, 2.0 * std::numbers::pi);
  if (object.model.parts.size() > 1) {
    TableObject o = standing_mug(object.name, object.model);
    place(o, x, y, yaw(rng));
    return o;
  }
  const Superquadric& sq = object.model.parts[0].shape;
  TableObject o = resting_part(object.name, sq, rest_of(sq), rng, p_standing);
  place(o, x, y, yaw(rng));
  return o;
}

}  // namespace rangefit::sim
