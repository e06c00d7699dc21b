# The pan-tilt head's part of service_hil_test.sh (sourced there: uses $rangefit, $src, $work, fd 7
# to the cell peer and its log $work/peer.log): the head's device table, the object requests, what
# a user checks of their answers.

# One pan of the head across the table, -10 .. +10 deg at 5 deg/s (rad, rad/s): the peer's head
# (rangefit_cell_peer --pan-half-deg 10 --head-sweep-s 4).
head_sweep=(-0.174533 0.174533 0.0872665)

# The head as the fig. 5.18 scene mounts it ([sensors.pantilt]: 700 mm above the table centre,
# looking down), so the results are in the scene's frame, as the simulated head gives them; its
# pan and tilt axes and ranger on their own CAN bus (the driver is that bus' SYNC master). The
# [fusion.pan_tilt] lines are the peer's head: 25 profiles/s of 128 points (the thesis' head: <= 100
# of 512), so that its CAN FD stream (6 frames a profile, 150 frames/s, free-running as a real
# ranger's) leaves the emulated VM's two CPUs to the other cells' streams.
head_fusion() {
  cat <<TOML
[fusion.pan_tilt]
profile_rate_hz = 25.0
profile_period_ms = 40.0
[fusion.pan_tilt.ranger]
points_per_profile = 128
TOML
}

# A device of the head, name $1 with its ranger on CAN node $2 of vcan1: the head itself (its pan
# and tilt axes on nodes 1 and 2) or, with $3, a further camera of its laser plane on the head $3
# (motion), mounted with it. Its configured sweep is the head_request's, which a request naming
# several sensors cannot give.
head_device() {
  printf '[[devices]]\nname = "%s"\nkind = "pan_tilt"\ndriver = "real"\ntransport = "vcan1"\n' "$1"
  if [[ -n ${3:-} ]]; then
    printf 'can_node = %s\nmotion = "%s"\n' "$2" "$3"
  else
    printf 'can_node = %s\npan_node = 1\ntilt_node = 2\n' "$2"
  fi
  printf 'xyz_mm = [150.0, 100.0, 700.0]\nrpy_rad = [3.141592653589793, 0.0, 0.0]\n'
  printf 'sweep_start = %s\nsweep_end = %s\nsweep_speed = %s\n' "${head_sweep[@]}"
}

# The cone of fig. 5.18 from one pan of the head across the table (head_sweep): JSON to $1,
# request id $2.
head_request() {
  "$rangefit" request object --id "$2" --model cone --sensor head --sweep "${head_sweep[@]}" \
    --seed 1 --timeout 120 > "$1" 2> "$1.err"
}

# The same cone from both cameras of the head's laser plane in one pan (the devices' configured
# sweep): JSON to $1, request id $2.
two_head_camera_request() {
  "$rangefit" request object --id "$2" --model cone --sensors head,head_b --seed 1 \
    --timeout 120 > "$1" 2> "$1.err"
}

# The cone in $1 stands where fig. 5.18 puts it, (213.074, 110.438, 40) mm, upright.
# The simulated head (driver = "sim", same scene, [fusion.pan_tilt] and request) finds it within
# 0.033-0.092 mm and 0.14-0.27 deg (noise and detection seeds 1-3; pan_tilt_sim_accuracy.sh).
# Through the real drivers in the emulated VM the profile stamps (the ranger's clock) and the
# angle stamps (SYNC receive) carry the VM's scheduling jitter; an offset of 10 ms between the two
# streams turns each profile by 0.05 deg of pan (5 deg/s), moving the cone 0.58 mm along the sweep
# at its 660 mm range. The bounds are the simulated head's worst errors plus that: 0.7 mm, 0.6 deg.
# Each camera's profiles carry such an offset (its own ranger's clock against the same angles):
# the two-camera request is held to the same bounds (measured 0.129 mm, 0.197 deg).
head_accurate() {
  python3 "$src/test/hil/part_error.py" "$1" --at 213.074 110.438 40.0 --max-mm 0.7 --max-deg 0.6
}

# Both cameras of the head fed the cloud of $2, a two-camera answer, against $1, the one-camera
# answer of head_request: points per second of scan. The number of points alone does not tell,
# as a request records from its arrival until the head has completed a pan (4 .. 10 s of the
# peer's 6.3 s cycle). Each camera streams 25 profiles/s of 128 points, of which 116.6 (first
# camera) and 114.7 (second) hit the table top on average over the pan (the recordings), so one
# camera fills the cloud at ~2900 points/s (measured 2880-2990) and two at about twice that
# (measured 5710/s, 1.98 times). With one camera's profiles only, the ratio is about 1: the bound
# is 1.5.
both_head_cameras() {
  python3 - "$1" "$2" <<'PY'
import json, sys
one, both = (json.load(open(f)) for f in sys.argv[1:3])
rate = lambda r: r["num_points"] / max(r["scan_seconds"], 1e-3)
ratio = rate(both) / max(rate(one), 1e-3)
print("  one camera: %d points in %.1f s (%.0f/s); both: %d points in %.1f s (%.0f/s): %.2f times"
      % (one["num_points"], one["scan_seconds"], rate(one), both["num_points"],
         both["scan_seconds"], rate(both), ratio))
sys.exit(0 if both["found"] and ratio > 1.5 else 1)
PY
}
