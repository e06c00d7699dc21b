#include "detect/object_detector.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "test/detect/object_scenes.hpp"

namespace rangefit {
namespace {

using test::Scene;

const Scene& fig_scene() {
  static const Scene s = test::fig_5_18_scene();
  return s;
}

int true_positives(const ObjectModel& model, const Scene& scene, std::size_t truth_index, int seeds,
                   ObjectDetectOptions o, bool check_axis) {
  int tp = 0;
  for (int s = 0; s < seeds; ++s) {
    o.seed = static_cast<std::uint64_t>(s + 1);
    const ObjectDetectResult r = detect_object(model, scene.rendered.cloud.points, o);
    if (r.found() && test::true_positive(r.instances[0].parts[0].T_world_part,
                                         scene.parts[truth_index], check_axis)) {
      ++tp;
    } else if (r.found()) {
      const auto& T = r.instances[0].parts[0].T_world_part;
      std::printf("  miss seed %d: c=(%.1f %.1f %.1f) z=(%.2f %.2f %.2f) M=%.3f I=%zu S=%zu\n",
                  s + 1, T.translation().x(), T.translation().y(), T.translation().z(),
                  T.linear()(0, 2), T.linear()(1, 2), T.linear()(2, 2),
                  r.instances[0].parts[0].scores.measure, r.instances[0].parts[0].scores.interior,
                  r.instances[0].parts[0].scores.surface);
    }
  }
  return tp;
}

TEST(ObjectDetector, FindsEachFigure518PrimitiveForMostSeeds) {
  const Scene& scene = fig_scene();
  std::printf("scene points %zu\n", scene.rendered.cloud.size());
  const char* names[] = {"cylinder", "box", "sphere", "cone"};
  const Superquadric models[] = {test::cylinder_model(), test::box_model(), test::sphere_model(),
                                 test::cone_model()};
  ObjectDetectOptions o;
  o.viewpoint = scene.eye;
  const int seeds = 10;
  for (std::size_t i = 0; i < 4; ++i) {
    const int tp = true_positives(test::single(names[i], models[i]), scene, i, seeds, o, i != 2);
    std::printf("%s: %d/%d\n", names[i], tp, seeds);
  }
}

}  // namespace
}  // namespace rangefit
