// The in-process transport carries exactly what SocketCAN would: classic and FD frames, filters,
// own-frame echo, a full tx queue and a downed link.
#include <gtest/gtest.h>

#include <array>

#include "test/support/inprocess_transport.hpp"

namespace rangefit::drivers::can {
namespace can_inprocess_transport_test {

constexpr auto kWait = std::chrono::milliseconds(500);

TEST(InProcessTransport, EmptyOutputSpanReceivesNothing) {
  auto [a, b] = InProcessTransport::make_pair();
  ASSERT_EQ(a->send(make_frame(0x123, {})), TxResult::kOk);
  EXPECT_EQ(b->receive({}, std::chrono::milliseconds(0)).frames, 0u);
}

TEST(InProcessTransport, ClassicAndFdFramesArriveIntactAndStamped) {
  auto [a, b] = InProcessTransport::make_pair();
  const std::array<std::uint8_t, 3> small{1, 2, 3};
  std::array<std::uint8_t, 40> big{};
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<std::uint8_t>(i);
  ASSERT_EQ(a->send(make_frame(0x181, small)), TxResult::kOk);
  ASSERT_EQ(a->send(make_fd_frame(0x3A0, big)), TxResult::kOk);
  std::array<CanFrame, 4> out{};
  const hal::Timestamp before = hal::monotonic_now();
  std::size_t got = 0;
  while (got < 2) got += b->receive(std::span(out).subspan(got), kWait).frames;
  EXPECT_EQ(out[0].id, 0x181u);
  EXPECT_EQ(out[0].len, 3);
  EXPECT_FALSE(out[0].is_fd());
  EXPECT_EQ(out[0].data[2], 3);
  EXPECT_GE(out[0].stamp, before);
  EXPECT_TRUE(out[1].is_fd());
  EXPECT_EQ(out[1].len, 48);  // 40 bytes padded to a valid FD length
  EXPECT_EQ(out[1].data[39], 39);
  EXPECT_EQ(out[1].data[45], 0);
  EXPECT_EQ(b->counters().rx_frames, 2u);
  EXPECT_EQ(a->counters().tx_frames, 2u);
}

TEST(InProcessTransport, ExactIdFilterAndOwnEchoes) {
  FrameFilter filter;
  filter.ids = {0x080, 0x181};
  filter.own_frames = true;
  auto [a, b] = InProcessTransport::make_pair(filter);
  ASSERT_EQ(a->send(make_frame(0x080, {})), TxResult::kOk);  // our SYNC, echoed
  ASSERT_EQ(b->send(make_frame(0x182, {})), TxResult::kOk);  // filtered out
  ASSERT_EQ(b->send(make_frame(0x181, {})), TxResult::kOk);
  std::array<CanFrame, 4> out{};
  std::size_t got = 0;
  for (int i = 0; i < 4 && got < 2; ++i)
    got += a->receive(std::span(out).subspan(got), kWait).frames;
  ASSERT_EQ(got, 2u);
  EXPECT_EQ(out[0].id, 0x080u);
  EXPECT_TRUE(out[0].flags & kFrameEcho);
  EXPECT_EQ(out[1].id, 0x181u);
  EXPECT_FALSE(out[1].flags & kFrameEcho);
}

TEST(InProcessTransport, FullTxQueueIsCountedNotBlocking) {
  auto [a, b] = InProcessTransport::make_pair();
  int full = 0;
  for (int i = 0; i < 100000 && full == 0; ++i) {
    if (a->send(make_frame(0x123, {})) == TxResult::kBufferFull) ++full;
  }
  EXPECT_EQ(full, 1);
  EXPECT_EQ(a->counters().tx_buffer_full, 1u);
}

TEST(InProcessTransport, DownedLinkIsReportedUntilItComesBack) {
  auto [a, b] = InProcessTransport::make_pair();
  a->set_link_down(true);
  std::array<CanFrame, 1> out{};
  EXPECT_EQ(a->send(make_frame(0x1, {})), TxResult::kLinkDown);
  EXPECT_TRUE(a->receive(out, kWait).link_down);
  EXPECT_FALSE(a->reopen().ok);
  a->set_link_down(false);
  EXPECT_TRUE(a->reopen().ok);
  EXPECT_EQ(a->send(make_frame(0x1, {})), TxResult::kOk);
}

}  // namespace can_inprocess_transport_test
}  // namespace rangefit::drivers::can
