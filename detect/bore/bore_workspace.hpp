#pragma once
// The memory of detect_bore's calls, kept between them. Every buffer of one call is carved from
// one block (a monotonic arena: nothing is freed before the call ends, so no buffer is ever
// returned to the heap mid-call); a call that outgrew the block replaces it, at its end, by one
// as large as the call needed in all. So after one call on a scan, a call on a like scan (same
// sensor, same bore) allocates nothing: a cyclic caller sees no heap traffic and no allocator
// latency. Not shared between threads: one workspace per calling thread.

#include <cstddef>
#include <memory>
#include <memory_resource>

namespace rangefit {

class BoreWorkspace {
 public:
  BoreWorkspace() = default;
  BoreWorkspace(const BoreWorkspace&) = delete;
  BoreWorkspace& operator=(const BoreWorkspace&) = delete;
  BoreWorkspace(BoreWorkspace&&) = default;
  BoreWorkspace& operator=(BoreWorkspace&&) = default;

  std::size_t capacity() const { return size_; }  // bytes of the block the next call starts with

 private:
  friend class BoreArena;
  std::unique_ptr<std::byte[]> block_;
  std::size_t size_ = 0;  // of block_
};

// One call's arena (internal to detect/bore): over a workspace's block, or over nothing for a
// call without one. Buffers the block cannot hold come from the heap; at the end of the call the
// workspace's block grows to hold them next time.
class BoreArena {
 public:
  explicit BoreArena(BoreWorkspace* ws);
  BoreArena(const BoreArena&) = delete;
  BoreArena& operator=(const BoreArena&) = delete;
  ~BoreArena();

  std::pmr::memory_resource* resource() { return &arena_; }

 private:
  // The heap behind the block, counting what it hands out.
  class Heap final : public std::pmr::memory_resource {
   public:
    std::size_t taken = 0;

   private:
    void* do_allocate(std::size_t bytes, std::size_t align) override;
    void do_deallocate(void* p, std::size_t bytes, std::size_t align) override;
    bool do_is_equal(const std::pmr::memory_resource& o) const noexcept override;
  };

  BoreWorkspace* ws_;
  Heap heap_;
  std::pmr::monotonic_buffer_resource arena_;
};

}  // namespace rangefit
