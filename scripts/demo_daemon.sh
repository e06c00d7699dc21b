#!/usr/bin/env bash
# Starts rangefitd on a replayed synthetic bore plate (loopback-only DDS, random domain), sends a
# bore request and an object request with the `rangefit request` client, prints both results,
# and stops the daemon. Usage: bash scripts/demo_daemon.sh [BUILD_DIR]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
if [[ ! -x "$build/daemon/rangefitd/rangefitd" ]]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$build" -j2 --target rangefitd rangefit
fi
work="$(mktemp -d)"
trap 'kill "$pid" 2>/dev/null || true; wait "$pid" 2>/dev/null || true; rm -rf "$work"' EXIT
domain=$((RANDOM % 200 + 1))
export CYCLONEDDS_URI="file://$root/systemd/cyclonedds-loopback.xml"

# The scan the CSS "device" returns: a plate (z = 0) with a 5 mm bore along z at the origin,
# 0.2 mm spacing, seen from above at a slant so part of the wall is visible (ASCII PLY, mm).
python3 - "$work/plate.ply" <<'PY'
import math, random, sys
random.seed(1)
pts = []
s = 0.2
n = int(13 / s)
for i in range(-n, n + 1):
    for j in range(-n, n + 1):
        x, y = i * s, j * s
        if x * x + y * y > 25.0:
            pts.append((x, y, random.gauss(0, 0.02)))
for k in range(1, 100):
    z = -k * s
    for a in range(180):
        t = 2 * math.pi * a / 180
        if math.cos(t) < 0.2:  # the wall side the slanted sensor sees
            r = 5.0 + random.gauss(0, 0.02)
            pts.append((r * math.cos(t), r * math.sin(t), z))
with open(sys.argv[1], "w") as f:
    f.write("ply\nformat ascii 1.0\nelement vertex %d\n" % len(pts))
    f.write("property double x\nproperty double y\nproperty double z\nend_header\n")
    for p in pts:
        f.write("%.4f %.4f %.4f\n" % p)
PY

cat > "$work/rangefitd.toml" <<TOML
[service]
bore_sensor = "css"
object_sensor = "css"
[dds]
domain_id = $domain
[spool]
directory = "$work/spool"
[[devices]]
name = "css"
kind = "css"
driver = "replay"
replay_file = "$work/plate.ply"
[[objects]]
name = "box"
scale_mm = [40.0, 30.0, 20.0]
shape = [0.1, 0.1]
TOML

"$build/daemon/rangefitd/rangefitd" --config "$work/rangefitd.toml" &
pid=$!
echo "== bore request =="
"$build/daemon/rangefit" request bore --domain "$domain" --id demo-bore \
  --position 0 0 0 --axis 0 0 1 --radius 5 --timeout 60 || true
echo "== object request =="
"$build/daemon/rangefit" request object --domain "$domain" --id demo-object --model box \
  --timeout 60 || true
kill -TERM "$pid"
wait "$pid"
