#pragma once
// rangefitd's unit denies every IP peer outside its IPAddressAllow= list (ip_allow.hpp), so an
// interface configured on an address outside it would bind fine and then never see a packet.
// These checks run on the configuration at start-up and on reload and refuse it instead:
//   [http] listen, [tcp] listen, and the DDS side's Cyclone configuration (dds.config_uri, else
//   CYCLONEDDS_URI): its <NetworkInterface address|name>, <NetworkInterfaceAddress> and
//   <Peer address>. Interface names are looked up among the host's interfaces; an interface that
//   is not there, a host name, or Cyclone's autodetermine is left to Cyclone (nothing to compare).

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "daemon/service/config.hpp"
#include "daemon/service/ip_allow.hpp"

namespace rangefit::daemon {

// What a Cyclone DDS XML configuration names as its addresses.
struct DdsAddresses {
  std::vector<std::string> interface_addresses;  // <NetworkInterface address=...>, numeric
  std::vector<std::string> interface_names;      // <NetworkInterface name=...> (or a non-numeric
                                                 // address), e.g. "lo", "eth0"
  std::vector<std::string> peers;                // <Peer address=...>, the host part, numeric
};
DdsAddresses dds_addresses(std::string_view xml);

// The numeric addresses of the host's network interface of that name (none when it is absent).
using InterfaceLookup = std::function<std::vector<std::string>(const std::string& name)>;
std::vector<std::string> host_interface_addresses(const std::string& name);

// "" when every address above lies inside `allow`; else an error naming the field, the address
// and the list, e.g. `http.listen "0.0.0.0:8080": ... outside the unit's IPAddressAllow=...`.
std::string check_allowed_addresses(const DaemonConfig& config, const IpAllowList& allow,
                                    const InterfaceLookup& lookup = host_interface_addresses);

}  // namespace rangefit::daemon
