#pragma once
// f(i) for every i in [0, n) on up to `threads` threads (0: one per core), the caller's among
// them; each thread takes the next index not yet taken, so a few slow items do not leave the
// others idle. f must write only what index i owns: then the results do not depend on the
// number of threads or on which thread ran which index (the detector's hypotheses, the model
// learning's starts). An exception thrown by f ends the items not yet taken and is rethrown to
// the caller once every thread has stopped; when no more threads can be started, those running
// do all the items.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace rangefit {

// The threads asked for: `threads`, or one per core for 0 (or less).
inline std::size_t thread_count(int threads) {
  if (threads > 0) return static_cast<std::size_t>(threads);
  return std::max<std::size_t>(1, std::thread::hardware_concurrency());
}

template <class F>
void parallel_for(std::size_t n, int threads, F&& f) {
  const std::size_t workers = std::min(n, thread_count(threads));
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto work = [&] {
    try {
      for (std::size_t i = next++; i < n; i = next++) f(i);
    } catch (...) {
      next = n;
      const std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t w = 1; w < workers; ++w) {
    try {
      pool.emplace_back(work);
    } catch (const std::system_error&) {
      break;
    }
  }
  work();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace rangefit
