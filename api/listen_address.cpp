#include "api/listen_address.hpp"

#include <arpa/inet.h>

#include <charconv>

namespace rangefit::api {

std::optional<ListenAddress> parse_listen_address(const std::string& text, std::string* error) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos) {
    *error = "listen address \"" + text + "\" needs HOST:PORT";
    return std::nullopt;
  }
  ListenAddress a;
  a.host = text.substr(0, colon);
  if (a.host == "localhost") a.host = "127.0.0.1";
  in_addr ignored{};
  if (inet_pton(AF_INET, a.host.c_str(), &ignored) != 1) {
    *error = "listen address \"" + text + "\": host must be an IPv4 address such as 127.0.0.1";
    return std::nullopt;
  }
  const std::string port = text.substr(colon + 1);
  const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), a.port);
  if (port.empty() || ec != std::errc() || end != port.data() + port.size() || a.port < 0 ||
      a.port > 65535) {
    *error = "listen address \"" + text + "\": port must be a number 0..65535";
    return std::nullopt;
  }
  return a;
}

}  // namespace rangefit::api
