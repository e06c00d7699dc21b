#include "daemon/dds/dds_security.hpp"

#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace rangefit::daemon {
namespace {

std::string xml_escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string file_uri(const std::filesystem::path& p) {
  return xml_escaped("file:" + std::filesystem::absolute(p).lexically_normal().string());
}

// <Library> of a builtin plugin, by absolute path: Debian keeps the plugins outside the
// loader's search path.
std::string library(const std::filesystem::path& dir, const char* name, const char* init,
                    const char* finalize) {
  return "<Library path=\"" + xml_escaped((dir / name).string()) + "\" initFunction=\"" + init +
         "\" finalizeFunction=\"" + finalize + "\"/>";
}

}  // namespace

std::string dds_security_xml(const DdsSecurityConfig& s) {
  if (!s.enabled()) return {};
  return "<CycloneDDS xmlns=\"https://cdds.io/config\"><Domain Id=\"any\"><Security>"
         "<Authentication>" +
         library(s.plugin_dir, "libdds_security_auth.so", "init_authentication",
                 "finalize_authentication") +
         "<IdentityCA>" + file_uri(s.identity_ca) + "</IdentityCA>" + "<IdentityCertificate>" +
         file_uri(s.identity_certificate) + "</IdentityCertificate>" + "<PrivateKey>" +
         file_uri(s.private_key) + "</PrivateKey></Authentication>" + "<AccessControl>" +
         library(s.plugin_dir, "libdds_security_ac.so", "init_access_control",
                 "finalize_access_control") +
         "<PermissionsCA>" + file_uri(s.permissions_ca) + "</PermissionsCA>" + "<Governance>" +
         file_uri(s.governance) + "</Governance>" + "<Permissions>" + file_uri(s.permissions) +
         "</Permissions></AccessControl>" + "<Cryptographic>" +
         library(s.plugin_dir, "libdds_security_crypto.so", "init_crypto", "finalize_crypto") +
         "</Cryptographic></Security></Domain></CycloneDDS>";
}

std::string with_dds_security(const std::string& uri, const DdsSecurityConfig& s) {
  if (!s.enabled()) return uri;
  for (const auto& [field, path] : DdsSecurityConfig::documents(s)) {
    if (!std::ifstream(*path)) {
      throw std::runtime_error(std::string("dds.security.") + field + ": cannot read " +
                               path->string());
    }
  }
  const auto auth = s.plugin_dir / "libdds_security_auth.so";
  if (!std::filesystem::exists(auth)) {
    throw std::runtime_error("dds.security.plugin_dir: no " + auth.string() +
                             " (Debian: install libddsc0debian)");
  }
  const std::string xml = dds_security_xml(s);
  return uri.empty() ? xml : uri + "," + xml;
}

}  // namespace rangefit::daemon
