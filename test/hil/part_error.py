"""How far the first part of a rangefit result (JSON of `rangefit request`) is from where the
scene puts it: the distance of its origin from --at (mm), the angle of its z axis from --axis
(deg, either direction) and, with --radius, the bore radius error (mm). Prints them; exits 0 when
all are within the --max-* bounds, 1 when not (or nothing was found).
Usage: part_error.py RESULT.json --at X Y Z [--axis X Y Z] --max-mm E --max-deg D
                     [--radius R --max-radius-mm DR]"""
import argparse
import json
import math
import sys

a = argparse.ArgumentParser()
a.add_argument("result")
a.add_argument("--at", type=float, nargs=3, required=True)
a.add_argument("--axis", type=float, nargs=3, default=(0.0, 0.0, 1.0))
a.add_argument("--max-mm", type=float, required=True)
a.add_argument("--max-deg", type=float, required=True)
a.add_argument("--radius", type=float)
a.add_argument("--max-radius-mm", type=float, default=0.0)
args = a.parse_args()

r = json.load(open(args.result))
if not r["found"]:
    sys.exit("  not found: " + r["reason"])
p = r["parts"][0]
w, x, y, z = p["quaternion_wxyz"]
axis = (2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y))
truth = [c / math.hypot(*args.axis) for c in args.axis]
cos = abs(sum(u * v for u, v in zip(axis, truth)))
e = math.dist(p["translation_mm"], args.at)
tilt = math.degrees(math.acos(min(1.0, cos)))
name = r.get("model") or r.get("kind", "part")
line = (f"  {name} at {p['translation_mm']}, {r['num_points']} points, scan "
        f"{r['scan_seconds']:.1f} s: position error {e:.3f} mm, axis {tilt:.3f} deg")
ok = e < args.max_mm and tilt < args.max_deg
if args.radius is not None:
    dr = abs(r["bore_radius_mm"] - args.radius)
    line += f", radius error {dr:.3f} mm"
    ok = ok and dr < args.max_radius_mm
print(line)
sys.exit(0 if ok else 1)
