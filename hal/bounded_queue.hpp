#pragma once
// Bounded multi-producer queue between a device thread and its consumer. push() never blocks:
// when full it drops the new sample and counts it, so a slow consumer cannot stall a driver.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <vector>

namespace rangefit::hal {

template <class T>
class BoundedQueue {
 public:
  explicit BoundedQueue(std::size_t capacity) : capacity_(capacity) {}

  // Returns false (and counts a drop) when the queue is full.
  bool push(T value) {
    {
      std::lock_guard lock(mutex_);
      if (items_.size() >= capacity_) {
        ++dropped_;
        return false;
      }
      items_.push_back(std::move(value));
    }
    cv_.notify_one();
    return true;
  }

  // Moves all queued items into out; waits up to timeout for the first. Returns the count.
  template <class Rep, class Period>
  std::size_t drain(std::vector<T>& out, std::chrono::duration<Rep, Period> timeout) {
    std::unique_lock lock(mutex_);
    if (items_.empty()) cv_.wait_for(lock, timeout, [&] { return !items_.empty(); });
    const std::size_t n = items_.size();
    for (auto& item : items_) out.push_back(std::move(item));
    items_.clear();
    return n;
  }

  std::uint64_t dropped() const {
    std::lock_guard lock(mutex_);
    return dropped_;
  }
  std::size_t size() const {
    std::lock_guard lock(mutex_);
    return items_.size();
  }

 private:
  const std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<T> items_;
  std::uint64_t dropped_ = 0;
};

}  // namespace rangefit::hal
