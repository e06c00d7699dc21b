#pragma once
// The heap allocations of a piece of code: how many, and the largest. Linking this library
// replaces operator new (every form) for the whole test program, so only the programs that
// measure allocations link it. Watches one piece of code at a time.

#include <cstddef>
#include <utility>

namespace rangefit::test {

struct AllocationStats {
  std::size_t count = 0;    // calls of any operator new
  std::size_t largest = 0;  // bytes of the largest single one
};

void start_watching_allocations();
AllocationStats stop_watching_allocations();

template <class F>
AllocationStats allocations_of(F&& f) {
  start_watching_allocations();
  std::forward<F>(f)();
  return stop_watching_allocations();
}

}  // namespace rangefit::test
