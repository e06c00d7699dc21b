#pragma once
// `listen = "127.0.0.1:8080"` of the config: a numeric IPv4 address (or "localhost") and a port.

#include <optional>
#include <string>

namespace rangefit::api {

struct ListenAddress {
  std::string host = "127.0.0.1";
  int port = 8080;  // 0: any free port (tests)
};

// nullopt and *error on a missing or non-numeric port, a port over 65535, or a host that is not
// a dotted IPv4 address or "localhost" (which becomes 127.0.0.1).
std::optional<ListenAddress> parse_listen_address(const std::string& text, std::string* error);

}  // namespace rangefit::api
