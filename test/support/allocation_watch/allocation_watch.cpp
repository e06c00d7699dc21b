#include "test/support/allocation_watch/allocation_watch.hpp"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <new>

// The replacement operator new is malloc-based, so its operator delete frees; GCC's
// -Wmismatched-new-delete cannot see that the two are a pair once inlined.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

namespace {

std::atomic<bool> g_watch{false};
std::atomic<std::size_t> g_count{0}, g_largest{0};

void note(std::size_t size) {
  if (!g_watch.load(std::memory_order_relaxed)) return;
  g_count.fetch_add(1, std::memory_order_relaxed);
  std::size_t seen = g_largest.load(std::memory_order_relaxed);
  while (size > seen && !g_largest.compare_exchange_weak(seen, size, std::memory_order_relaxed)) {
  }
}

}  // namespace

void* operator new(std::size_t size) {
  note(size);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
// The aligned forms too: std::pmr's heap resource allocates with them.
void* operator new(std::size_t size, std::align_val_t align) {
  note(size);
  const auto a = static_cast<std::size_t>(align);
  if (void* p = std::aligned_alloc(a, (std::max<std::size_t>(size, 1) + a - 1) / a * a)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace rangefit::test {

void start_watching_allocations() {
  g_count = 0;
  g_largest = 0;
  g_watch = true;
}

AllocationStats stop_watching_allocations() {
  g_watch = false;
  return {g_count.load(), g_largest.load()};
}

}  // namespace rangefit::test
