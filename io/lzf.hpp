#pragma once
// LZF decompression (Marc Lehmann's liblzf format), as PCL uses for DATA binary_compressed.

#include <cstddef>
#include <string_view>

namespace rangefit::io::detail {

// Decompresses `in` into exactly out_size bytes at out. Returns false, without reading or writing
// out of bounds, when the stream is malformed or does not produce exactly out_size bytes.
bool lzf_decompress(std::string_view in, char* out, std::size_t out_size);

// Worst-case expansion of LZF: a 3-byte back reference yields up to 264 bytes.
inline constexpr std::size_t kLzfMaxRatio = 88;

}  // namespace rangefit::io::detail
