#!/usr/bin/env bash
# Installs the Debian 12 packages rangefit builds and tests with. Idempotent; needs root.
set -euo pipefail

packages=(
  cmake g++ make pkg-config git ca-certificates
  libeigen3-dev libnanoflann-dev libembree-dev libtomlplusplus-dev libcli11-dev nlohmann-json3-dev
  libspdlog-dev libfmt-dev libsystemd-dev libgtest-dev libgmock-dev libbenchmark-dev
  cyclonedds-dev cyclonedds-tools libmodbus-dev libusb-1.0-0-dev
  python3-pymodbus python3-serial-asyncio mbpoll  # independent Modbus peers for the drivers tests
  openssl  # scripts/make_dds_security.sh: the DDS Security test's CA and signed documents
  dpkg-dev file  # cpack -G DEB: dpkg-shlibdeps (and file) fill the package's Depends
  ccache  # .ci/run: compile results kept outside the clone
  clang libclang-rt-14-dev  # .ci/run: the ASan+UBSan suite and the libFuzzer harnesses of test/fuzz
  libcairo2-dev fonts-dejavu-core  # render/: pictures of scans and detections, legend font
  zlib1g-dev liblzf-dev  # drivers/: CRC-32 (zlib's crc32); io/: PCD binary_compressed (liblzf)
  libcpp-httplib-dev  # api/: the HTTP/JSON interface for robot controllers
  chromium chromium-driver python3  # test/web/browser_test.py: the page in headless Chromium
)
# web/: npm ci fetches three.js (pinned in web/package-lock.json) for rangefitd's page at
# configure time. A Node.js that brings its own npm (nodesource's) is used as it is.
command -v npm > /dev/null || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  if [ "$(id -u)" -ne 0 ]; then
    echo "deps.sh: missing packages (${missing[*]}); run as root to install them" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
