#pragma once
// The address list of the systemd unit's IPAddressAllow= (systemd.resource-control(5)): "any",
// "localhost", "link-local", "multicast", and IPv4/IPv6 addresses with an optional /prefix. The
// unit denies every other peer (IPAddressDeny=any), so rangefitd checks that what it listens on
// lies inside the list it was built with (address_check.hpp) instead of serving a socket nobody
// outside the list can reach.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rangefit::daemon {

struct IpRange {
  bool v6 = false;
  std::array<std::uint8_t, 16> prefix{};  // network byte order; IPv4 in the first 4 bytes
  int bits = 0;                           // prefix length: 0..32 (IPv4) or 0..128 (IPv6)
};

struct IpAllowList {
  std::string text;  // as written, for error messages
  std::vector<IpRange> ranges;
};

// nullopt and *error on a word that is neither a keyword nor an address[/prefix].
std::optional<IpAllowList> parse_ip_allow(std::string_view text, std::string* error);

// The numeric IPv4 or IPv6 address lies in one of the ranges. A wildcard address (0.0.0.0, ::)
// stands for every address of its family, so only a /0 range of that family ("any") holds it.
// False for anything that is not a numeric address.
bool ip_allowed(const IpAllowList& list, std::string_view address);

// The list this rangefitd was built with: the unit's IPAddressAllow= (CMake
// RANGEFITD_IP_ADDRESS_ALLOW).
const IpAllowList& built_ip_allow();

}  // namespace rangefit::daemon
