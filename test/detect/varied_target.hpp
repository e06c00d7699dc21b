#pragma once
// The target of a varied tuning scene (sim/varied_scene.hpp) must be found where it stands: the
// check of the object tests that pin a fixed seed, with the rejections in the message.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "detect/object/object_detector.hpp"
#include "sim/varied_scene.hpp"
#include "test/detect/object_scenes.hpp"
#include "test/detect/stripe_scan_fixture.hpp"

namespace rangefit::test {

// The reason and every rejection (check, value, where).
inline std::string describe_rejections(const ObjectDetectResult& r) {
  std::string out = to_string(r.reason);
  for (const Rejection& x : r.rejections) {
    out += std::string("; ") + to_string(x.check) + " " + std::to_string(x.value) + " at " +
           std::to_string(x.centre.x()) + " " + std::to_string(x.centre.y());
  }
  return out;
}

// The object-free varied tuning scene of `seed`: the seed draws the model it is searched for.
inline sim::VariedScene object_free_scene(std::uint64_t seed, bool pan_tilt = false) {
  sim::VariedSceneOptions so;
  so.target = sim::VariedTarget::kNone;
  so.pan_tilt = pan_tilt;
  return sim::make_varied_scene(so, seed);
}

inline void expect_varied_target_found(sim::VariedTarget target, std::uint64_t seed,
                                       bool pan_tilt = false) {
  sim::VariedSceneOptions so;
  so.target = target;
  so.pan_tilt = pan_tilt;
  const sim::VariedScene s = sim::make_varied_scene(so, seed);
  const ObjectDetectResult r = detect_in(s, seed);
  ASSERT_TRUE(r.found()) << "seed " << seed << ": " << describe_rejections(r);
  // A sphere has no axis to check, only its centre.
  const bool axis = target != sim::VariedTarget::kSphere;
  EXPECT_TRUE(true_positive(r.instances[0].parts[0].T_world_part,
                            s.parts[static_cast<std::size_t>(s.target_parts[0])], axis))
      << "seed " << seed << ": " << describe_rejections(r);
}

}  // namespace rangefit::test
