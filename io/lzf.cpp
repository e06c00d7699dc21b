#include "io/lzf.hpp"

#include <cstdint>
#include <cstring>

namespace rangefit::io::detail {

bool lzf_decompress(std::string_view in, char* out, std::size_t out_size) {
  std::size_t ip = 0;
  std::size_t op = 0;
  auto byte = [&](std::size_t i) {
    return static_cast<std::size_t>(static_cast<std::uint8_t>(in[i]));
  };
  while (ip < in.size()) {
    const std::size_t ctrl = byte(ip++);
    if (ctrl < 32) {  // literal run of ctrl + 1 bytes
      const std::size_t length = ctrl + 1;
      if (length > in.size() - ip || length > out_size - op) return false;
      std::memcpy(out + op, in.data() + ip, length);
      ip += length;
      op += length;
      continue;
    }
    std::size_t length = ctrl >> 5;  // back reference: length - 2, 7 means "one more byte"
    if (length == 7) {
      if (ip >= in.size()) return false;
      length += byte(ip++);
    }
    if (ip >= in.size()) return false;
    const std::size_t distance = ((ctrl & 0x1f) << 8) + byte(ip++) + 1;
    length += 2;
    if (distance > op || length > out_size - op) return false;
    for (std::size_t k = 0; k < length; ++k, ++op) out[op] = out[op - distance];  // may overlap
  }
  return op == out_size;
}

}  // namespace rangefit::io::detail
