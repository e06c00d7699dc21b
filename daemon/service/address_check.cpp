#include "daemon/service/address_check.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netinet/in.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>

#include "api/listen_address.hpp"

namespace rangefit::daemon {
namespace {

bool numeric(const std::string& text) {
  unsigned char buf[16];
  return inet_pton(AF_INET, text.c_str(), buf) == 1 || inet_pton(AF_INET6, text.c_str(), buf) == 1;
}

std::string strip_comments(std::string_view xml) {
  std::string out;
  for (std::size_t i = 0; i < xml.size();) {
    const std::size_t open = xml.find("<!--", i);
    out.append(xml.substr(i, open == std::string_view::npos ? open : open - i));
    if (open == std::string_view::npos) break;
    const std::size_t close = xml.find("-->", open + 4);
    i = close == std::string_view::npos ? xml.size() : close + 3;
  }
  return out;
}

// The value of attribute `name` inside one start tag's text ("" when absent).
std::string attribute(std::string_view tag, std::string_view name) {
  for (std::size_t at = tag.find(name); at != std::string_view::npos; at = tag.find(name, at + 1)) {
    const bool starts = at > 0 && (tag[at - 1] == ' ' || tag[at - 1] == '\t' ||
                                   tag[at - 1] == '\n' || tag[at - 1] == '\r');
    std::size_t i = at + name.size();
    while (i < tag.size() && (tag[i] == ' ' || tag[i] == '\t')) ++i;
    if (!starts || i + 1 >= tag.size() || tag[i] != '=') continue;
    ++i;
    while (i < tag.size() && (tag[i] == ' ' || tag[i] == '\t')) ++i;
    if (i >= tag.size() || (tag[i] != '"' && tag[i] != '\'')) continue;
    const std::size_t end = tag.find(tag[i], i + 1);
    if (end == std::string_view::npos) return "";
    return std::string(tag.substr(i + 1, end - i - 1));
  }
  return "";
}

// Cyclone's peer: "HOST", "HOST:PORT", "[V6]" or "[V6]:PORT", or a bare IPv6 address.
std::string peer_host(const std::string& peer) {
  if (numeric(peer)) return peer;
  if (peer.starts_with('[')) {
    const auto close = peer.find(']');
    return close == std::string::npos ? "" : peer.substr(1, close - 1);
  }
  const auto colon = peer.find(':');
  if (colon != std::string::npos && peer.find(':', colon + 1) == std::string::npos) {
    return peer.substr(0, colon);
  }
  return peer;
}

// The XML texts a Cyclone configuration URI names: inline XML, or a comma-separated list of
// file:// URIs and XML fragments (as CYCLONEDDS_URI); files that cannot be read are skipped
// (Cyclone itself reports them).
std::vector<std::string> cyclone_texts(const std::string& uri) {
  std::vector<std::string> texts;
  const auto first = uri.find_first_not_of(" \t\n");
  if (first == std::string::npos) return texts;
  if (uri[first] == '<') return {uri};
  for (std::size_t i = 0; i <= uri.size();) {
    std::size_t comma = uri.find(',', i);
    if (comma == std::string::npos) comma = uri.size();
    std::string part = uri.substr(i, comma - i);
    const auto b = part.find_first_not_of(" \t\n"), e = part.find_last_not_of(" \t\n");
    part = b == std::string::npos ? "" : part.substr(b, e - b + 1);
    if (part.starts_with("file://")) {
      std::ifstream in(part.substr(7));
      if (in)
        texts.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    } else if (part.starts_with('<')) {
      texts.push_back(part);
    }
    i = comma + 1;
  }
  return texts;
}

std::string outside(const std::string& field, const std::string& value, const std::string& address,
                    const IpAllowList& allow) {
  const bool all = address == "0.0.0.0" || address == "::";
  return field + " \"" + value + "\": " +
         (all ? address +
                    " means every address, and only IPAddressAllow=any admits clients "
                    "from everywhere"
              : address + " is outside the unit's IPAddressAllow=") +
         (all ? "; the unit allows \"" : " \"") + allow.text +
         "\", which drops every other peer (IPAddressDeny=any): use an address inside it, or "
         "build rangefitd and its unit with -DRANGEFITD_IP_ADDRESS_ALLOW=\"...\"";
}

}  // namespace

DdsAddresses dds_addresses(std::string_view xml_text) {
  DdsAddresses out;
  const std::string xml = strip_comments(xml_text);
  for (std::size_t lt = xml.find('<'); lt != std::string::npos; lt = xml.find('<', lt + 1)) {
    const std::size_t gt = xml.find('>', lt);
    if (gt == std::string::npos) break;
    const std::string_view tag = std::string_view(xml).substr(lt + 1, gt - lt - 1);
    const std::size_t name_end = tag.find_first_of(" \t\r\n/");
    const std::string_view name = tag.substr(0, name_end);
    if (name == "NetworkInterface") {
      const std::string address = attribute(tag, "address"), iface = attribute(tag, "name");
      if (!address.empty()) {
        (numeric(address) ? out.interface_addresses : out.interface_names).push_back(address);
      }
      if (!iface.empty()) out.interface_names.push_back(iface);
    } else if (name == "NetworkInterfaceAddress") {  // Cyclone's older spelling, text content
      const std::size_t end = xml.find('<', gt);
      std::string value = xml.substr(gt + 1, end == std::string::npos ? 0 : end - gt - 1);
      const auto b = value.find_first_not_of(" \t\r\n"), e = value.find_last_not_of(" \t\r\n");
      value = b == std::string::npos ? "" : value.substr(b, e - b + 1);
      if (!value.empty() && value != "auto") {
        (numeric(value) ? out.interface_addresses : out.interface_names).push_back(value);
      }
    } else if (name == "Peer") {
      const std::string host = peer_host(attribute(tag, "address"));
      if (numeric(host)) out.peers.push_back(host);
    }
  }
  return out;
}

std::vector<std::string> host_interface_addresses(const std::string& name) {
  std::vector<std::string> out;
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) return out;
  const std::unique_ptr<ifaddrs, void (*)(ifaddrs*)> guard(list, freeifaddrs);
  for (const ifaddrs* a = list; a != nullptr; a = a->ifa_next) {
    if (a->ifa_addr == nullptr || a->ifa_name == nullptr || name != a->ifa_name) continue;
    char text[INET6_ADDRSTRLEN] = {};
    if (a->ifa_addr->sa_family == AF_INET) {
      inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in*>(a->ifa_addr)->sin_addr, text,
                sizeof text);
    } else if (a->ifa_addr->sa_family == AF_INET6) {
      inet_ntop(AF_INET6, &reinterpret_cast<const sockaddr_in6*>(a->ifa_addr)->sin6_addr, text,
                sizeof text);
    } else {
      continue;
    }
    out.emplace_back(text);
  }
  return out;
}

std::string check_allowed_addresses(const DaemonConfig& config, const IpAllowList& allow,
                                    const InterfaceLookup& lookup) {
  for (const auto& [field, c] :
       {std::pair{"http.listen", &config.http}, std::pair{"tcp.listen", &config.tcp}}) {
    if (c->listen.empty()) continue;
    std::string why;
    const auto address = api::parse_listen_address(c->listen, &why);
    if (!address) return std::string(field) + ": " + why;
    if (!ip_allowed(allow, address->host)) return outside(field, c->listen, address->host, allow);
  }
  std::string uri = config.dds.config_uri;
  const std::string field =
      uri.empty() ? "CYCLONEDDS_URI (dds.config_uri is empty)" : "dds.config_uri";
  if (uri.empty()) {
    const char* env = std::getenv("CYCLONEDDS_URI");
    uri = env != nullptr ? env : "";
  }
  for (const std::string& xml : cyclone_texts(uri)) {
    const DdsAddresses dds = dds_addresses(xml);
    for (const std::string& a : dds.interface_addresses) {
      if (!ip_allowed(allow, a)) return outside(field + ": NetworkInterface", a, a, allow);
    }
    for (const std::string& name : dds.interface_names) {
      const std::vector<std::string> addresses = lookup(name);
      bool any_allowed = addresses.empty();  // not on this host: Cyclone reports it
      for (const std::string& a : addresses) any_allowed = any_allowed || ip_allowed(allow, a);
      if (!any_allowed) {
        return outside(field + ": NetworkInterface", name, addresses.front(), allow);
      }
    }
    for (const std::string& a : dds.peers) {
      if (!ip_allowed(allow, a)) return outside(field + ": Peer", a, a, allow);
    }
  }
  return "";
}

}  // namespace rangefit::daemon
