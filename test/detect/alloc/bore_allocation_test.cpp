// Allocations of the bore pipeline's hot path: with a workspace kept between calls, a call on a
// scan like the one before allocates nothing (its buffers keep their capacity), so a cyclic
// caller sees no heap traffic and no allocator latency. Counted by test/support's
// allocation_watch (operator new replaced in this test program only).
#include <gtest/gtest.h>

#include <cstdio>
#include <utility>

#include "detect/bore/bore_detector.hpp"
#include "test/bench/bore_bench_scan.hpp"
#include "test/detect/bore_test_cases.hpp"
#include "test/support/allocation_watch/allocation_watch.hpp"

namespace rangefit {
namespace bore_allocation_test {

template <class F>
std::size_t allocations(F&& f) {
  return test::allocations_of(std::forward<F>(f)).count;
}

// The CSS-density cases of the bore benchmark (Ø4 blind to a Ø50 bore with a ~60,000-point
// region): the first call sizes the workspace, the next calls on the same scan and on another
// seed of it (other noise, outliers and ghosts) allocate nothing and give the same answer as a
// call without a workspace.
TEST(BoreAllocations, NoneOnceTheWorkspaceHoldsALikeScan) {
  for (const auto& c : bench::css_bore_cases()) {
    const auto scan = sim::make_synthetic_bore(c.scan);
    sim::SyntheticBoreOptions other_seed = c.scan;
    other_seed.seed += 1000;
    const auto like = sim::make_synthetic_bore(other_seed);
    BoreOptions o;
    o.view_dir = scan.truth.view_dir;
    const BorePrior prior = bench::css_prior(scan.truth);
    BoreWorkspace ws;
    BoreResult first, again, next;
    const std::size_t a_first = allocations([&] { first = detect_bore(scan.cloud, prior, o, ws); });
    const std::size_t a_again = allocations([&] { again = detect_bore(scan.cloud, prior, o, ws); });
    const std::size_t a_next = allocations([&] { next = detect_bore(like.cloud, prior, o, ws); });
    const BoreResult plain = detect_bore(scan.cloud, prior, o);
    std::printf("%-9s allocations: first call %zu, same scan %zu, other seed %zu; workspace %zu kB\n",
                c.name, a_first, a_again, a_next, ws.capacity() / 1024);
    ASSERT_TRUE(first.found) << c.name << ": " << to_string(first.reason);
    ASSERT_TRUE(next.found) << c.name << ": " << to_string(next.reason);
    EXPECT_EQ(a_again, 0u) << c.name;
    EXPECT_EQ(a_next, 0u) << c.name;
    EXPECT_EQ(again.entrance, first.entrance) << c.name;
    EXPECT_EQ(plain.entrance, first.entrance) << c.name;
    EXPECT_EQ(plain.axis, first.axis) << c.name;
    EXPECT_EQ(plain.radius, first.radius) << c.name;
  }
}

// The same for the cone and elliptic bores (a countersink, a pure cone, a taper, an ellipse at
// the CSS's density), whose model fit replaces the cylinder's.
TEST(BoreAllocations, NoneForConesAndEllipsesOnceTheWorkspaceHoldsALikeScan) {
  for (const test::ShapeKind kind : {test::ShapeKind::kCountersink, test::ShapeKind::kCone,
                                     test::ShapeKind::kTaper, test::ShapeKind::kEllipse}) {
    const auto scan = sim::make_synthetic_bore(test::shape_scan_options(kind, 1));
    const auto like = sim::make_synthetic_bore(test::shape_scan_options(kind, 2));
    const BorePrior prior = test::shape_prior(scan.truth, 1);
    BoreOptions o;
    o.view_dir = scan.truth.view_dir;
    BoreWorkspace ws;
    BoreResult first, next;
    const std::size_t a_first = allocations([&] { first = detect_bore(scan.cloud, prior, o, ws); });
    const std::size_t a_next = allocations([&] { next = detect_bore(like.cloud, prior, o, ws); });
    const BoreResult plain = detect_bore(scan.cloud, prior, o);
    const int k = static_cast<int>(kind);
    std::printf("shape %d allocations: first call %zu, other seed %zu\n", k, a_first, a_next);
    ASSERT_TRUE(first.found) << k << ": " << to_string(first.reason);
    ASSERT_TRUE(first.shape.has_value()) << k;
    EXPECT_EQ(a_next, 0u) << k;
    EXPECT_EQ(plain.entrance, first.entrance) << k;
    EXPECT_EQ(plain.shape->half_angle, first.shape->half_angle) << k;
    EXPECT_EQ(plain.shape->radius2, first.shape->radius2) << k;
  }
}

}  // namespace bore_allocation_test
}  // namespace rangefit
