#!/usr/bin/env bash
# Test artefacts for DDS Security (authentication + access control, [dds.security] in
# rangefitd.toml): one CA that signs the identities and the permissions, an identity certificate
# and key per name, and S/MIME-signed governance and permissions documents. The governance
# admits authenticated participants only and encrypts discovery, liveliness and every topic's
# data; the permissions let every listed identity publish and subscribe to every topic in
# domains 0..230 (the most Cyclone's access control parser accepts), in any partition. For tests
# and for trying the feature; a cell's real PKI issues its own.
#   bash scripts/make_dds_security.sh OUT_DIR [NAME...]   (names default to: rangefitd client)
# Writes OUT_DIR/ca_cert.pem, ca_key.pem, <name>_cert.pem, <name>_key.pem, governance.xml,
# governance.p7s, permissions.xml, permissions.p7s. Needs the openssl command line tool.
set -euo pipefail
out="${1:?usage: make_dds_security.sh OUT_DIR [NAME...]}"
shift
names=("$@")
((${#names[@]})) || names=(rangefitd client)
command -v openssl >/dev/null || { echo "make_dds_security.sh: openssl is missing" >&2; exit 1; }
mkdir -p "$out"
cd "$out"

# EC P-256 keys: supported by Cyclone's authentication plugin and quick to make.
ecparams=(-newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes)
openssl req -x509 "${ecparams[@]}" -keyout ca_key.pem -out ca_cert.pem -days 3650 \
  -subj "/CN=rangefit test CA" 2>/dev/null
for name in "${names[@]}"; do
  openssl req "${ecparams[@]}" -keyout "${name}_key.pem" -out "${name}.csr" \
    -subj "/CN=${name}" 2>/dev/null
  openssl x509 -req -in "${name}.csr" -CA ca_cert.pem -CAkey ca_key.pem -CAcreateserial \
    -days 3650 -out "${name}_cert.pem" 2>/dev/null
  rm -f "${name}.csr"
done
rm -f ca_cert.srl

cat >governance.xml <<'EOF'
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      <domains><id_range><min>0</min><max>230</max></id_range></domains>
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
EOF

{
  cat <<'EOF'
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
EOF
  for name in "${names[@]}"; do
    cat <<EOF
    <grant name="${name}">
      <subject_name>CN=${name}</subject_name>
      <validity><not_before>2020-01-01T00:00:00</not_before><not_after>2120-01-01T00:00:00</not_after></validity>
      <allow_rule>
        <domains><id_range><min>0</min><max>230</max></id_range></domains>
        <publish><topics><topic>*</topic></topics><partitions><partition>*</partition></partitions></publish>
        <subscribe><topics><topic>*</topic></topics><partitions><partition>*</partition></partitions></subscribe>
      </allow_rule>
      <default>DENY</default>
    </grant>
EOF
  done
  cat <<'EOF'
  </permissions>
</dds>
EOF
} >permissions.xml

for doc in governance permissions; do
  openssl smime -sign -in "$doc.xml" -text -out "$doc.p7s" -signer ca_cert.pem -inkey ca_key.pem
done
echo "make_dds_security.sh: CA, identities (${names[*]}), governance and permissions in $out"
