#include "daemon/service/ip_allow.hpp"

#include <arpa/inet.h>

#include <charconv>
#include <sstream>
#include <stdexcept>

#ifndef RANGEFITD_IP_ADDRESS_ALLOW
#error "RANGEFITD_IP_ADDRESS_ALLOW: set from CMake (cmake/packaging.cmake), as the unit's"
#endif

namespace rangefit::daemon {
namespace {

struct Address {
  bool v6 = false;
  std::array<std::uint8_t, 16> bytes{};
};

std::optional<Address> numeric_address(const std::string& text) {
  Address a;
  if (inet_pton(AF_INET, text.c_str(), a.bytes.data()) == 1) return a;
  a.v6 = true;
  if (inet_pton(AF_INET6, text.c_str(), a.bytes.data()) == 1) return a;
  return std::nullopt;
}

IpRange range(const char* address, int bits) {
  const Address a = *numeric_address(address);
  return {a.v6, a.bytes, bits};
}

// The keywords' ranges as systemd.resource-control(5) defines them.
std::optional<std::vector<IpRange>> keyword(std::string_view word) {
  if (word == "any") return std::vector{range("0.0.0.0", 0), range("::", 0)};
  if (word == "localhost") return std::vector{range("127.0.0.0", 8), range("::1", 128)};
  if (word == "link-local") return std::vector{range("169.254.0.0", 16), range("fe80::", 64)};
  if (word == "multicast") return std::vector{range("224.0.0.0", 4), range("ff00::", 8)};
  return std::nullopt;
}

bool in_range(const IpRange& r, const Address& a) {
  if (r.v6 != a.v6) return false;
  const int full = r.bits / 8, rest = r.bits % 8;
  for (int i = 0; i < full; ++i) {
    if (r.prefix[i] != a.bytes[i]) return false;
  }
  if (rest == 0) return true;
  const auto mask = static_cast<std::uint8_t>(0xff << (8 - rest));
  return (r.prefix[full] & mask) == (a.bytes[full] & mask);
}

bool wildcard(const Address& a) {
  for (const std::uint8_t b : a.bytes) {
    if (b != 0) return false;
  }
  return true;
}

}  // namespace

std::optional<IpAllowList> parse_ip_allow(std::string_view text, std::string* error) {
  IpAllowList list;
  list.text = std::string(text);
  std::istringstream words(list.text);
  for (std::string word; words >> word;) {
    if (auto k = keyword(word)) {
      list.ranges.insert(list.ranges.end(), k->begin(), k->end());
      continue;
    }
    const auto slash = word.find('/');
    const auto address = numeric_address(word.substr(0, slash));
    const int max_bits = address && address->v6 ? 128 : 32;
    int bits = max_bits;
    bool ok = address.has_value();
    if (ok && slash != std::string::npos) {
      const char* first = word.data() + slash + 1;
      const char* last = word.data() + word.size();
      const auto [end, ec] = std::from_chars(first, last, bits);
      ok = first != last && ec == std::errc() && end == last && bits >= 0 && bits <= max_bits;
    }
    if (!ok) {
      *error = "IPAddressAllow list \"" + list.text + "\": \"" + word +
               "\" is neither any, localhost, link-local, multicast nor ADDRESS[/PREFIX]";
      return std::nullopt;
    }
    list.ranges.push_back({address->v6, address->bytes, bits});
  }
  return list;
}

bool ip_allowed(const IpAllowList& list, std::string_view text) {
  const auto address = numeric_address(std::string(text));
  if (!address) return false;
  // Listening on every address of a family takes clients from anywhere: only "any" admits them.
  const bool all = wildcard(*address);
  for (const IpRange& r : list.ranges) {
    if (all ? r.v6 == address->v6 && r.bits == 0 : in_range(r, *address)) return true;
  }
  return false;
}

const IpAllowList& built_ip_allow() {
  static const IpAllowList list = [] {
    std::string why;
    auto parsed = parse_ip_allow(RANGEFITD_IP_ADDRESS_ALLOW, &why);
    if (!parsed) throw std::runtime_error("this build's " + why);
    return *parsed;
  }();
  return list;
}

}  // namespace rangefit::daemon
