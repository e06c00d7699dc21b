#include "detect/bore/bore_workspace.hpp"

#include <new>

namespace rangefit {

void* BoreArena::Heap::do_allocate(std::size_t bytes, std::size_t align) {
  void* p = std::pmr::new_delete_resource()->allocate(bytes, align);
  taken += bytes;
  return p;
}

void BoreArena::Heap::do_deallocate(void* p, std::size_t bytes, std::size_t align) {
  std::pmr::new_delete_resource()->deallocate(p, bytes, align);
}

bool BoreArena::Heap::do_is_equal(const std::pmr::memory_resource& o) const noexcept {
  return this == &o;
}

BoreArena::BoreArena(BoreWorkspace* ws)
    : ws_(ws),
      arena_(ws ? ws->block_.get() : nullptr, ws ? ws->size_ : 0, &heap_) {}

BoreArena::~BoreArena() {
  if (!ws_ || heap_.taken == 0) return;
  arena_.release();  // the call's buffers are gone: the heap's share goes back first
  // The block and what the heap added, and a quarter more (a slightly denser scan still fits).
  // Without memory for it, the old block stays.
  const std::size_t size = ws_->size_ + heap_.taken + heap_.taken / 4;
  if (std::byte* grown = new (std::nothrow) std::byte[size]) {
    ws_->block_.reset(grown);
    ws_->size_ = size;
  }
}

}  // namespace rangefit
