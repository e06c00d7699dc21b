#pragma once
// Single-producer single-consumer ring between a driver's receive thread and its consumer. The
// producer side neither allocates (slots are preallocated; copy-assignment into a slot reuses
// its capacity) nor locks; publish() wakes the consumer through an eventfd, once per batch of
// pushes rather than once per sample (a write(2) per sample was the receive path's largest cost).
// A full ring drops the new sample and counts it, so a slow consumer never stalls the bus.

#include <poll.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <vector>

#include "hal/time.hpp"

namespace rangefit::drivers::can {

template <class T>
class SampleRing {
 public:
  explicit SampleRing(std::size_t capacity, const T& prototype = T{})
      : slots_(capacity < 1 ? 1 : capacity, prototype),
        efd_(eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC)) {}
  ~SampleRing() {
    if (efd_ >= 0) close(efd_);
  }
  SampleRing(const SampleRing&) = delete;
  SampleRing& operator=(const SampleRing&) = delete;

  // Producer only. False (and a counted drop) when full. The consumer sees the sample at once
  // when it polls, but a waiting consumer wakes only at the next publish().
  bool push(const T& value) {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) >= slots_.size()) {
      dropped_.fetch_add(1, std::memory_order_relaxed);
      return false;
    }
    slots_[head % slots_.size()] = value;
    head_.store(head + 1, std::memory_order_release);
    unpublished_ = true;
    return true;
  }

  // Producer only: wakes a waiting consumer if anything was pushed since the last call.
  void publish() {
    if (!unpublished_) return;
    unpublished_ = false;
    const std::uint64_t one = 1;
    (void)!write(efd_, &one, sizeof(one));
  }

  // Consumer only. Appends everything buffered to out; waits up to timeout for the first.
  std::size_t drain(std::vector<T>& out, hal::Duration timeout) {
    const hal::Timestamp deadline = hal::monotonic_now() + timeout;
    while (empty()) {
      const hal::Duration left = deadline - hal::monotonic_now();
      if (left.count() <= 0) return 0;
      pollfd pfd{efd_, POLLIN, 0};
      poll(&pfd, 1, static_cast<int>((left.count() + 999'999) / 1'000'000));
      std::uint64_t n = 0;
      (void)!read(efd_, &n, sizeof(n));
    }
    const std::uint64_t head = head_.load(std::memory_order_acquire);
    std::uint64_t tail = tail_.load(std::memory_order_relaxed);
    const std::size_t count = static_cast<std::size_t>(head - tail);
    for (; tail != head; ++tail) out.push_back(slots_[tail % slots_.size()]);
    tail_.store(tail, std::memory_order_release);
    return count;
  }

  bool empty() const {
    return head_.load(std::memory_order_acquire) == tail_.load(std::memory_order_acquire);
  }
  std::uint64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }

 private:
  std::vector<T> slots_;
  int efd_ = -1;
  std::atomic<std::uint64_t> head_{0};
  std::atomic<std::uint64_t> tail_{0};
  std::atomic<std::uint64_t> dropped_{0};
  bool unpublished_ = false;  // producer only
};

}  // namespace rangefit::drivers::can
