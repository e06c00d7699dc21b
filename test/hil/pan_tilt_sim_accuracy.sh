#!/usr/bin/env bash
# How accurately the simulated cell finds the fig. 5.18 cone with the pan-tilt head on the request
# the HIL VM sends the real-driver head (pan_tilt_checks.sh): rangefitd on this host with the head
# as driver = "sim" (same scene, [fusion.pan_tilt] and request; DDS on loopback), three requests
# (noise seeds sim.seed + 0..2, detection seeds 1..3), each result's error printed by
# part_error.py. The VM's bound (head_accurate) is derived from these figures.
#   pan_tilt_sim_accuracy.sh BUILD_DIR SOURCE_DIR
set -uo pipefail
build=$(realpath "${1:?usage: pan_tilt_sim_accuracy.sh BUILD_DIR SOURCE_DIR}")
src=$(realpath "${2:?usage: pan_tilt_sim_accuracy.sh BUILD_DIR SOURCE_DIR}")
work=$(mktemp -d /tmp/rangefit-pan-tilt-sim.XXXXXX)
rangefit=$build/daemon/cli/rangefit
source "$src/test/hil/pan_tilt_checks.sh"
cp "$src/data/models/cone.toml" "$work/cone.toml"
export CYCLONEDDS_URI="file://$src/systemd/cyclonedds-loopback.xml"
cat > "$work/sim.toml" <<TOML
[service]
scan_timeout_s = 60.0
object_sensor = "head"
[dds]
config_uri = "$CYCLONEDDS_URI"
[spool]
directory = "$work/spool"
[sim]
seed = 1
noise = true
$(head_fusion)
[[devices]]
name = "head"
kind = "pan_tilt"
driver = "sim"
scene = "$src/data/scenes/table_top_fig5_18.toml"
[[objects]]
model = "cone.toml"
TOML
"$build/daemon/rangefitd/rangefitd" --config "$work/sim.toml" > "$work/rangefitd.log" 2>&1 &
daemon=$!
trap 'kill $daemon 2>/dev/null; wait $daemon 2>/dev/null; rm -rf "$work"' EXIT
sleep 2
for seed in 1 2 3; do
  "$rangefit" request object --id "sim-$seed" --model cone --sensor head \
    --sweep -0.174533 0.174533 0.0872665 --seed "$seed" --timeout 120 > "$work/r$seed.json"
  echo "seed $seed: $(python3 "$src/test/hil/part_error.py" "$work/r$seed.json" \
    --at 213.074 110.438 40.0 --max-mm 1e9 --max-deg 1e9)"
done
