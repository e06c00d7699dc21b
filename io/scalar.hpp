#pragma once
// Binary scalar values shared by the PLY, PCD and STL codecs: the types these formats declare,
// decoding from raw bytes in either byte order, and appending encoded values to a buffer.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>

namespace rangefit::io::detail {

enum class Scalar {
  kInt8,
  kUint8,
  kInt16,
  kUint16,
  kInt32,
  kUint32,
  kInt64,
  kUint64,
  kFloat32,
  kFloat64
};

constexpr std::size_t scalar_size(Scalar type) {
  switch (type) {
    case Scalar::kInt8:
    case Scalar::kUint8:
      return 1;
    case Scalar::kInt16:
    case Scalar::kUint16:
      return 2;
    case Scalar::kInt32:
    case Scalar::kUint32:
    case Scalar::kFloat32:
      return 4;
    case Scalar::kInt64:
    case Scalar::kUint64:
    case Scalar::kFloat64:
      return 8;
  }
  return 1;
}

constexpr bool scalar_is_integer(Scalar type) {
  return type != Scalar::kFloat32 && type != Scalar::kFloat64;
}

template <typename T>
T load_raw(const char* bytes, bool big_endian) {
  unsigned char buffer[sizeof(T)];
  std::memcpy(buffer, bytes, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(buffer[i], buffer[sizeof(T) - 1 - i]);
  }
  T value;
  std::memcpy(&value, buffer, sizeof(T));
  return value;
}

// Value of one scalar as a double (exact for every type except 64-bit integers beyond 2^53).
inline double decode_scalar(const char* bytes, Scalar type, bool big_endian) {
  switch (type) {
    case Scalar::kInt8:
      return load_raw<std::int8_t>(bytes, big_endian);
    case Scalar::kUint8:
      return load_raw<std::uint8_t>(bytes, big_endian);
    case Scalar::kInt16:
      return load_raw<std::int16_t>(bytes, big_endian);
    case Scalar::kUint16:
      return load_raw<std::uint16_t>(bytes, big_endian);
    case Scalar::kInt32:
      return load_raw<std::int32_t>(bytes, big_endian);
    case Scalar::kUint32:
      return load_raw<std::uint32_t>(bytes, big_endian);
    case Scalar::kInt64:
      return static_cast<double>(load_raw<std::int64_t>(bytes, big_endian));
    case Scalar::kUint64:
      return static_cast<double>(load_raw<std::uint64_t>(bytes, big_endian));
    case Scalar::kFloat32:
      return load_raw<float>(bytes, big_endian);
    case Scalar::kFloat64:
      return load_raw<double>(bytes, big_endian);
  }
  return 0.0;
}

template <typename T>
void append_raw(std::string& out, T value, bool big_endian) {
  char buffer[sizeof(T)];
  std::memcpy(buffer, &value, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(buffer[i], buffer[sizeof(T) - 1 - i]);
  }
  out.append(buffer, sizeof(T));
}

}  // namespace rangefit::io::detail
