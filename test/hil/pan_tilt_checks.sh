# The pan-tilt head's part of service_hil_test.sh (sourced there: uses $rangefit, $src, $work, fd 7
# to the cell peer and its log $work/peer.log): the head's device table, the object request, what
# a user checks of its answer.

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
head_device() {
  cat <<TOML
[[devices]]
name = "head"
kind = "pan_tilt"
driver = "real"
transport = "vcan1"
can_node = 32
pan_node = 1
tilt_node = 2
xyz_mm = [150.0, 100.0, 700.0]
rpy_rad = [3.141592653589793, 0.0, 0.0]
TOML
}

# The cone of fig. 5.18 from one pan of the head across the table, -10 .. +10 deg at 5 deg/s (the
# peer's head: rangefit_cell_peer --pan-half-deg 10 --head-sweep-s 4 --head-rate-hz 25): JSON to
# $1, request id $2.
head_request() {
  "$rangefit" request object --id "$2" --model cone --sensor head \
    --sweep -0.174533 0.174533 0.0872665 --seed 1 --timeout 120 > "$1" 2> "$1.err"
}

# The cone in $1 stands where fig. 5.18 puts it, (213.074, 110.438, 40) mm, upright.
# The simulated head (driver = "sim", same scene, [fusion.pan_tilt] and request) finds it within
# 0.033-0.092 mm and 0.14-0.27 deg (noise and detection seeds 1-3; pan_tilt_sim_accuracy.sh).
# Through the real drivers in the emulated VM the profile stamps (the ranger's clock) and the
# angle stamps (SYNC receive) carry the VM's scheduling jitter; an offset of 10 ms between the two
# streams turns each profile by 0.05 deg of pan (5 deg/s), moving the cone 0.58 mm along the sweep
# at its 660 mm range. The bounds are the simulated head's worst errors plus that: 0.7 mm, 0.6 deg.
head_accurate() {
  python3 "$src/test/hil/part_error.py" "$1" --at 213.074 110.438 40.0 --max-mm 0.7 --max-deg 0.6
}
