#include "hal/bounded_queue.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace rangefit::hal {
namespace bounded_queue_test {

using namespace std::chrono_literals;

TEST(BoundedQueue, DrainOfEmptyQueueTimesOutWithNothing) {
  BoundedQueue<int> q(4);
  std::vector<int> out;
  EXPECT_EQ(q.drain(out, 1ms), 0u);
  EXPECT_TRUE(out.empty());
}

TEST(BoundedQueue, FullQueueDropsNewSamplesAndCountsThem) {
  BoundedQueue<int> q(2);
  EXPECT_TRUE(q.push(1));
  EXPECT_TRUE(q.push(2));
  EXPECT_FALSE(q.push(3));
  EXPECT_EQ(q.dropped(), 1u);
  std::vector<int> out;
  EXPECT_EQ(q.drain(out, 0ms), 2u);
  EXPECT_EQ(out, (std::vector<int>{1, 2}));
}

TEST(BoundedQueue, DrainWakesWhenAProducerPushes) {
  BoundedQueue<int> q(8);
  std::thread producer([&] {
    std::this_thread::sleep_for(5ms);
    q.push(42);
  });
  std::vector<int> out;
  EXPECT_EQ(q.drain(out, 5s), 1u);
  producer.join();
  EXPECT_EQ(out.front(), 42);
}

}  // namespace bounded_queue_test
}  // namespace rangefit::hal
