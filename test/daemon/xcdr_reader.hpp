#pragma once
// What a ROS 2 node gets off the wire: the serialized sample of a reader (encapsulation header and
// CDR body), and a little-endian XCDR1 reader written from the CDR rules, independent of the
// idlc-generated code, for the tests that check rangefitd's ROS 2 messages byte by byte.
#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace rangefit::test {

inline std::string type_name(dds_entity_t reader) {
  char name[256] = {};
  dds_get_type_name(dds_get_topic(reader), name, sizeof name);
  return name;
}

// The serialized sample as it travels: 4 bytes of encapsulation, then the CDR body.
inline std::optional<std::vector<unsigned char>> take_bytes(dds_entity_t reader,
                                                            std::chrono::seconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < deadline) {
    ddsi_serdata* sd = nullptr;
    dds_sample_info_t info;
    if (dds_takecdr(reader, &sd, 1, &info, DDS_ANY_STATE) == 1) {
      std::vector<unsigned char> bytes(ddsi_serdata_size(sd));
      ddsi_serdata_to_ser(sd, 0, bytes.size(), bytes.data());
      ddsi_serdata_unref(sd);
      if (info.valid_data) return bytes;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return std::nullopt;
}

// Reads past the end throw, so a message shorter than its definition fails the test.
struct Cdr {
  const std::vector<unsigned char>& b;
  std::size_t at = 4;  // after the encapsulation header
  void align(std::size_t n) { at = 4 + ((at - 4 + n - 1) / n) * n; }
  void need(std::size_t n) const {
    if (at + n > b.size()) throw std::out_of_range("CDR read past the end of the sample");
  }
  template <class T>
  T get() {
    align(sizeof(T));
    need(sizeof(T));
    T v;
    std::memcpy(&v, b.data() + at, sizeof(T));
    at += sizeof(T);
    return v;
  }
  std::string str() {
    const auto n = get<std::uint32_t>();
    need(n);
    std::string s(reinterpret_cast<const char*>(b.data() + at), n > 0 ? n - 1 : 0);
    at += n;
    return s;
  }
  std::vector<unsigned char> octets() {  // sequence<uint8>
    const auto n = get<std::uint32_t>();
    need(n);
    std::vector<unsigned char> v(b.begin() + static_cast<std::ptrdiff_t>(at),
                                 b.begin() + static_cast<std::ptrdiff_t>(at + n));
    at += n;
    return v;
  }
  // Everything read: only the padding to a multiple of 4 is left, whose length the low two bits
  // of the encapsulation options give (XTypes 1.3, 7.6.3.1.2).
  bool done() const { return b.size() >= 4 && at + (b[3] & 3u) == b.size(); }
};

}  // namespace rangefit::test
