#pragma once
// A DDS sample as it arrives off the wire: the 4-byte encapsulation header and its XCDR body,
// either byte order, through Cyclone's own receive path for its type, as ddsi_serdata_default.c
// does it (the body is checked and byte-swapped by dds_stream_normalize_data, dropped when that
// fails, then read into the sample by dds_stream_read). Shared by the DDS messages fuzzer and the
// test that its seeds still decode with the current types.
#include <dds/dds.h>
#include <dds/ddsi/ddsi_cdrstream.h>

#include <bit>
#include <cstdint>
#include <span>
#include <vector>

namespace rangefit::test {

// One received sample of type T (the idlc struct of desc), or none when Cyclone would drop the
// bytes. Owns what dds_stream_read allocated (strings, sequences).
template <class T>
class WireSample {
 public:
  WireSample(const dds_topic_descriptor_t& desc, std::span<const std::uint8_t> bytes)
      : desc_(desc) {
    // The encapsulation (XTypes 7.6.3.1.2): 0x00 0x00/0x01 plain CDR (XCDR1) big/little endian,
    // 0x00 0x10/0x11 plain CDR2; the low two bits of the options count the padding at the end.
    if (bytes.size() < 4 || bytes.size() > (1u << 24) || bytes[0] != 0) return;
    const std::uint8_t id = bytes[1];
    if (id != 0x00 && id != 0x01 && id != 0x10 && id != 0x11) return;
    const std::uint32_t xcdr = (id & 0x10) != 0 ? 2 : 1;
    const bool little = (id & 1) != 0;
    const bool swap = little != (std::endian::native == std::endian::little);
    const std::uint32_t pad = bytes[3] & 3u;
    if (bytes.size() - 4 < pad) return;
    body_.assign(bytes.begin() + 4, bytes.end() - pad);
    body_.resize(body_.size() + 8);  // never a null buffer, even for an empty body
    const auto size = static_cast<std::uint32_t>(body_.size() - 8);
    std::uint32_t off = 0;
    if (dds_stream_normalize_data(reinterpret_cast<char*>(body_.data()), &off, size, swap, xcdr,
                                  desc_.m_ops) == nullptr) {
      return;
    }
    dds_istream_t in;
    dds_istream_init(&in, size, body_.data(), xcdr);
    dds_stream_read(&in, reinterpret_cast<char*>(&sample_), desc_.m_ops);
    dds_istream_fini(&in);
    read_ = true;
  }
  ~WireSample() {
    if (read_) dds_sample_free(&sample_, &desc_, DDS_FREE_CONTENTS);
  }
  WireSample(const WireSample&) = delete;
  WireSample& operator=(const WireSample&) = delete;
  const T* get() const { return read_ ? &sample_ : nullptr; }

 private:
  const dds_topic_descriptor_t& desc_;
  std::vector<std::uint8_t> body_;
  T sample_{};
  bool read_ = false;
};

}  // namespace rangefit::test
