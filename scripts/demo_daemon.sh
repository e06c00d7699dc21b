#!/usr/bin/env bash
# rangefitd on the simulated cell: starts the daemon (loopback-only DDS, random domain, temporary
# spool) with the CSS on the robot over the bore plate and the stripe cell under the table-top
# scene of thesis fig. 5.18, sends a bore request and an object request with `rangefit request`,
# prints both results and stops the daemon (SIGTERM, also on error or Ctrl-C). Exits non-zero
# when either request fails. Needs a build: bash scripts/demo_daemon.sh [BUILD_DIR [TIME_SCALE]]
# (scripts/demo.sh installs the packages and builds first). TIME_SCALE 1 = the cell's real pace
# (about 25 s for the CSS scan and 65 s for the stripe scan), 0 = as fast as possible.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
time_scale="${2:-1}"
rangefitd="$build/daemon/rangefitd/rangefitd"
rangefit="$build/daemon/cli/rangefit"
for exe in "$rangefitd" "$rangefit"; do
  [[ -x "$exe" ]] || { echo "demo: $exe is missing; run scripts/demo.sh" >&2; exit 1; }
done
work="$(mktemp -d)"
pid=""
cleanup() {
  if [[ -n "$pid" ]] && kill -0 "$pid" 2>/dev/null; then
    kill -TERM "$pid"
    wait "$pid" || true
  fi
  rm -rf "$work"
}
trap cleanup EXIT
trap 'exit 130' INT TERM
domain=$((RANDOM % 200 + 1))
export CYCLONEDDS_URI="file://$root/systemd/cyclonedds-loopback.xml"

cat > "$work/rangefitd.toml" <<TOML
[service]
bore_sensor = "css"
object_sensor = "stripe"
[dds]
domain_id = $domain
[spool]
directory = "$work/spool"
[sim]
time_scale = $time_scale
[[devices]]
name = "css"
kind = "css"
driver = "sim"
scene = "$root/data/scenes/bore_plate.toml"
[[devices]]
name = "stripe"
kind = "stripe"
driver = "sim"
scene = "$root/data/scenes/table_top_fig5_18.toml"
[[objects]]
name = "sphere"
scale_mm = [50.0, 50.0, 50.0]
shape = [1.0, 1.0]
TOML

"$rangefitd" --config "$work/rangefitd.toml" &
pid=$!
status=0
# CAD prior of the 12 mm straight bore the plate puts under the CSS; the simulated true entrance
# is (0, 0, 285.8) mm with the axis along z (data/scenes/bore_plate.toml).
echo "== bore request (CSS on the robot, bore plate) =="
"$rangefit" request bore --domain "$domain" --id demo-bore \
  --position 0.8 -0.5 285.8 --axis 0 0 1 --radius 6 --timeout 300 || status=1
# The sphere of fig. 5.18; truth: centre (160, 65, 50) mm, radius 50 mm.
echo "== object request (stripe cell, table-top scene) =="
"$rangefit" request object --domain "$domain" --id demo-object --model sphere \
  --timeout 300 || status=1
kill -TERM "$pid"
wait "$pid" || status=1
pid=""
if ((status)); then echo "demo: a request failed" >&2; else echo "demo: both requests answered, both found"; fi
exit "$status"
