#pragma once
// Reads fixed-size values off the front of a fuzzer input; past the end every value is 0, so a
// harness can draw as many values as it likes from any input.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

namespace rangefit::fuzz {

class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : bytes_(data, size) {}

  template <typename T>
  T take() {
    T value{};
    const std::size_t n = std::min(sizeof(T), bytes_.size() - pos_);
    std::memcpy(&value, bytes_.data() + pos_, n);
    pos_ += n;
    return value;
  }
  // Up to n bytes (fewer at the end of the input).
  std::span<const std::uint8_t> take_span(std::size_t n) {
    n = std::min(n, bytes_.size() - pos_);
    const auto out = bytes_.subspan(pos_, n);
    pos_ += n;
    return out;
  }
  std::span<const std::uint8_t> rest() const { return bytes_.subspan(pos_); }
  bool empty() const { return pos_ >= bytes_.size(); }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
};

}  // namespace rangefit::fuzz
