// detect/common/parallel_for.hpp: every index once on any number of threads, and an exception
// thrown by an item reaches the caller instead of ending the program.
#include "detect/common/parallel_for.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

namespace rangefit {
namespace {

TEST(ParallelFor, EveryIndexOnceOnAnyNumberOfThreads) {
  for (int threads : {0, 1, 2, 7}) {
    std::vector<std::atomic<int>> runs(1000);
    parallel_for(runs.size(), threads, [&](std::size_t i) { ++runs[i]; });
    for (std::size_t i = 0; i < runs.size(); ++i) {
      ASSERT_EQ(runs[i].load(), 1) << "index " << i << ", threads " << threads;
    }
  }
  int calls = 0;
  parallel_for(0, 4, [&](std::size_t) { ++calls; });
  EXPECT_EQ(calls, 0);
}

TEST(ParallelFor, AnItemsExceptionReachesTheCaller) {
  for (int threads : {1, 3}) {
    std::atomic<int> done{0};
    EXPECT_THROW(parallel_for(500, threads,
                              [&](std::size_t i) {
                                if (i == 37) throw std::runtime_error("item 37");
                                ++done;
                              }),
                 std::runtime_error)
        << threads;
    EXPECT_LT(done.load(), 500) << threads;
  }
}

}  // namespace
}  // namespace rangefit
