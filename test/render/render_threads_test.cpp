// Pictures drawn from several threads at once, as two services in one process (or the service and
// a command) draw them, each thread freeing the font caches after its picture as the service does:
// every picture must come out whole, with its legend text.
#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "render/render.hpp"
#include "test/render/picture_checks.hpp"

namespace rangefit::render {
namespace render_threads_test {

// Pixels of the legend strip that are not background: the text.
int legend_ink(const Rendering& r) {
  int ink = 0;
  for (int y = r.sensor.y0 + r.sensor.view.height; y < r.image.height; ++y) {
    for (int x = 0; x < r.image.width; ++x) ink += r.image.at(x, y) == kBackground ? 0 : 1;
  }
  return ink;
}

TEST(RenderThreads, PicturesDrawnConcurrentlyWithCacheReleasesAreAllWhole) {
  const sim::SyntheticBoreScan scan = test::clean_bore();
  const sim::SyntheticBoreTruth& t = scan.truth;
  Drawing drawing;
  drawing.bores.push_back({t.entrance, t.axis, t.radius, t.plane_normal, 6.0 * t.radius, {}});
  drawing.legend = {"bore: radius 5.000 mm", "entrance 0.000 0.000 0.000"};
  RenderOptions o;
  o.panel_width = o.panel_height = 160;
  const int reference = legend_ink(render_scan(scan.cloud, drawing, o));
  release_font_caches();
  ASSERT_GT(reference, 100) << "the legend has text";

  constexpr int kThreads = 4, kPictures = 15;
  std::vector<int> whole(kThreads, 0);
  std::vector<std::thread> threads;
  for (int k = 0; k < kThreads; ++k) {
    threads.emplace_back([&, k] {
      for (int i = 0; i < kPictures; ++i) {
        const Rendering r = render_scan(scan.cloud, drawing, o);
        whole[k] += legend_ink(r) == reference ? 1 : 0;
        release_font_caches();
      }
    });
  }
  for (auto& th : threads) th.join();
  for (int k = 0; k < kThreads; ++k) EXPECT_EQ(whole[k], kPictures) << "thread " << k;
}

}  // namespace render_threads_test
}  // namespace rangefit::render
