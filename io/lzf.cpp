#include "io/lzf.hpp"

#include <liblzf/lzf.h>

#include <limits>

namespace rangefit::io::detail {

// liblzf is built with CHECK_INPUT (its default), so a malformed stream or one that would run
// past out_size returns 0 instead of reading or writing out of bounds. Its lengths are unsigned
// int; PCD stores both sizes as uint32, so anything larger is malformed anyway.
bool lzf_decompress(std::string_view in, char* out, std::size_t out_size) {
  constexpr std::size_t kMax = std::numeric_limits<unsigned int>::max();
  if (in.size() > kMax || out_size > kMax) return false;
  if (out_size == 0) return in.empty();
  if (in.empty()) return false;
  const unsigned int n = ::lzf_decompress(in.data(), static_cast<unsigned int>(in.size()), out,
                                          static_cast<unsigned int>(out_size));
  return n == out_size;
}

}  // namespace rangefit::io::detail
