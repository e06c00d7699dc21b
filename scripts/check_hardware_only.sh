#!/usr/bin/env bash
# The hardware-only build (RANGEFIT_WITH_SIM=OFF): rangefitd and rangefit without the simulator.
# Checks that neither links Embree, that `rangefit simulate` is gone, and that a config asking
# for a simulated device is refused at start-up with the reason. Usage: check_hardware_only.sh DIR
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-nosim}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DRANGEFIT_WITH_SIM=OFF \
  -DRANGEFIT_BUILD_TESTS=OFF -DRANGEFIT_BUILD_BENCHMARKS=OFF > /dev/null
cmake --build "$build" -j"$(nproc)" --target rangefitd rangefit
fail() { echo "hardware-only build: $*" >&2; exit 1; }
for exe in "$build/daemon/rangefitd/rangefitd" "$build/daemon/cli/rangefit"; do
  if readelf -d "$exe" | grep -qi embree; then fail "$exe links Embree"; fi
done
if "$build/daemon/cli/rangefit" simulate --scene x --out /dev/null 2> /dev/null; then
  fail "rangefit simulate exists"
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/sim.toml" << TOML
[dds]
domain_id = 231
[spool]
directory = "$work/spool"
[[devices]]
name = "css"
kind = "css"
driver = "sim"
motion = "robot"
scene = "scene.toml"
[[devices]]
name = "robot"
kind = "robot"
driver = "sim"
TOML
if CYCLONEDDS_URI='<CycloneDDS><Domain><General><Interfaces><NetworkInterface address="127.0.0.1"/></Interfaces></General></Domain></CycloneDDS>' \
  timeout 30 "$build/daemon/rangefitd/rangefitd" --config "$work/sim.toml" 2> "$work/err"; then
  fail "rangefitd started with a simulated device"
fi
grep -q 'RANGEFIT_WITH_SIM=OFF' "$work/err" || { cat "$work/err"; fail "no reason given"; }
echo "hardware-only build: no Embree, no simulate, driver = \"sim\" refused"
