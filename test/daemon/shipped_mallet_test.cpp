// The shipped demo scene and the shipped model describe the same mallet: data/scenes/
// cluttered_mallet.toml's head and shaft have the part sizes of data/models/mallet.toml and the
// link between them is within what the detector accepts as that link (eq. 5.5-5.6, and the
// bearings of PartLink).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "detect/object/object_detector.hpp"
#include "io/object_model_file.hpp"
#include "sim/scene_loader.hpp"

namespace rangefit {
namespace shipped_mallet_test {

TEST(ShippedMallet, SceneAndModelAgreeOnPartsAndTheirLink) {
  const std::filesystem::path data = std::filesystem::path(RANGEFIT_SOURCE_DIR) / "data";
  const sim::Scene scene = sim::load_scene((data / "scenes/cluttered_mallet.toml").string());
  const ObjectModel model = io::read_object_model(data / "models/mallet.toml");
  ASSERT_EQ(model.parts.size(), 2u);
  ASSERT_EQ(model.links.size(), 1u);
  Eigen::Isometry3d pose[2];
  for (int p = 0; p < 2; ++p) {
    const std::string name = "mallet/" + model.parts[p].name;
    const sim::SceneObject* found = nullptr;
    for (const auto& o : scene.objects) found = o.name == name ? &o : found;
    ASSERT_NE(found, nullptr) << name;
    const auto* sq = std::get_if<sim::SuperquadricShape>(&found->shape);
    ASSERT_NE(sq, nullptr) << name;
    const Superquadric& m = model.parts[p].shape;
    EXPECT_EQ(sq->model.a1, m.a1) << name;
    EXPECT_EQ(sq->model.a2, m.a2) << name;
    EXPECT_EQ(sq->model.a3, m.a3) << name;
    EXPECT_EQ(sq->model.eps1, m.eps1) << name;
    EXPECT_EQ(sq->model.eps2, m.eps2) << name;
    pose[p] = found->T_world_object;
    // Resting on the table (z = 0): the part's lowest point is at z = 0.
    const Eigen::Vector3d up = pose[p].linear().transpose() * Eigen::Vector3d::UnitZ();
    const double half_height =
        std::abs(up.x()) * m.a1 + std::abs(up.y()) * m.a2 + std::abs(up.z()) * m.a3;
    EXPECT_NEAR(pose[p].translation().z(), half_height, 1e-6) << name;
  }
  const PartLink& link = model.links[0];
  const ObjectDetectOptions o;
  const double angle = std::acos(std::abs(pose[0].linear().col(2).dot(pose[1].linear().col(2))));
  EXPECT_NEAR(angle, link.angle_rad, 1e-3);
  const double distance = (pose[0].translation() - pose[1].translation()).norm();
  EXPECT_LT(std::abs(distance - link.distance_mm),
            0.25 * o.link_distance_tolerance * link.distance_mm);
  // The shaft's centre in the head's middle plane, its axis pointing at the head's centre.
  ASSERT_TRUE(link.bearing_rad.has_value());
  const Eigen::Vector3d line = (pose[1].translation() - pose[0].translation()).normalized();
  for (int p = 0; p < 2; ++p) {
    EXPECT_NEAR(std::acos(std::min(1.0, std::abs(pose[p].linear().col(2).dot(line)))),
                (*link.bearing_rad)[static_cast<std::size_t>(p)], 1e-3)
        << model.parts[static_cast<std::size_t>(p)].name;
  }
}

}  // namespace shipped_mallet_test
}  // namespace rangefit
