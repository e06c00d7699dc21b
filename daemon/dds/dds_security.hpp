#pragma once
// [dds.security] → Cyclone DDS: the Domain/Security element that loads Cyclone's builtin
// authentication, access-control and cryptography plugins with the configured documents. It is
// handed to Cyclone as one more XML fragment of the daemon participant's configuration list
// (Cyclone merges the list in order), so it adds to whatever dds.config_uri or the environment
// names.
// With security on, only participants that authenticate with an identity of the same CA and hold
// permissions signed by the permissions CA see rangefitd's topics; what the governance protects
// is encrypted on the wire.

#include <string>

#include "daemon/service/config.hpp"

namespace rangefit::daemon {

// <CycloneDDS><Domain Id="any"><Security>...</Security></Domain></CycloneDDS> for the
// configuration (paths made absolute as file: URIs, XML-escaped); empty when !s.enabled().
std::string dds_security_xml(const DdsSecurityConfig& s);

// The Cyclone configuration list `uri` (CYCLONEDDS_URI syntax, may be empty) with the security
// fragment appended; `uri` unchanged when security is off. Throws std::runtime_error naming the
// dds.security field whose file cannot be read, so a typo fails at start-up instead of as a
// participant Cyclone refuses to create.
std::string with_dds_security(const std::string& uri, const DdsSecurityConfig& s);

}  // namespace rangefit::daemon
