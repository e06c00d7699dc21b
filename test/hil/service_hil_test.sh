#!/usr/bin/env bash
# The product as deployed, in the HIL VM (systemd is PID 1, test/hil/run_vm.sh): the Debian
# package is installed with dpkg, rangefitd.service starts from the packaged unit with
# driver = "real" devices against the simulated cells on the real transports (rangefit_cell_peer:
# the CSS as a USB gadget on dummy_hcd, the robot's last joint as a CiA 402 node on vcan0; the
# stripe cell's ranger on CAN FD on vcan0 and its linear axis' Festo drive as a Modbus TCP server
# on loopback; the pan-tilt head's two CiA 402 axes and CAN FD rangers on vcan1), and a user's
# checks run against it: a bore request over DDS, the CSS unplugged mid-scan, an object request on
# the stripe cell, the axis' server stopped mid-sweep, an object request on the pan-tilt head, its
# tilt axis silent mid-stroke, one from both cameras of the head, the watchdog
# after SIGSTOP, the journal, a broken reload, the sandbox's score, USB devices and writes.
# Usage (root, in the VM): service_hil_test.sh BUILD_DIR SOURCE_DIR
set -uo pipefail
build=${1:?usage: service_hil_test.sh BUILD_DIR SOURCE_DIR}
src=${2:?usage: service_hil_test.sh BUILD_DIR SOURCE_DIR}
failures=0
# Everything also goes to BUILD_DIR/hil-run/service_hil.log, readable on the host after the VM.
mkdir -p "$build/hil-run" && exec > >(tee "$build/hil-run/service_hil.log") 2>&1
start=$EPOCHREALTIME
since() { awk -v a="$1" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f", b - a }'; }
stamp() { since "$start"; }
log() { echo "HIL service [$(stamp) s]: $*"; }
pass() { log "PASS $*"; }
fail() { log "FAIL $*"; failures=$((failures + 1)); }
check() { local what=$1; shift; if "$@"; then pass "$what"; else fail "$what"; fi; }
die() { log "FATAL $*"; journalctl -u rangefitd --no-pager -n 50; exit 1; }

[[ $(cat /proc/1/comm) == systemd ]] || die "systemd is not PID 1 (run in test/hil/run_vm.sh)"
work=$(mktemp -d /tmp/rangefit-service-hil.XXXXXX)
peer_pid=""
cleanup() {
  systemctl stop rangefitd 2>/dev/null
  [[ -n $peer_pid ]] && { echo quit >&7; wait "$peer_pid" 2>/dev/null; }
}
trap cleanup EXIT

# 1. Install the Debian package (cpack -G DEB, built on the host by run_vm.sh) with dpkg into the
# VM's root (a tmpfs overlay over the host's, where rangefit is not installed and its
# dependencies are): its postinst creates the group, reloads udev and systemd. The unit is then
# checked as installed with `systemd-analyze verify`.
deb=$(ls "$build"/hil-run/deb/rangefit_*.deb 2>/dev/null | head -1)
[[ -f $deb ]] || die "no Debian package in $build/hil-run/deb (run_vm.sh builds it with cpack -G DEB)"
! dpkg-query -W rangefit > /dev/null 2>&1 || die "rangefit is already installed in the VM's root"
t0=$EPOCHREALTIME
dpkg -i "$deb" > "$work/dpkg.log" 2>&1; rc=$?
cat "$work/dpkg.log"
check "dpkg -i $(basename "$deb") into the VM's root (exit $rc, $(since "$t0") s)" test $rc -eq 0
((rc == 0)) || die "the package did not install"
check "dpkg: rangefit installed" \
  test "$(dpkg-query -W -f='${Status}' rangefit)" = "install ok installed"
unit=$(systemctl show -P FragmentPath rangefitd.service)
[[ -f $unit ]] || die "rangefitd.service not found after install"
config=$(sed -n 's/^ExecStart=.* --config \(.*\)$/\1/p' "$unit")
prefix=$(sed -n 's|^ExecStart=\(.*\)/sbin/rangefitd .*|\1|p' "$unit")
rangefit=$prefix/bin/rangefit
confdir=$(dirname "$config")
rules=$(dpkg -L rangefit | grep '/udev/rules.d/.*rangefit')
log "unit $unit, config $config, udev rule $rules"
# (Debian's /lib is /usr/lib: systemd may name the unit by either.)
check "packaged layout: /usr/sbin/rangefitd, /etc/rangefitd/rangefitd.toml, /usr/lib units" \
  test "$prefix:$config:$(realpath "$unit")" = \
  "/usr:/etc/rangefitd/rangefitd.toml:/usr/lib/systemd/system/rangefitd.service"
check "dpkg records the configuration as conffiles" \
  bash -c "dpkg-query -W -f='\${Conffiles}' rangefit | grep -q '$config'"
verify=$(systemd-analyze verify "$unit" 2>&1); rc=$?
[[ -n $verify ]] && echo "$verify"
check "systemd-analyze verify $unit: clean (exit $rc)" test $rc -eq 0 -a -z "$verify"
check "postinst created the group rangefit (sysusers)" getent group rangefit
check "rangefitd.service is known to systemd, not enabled by the package" \
  test "$(systemctl is-enabled rangefitd 2>/dev/null)" = disabled

# 2. The configuration: the CSS, the robot, the stripe ranger and its axis as real devices;
# loopback-only DDS (the VM has no other interface). The shipped Cyclone configuration is replaced
# by the loopback one.
cp "$src/systemd/cyclonedds-loopback.xml" "$confdir/cyclonedds.xml"
cp "$src/data/models/cone.toml" "$confdir/cone.toml"
axis_port=1502
source "$src/test/hil/stripe_checks.sh"
source "$src/test/hil/pan_tilt_checks.sh"
cat > "$config" <<TOML
[service]
scan_timeout_s = 30.0
stall_timeout_s = 30.0
bore_sensor = "css"
object_sensor = "stripe"
[dds]
config_uri = "file://$confdir/cyclonedds.xml"
diagnostics_period_s = 1.0
[spool]
directory = "/var/lib/rangefitd/spool"
# The emulated VM (TCG on a shared runner) stalls its threads for tens of ms: the joint stream
# may pause longer than a real controller's, while the joint moves at constant speed.
[fusion.time]
max_reference_gap_ms = 250
max_faults = 50
# The cell's geometry as the simulated one (hal::StripeCellGeometry), but the table is taken to
# the sweep's start at 50 mm/s, not the thesis' 6.3 (the VM's time budget).
[fusion.stripe_cell]
max_speed_mm_s = 50.0
[[devices]]
name = "css"
kind = "css"
driver = "real"
transport = "usb:1d6b:0105"
motion = "robot"
[[devices]]
name = "robot"
kind = "robot"
driver = "real"
transport = "vcan0"
can_node = 1
# The stripe cell (thesis fig. 5.8): the ranger on CAN FD, the table's axis on Modbus TCP. The
# cell's table frame sits in the scene as fig. 5.18's [sensors.stripe] mounts it, so the results
# are in the scene's frame, as the simulated cell gives them.
$(stripe_device stripe 32)
# A second camera of the laser plane, mirrored to its other side, on the same axis.
$(stripe_device stripe_b 33)
[[fusion.stripe_cell.cameras]]
name = "stripe_b"
ranger_position_cell_mm = [0, 200, 600]
ranger_rpy_cell_rad = [3.141592653589793, 0, 0]
baseline_mm = -300
[[devices]]
name = "axis"
kind = "axis"
driver = "real"
transport = "127.0.0.1:$axis_port"
# The pan-tilt head over the same table top (pan_tilt_checks.sh).
$(head_device head 32)
# A second camera of the head's laser plane, mirrored to its other side, on the same head.
$(head_device head_b 33 head)
$(head_fusion)
[[fusion.pan_tilt.cameras]]
name = "head_b"
baseline_mm = -425
[[objects]]
model = "cone.toml"
TOML
cp "$config" "$work/good.toml"

# 3. The cell: the peer's commands come from fd 7 (a fifo), its output goes to a log.
mkfifo "$work/peer.in"
"$build/test/hil/cell_peer/rangefit_cell_peer" --frames "$build/test/hil/cell_peer/bore_plate_css_6s.frames" \
  --can vcan0 --node 1 --scan-s 6 \
  --stripe "$build/test/hil/cell_peer/table_top_fig5_18.profiles" --modbus-port $axis_port \
  --ranger-node 32 --stripe-b "$build/test/hil/cell_peer/table_top_fig5_18_b.profiles" \
  --ranger-b-node 33 \
  --pan-tilt "$build/test/hil/cell_peer/table_top_fig5_18_pan_tilt.profiles" --head-can vcan1 \
  --pan-tilt-b "$build/test/hil/cell_peer/table_top_fig5_18_pan_tilt_b.profiles" \
  --head-ranger-b-node 33 --pan-half-deg 10 --head-sweep-s 4 --head-rate-hz 25 \
  < "$work/peer.in" > "$work/peer.log" 2>&1 &
peer_pid=$!
exec 7> "$work/peer.in"
for _ in $(seq 100); do grep -q "pan-tilt head up" "$work/peer.log" && break; sleep 0.1; done
grep -q "pan-tilt head up" "$work/peer.log" || die "cell peer did not come up: $(cat "$work/peer.log")"
log "$(cat "$work/peer.log")"

# 4. Start the service from the shipped unit (Type=notify: start returns after READY=1).
t0=$EPOCHREALTIME
systemctl start rangefitd || die "systemctl start rangefitd failed"
log "rangefitd active after $(since "$t0") s"
# The head's traffic (its drives answering every SYNC, its ranger's CAN FD stream) loads the
# emulated VM's CPUs and moved the stripe cell's profile stamps by ~27 ms (its cone 0.27 mm along
# the sweep, against 0.005-0.02 mm without the head): the head falls silent until its checks.
sleep 2; echo head-off >&7
export CYCLONEDDS_URI="file://$src/systemd/cyclonedds-loopback.xml"
bore() {  # one bore request for the 12 mm straight bore under the CSS: JSON to $1
  "$rangefit" request bore --id "$2" --position 0.3 -0.2 285.8 --axis 0 0 -1 --radius 6 \
    --plane-normal 0 0 1 --timeout 60 > "$1" 2> "$1.err"
}
accurate() {  # the bore in $1 is the 12 mm straight bore at (0, 0, 285.8), axis z, as cast
  # The simulated cell (driver = "sim") finds this bore exactly on the same noise-free 6 s stroke
  # and within 0.05 mm, 0.1 deg with noise (test/daemon/sim_bore_service_test); through the real
  # drivers in the emulated VM the stamps of both streams carry the VM's scheduling jitter:
  # measured 0.086 mm and 0.42 deg on a runner at load 20. The bounds are twice the position and
  # radius and a little over the axis error the real-driver path gave there.
  python3 "$src/test/hil/part_error.py" "$1" --at 0 0 285.8 --radius 6 --max-mm 0.2 \
    --max-deg 0.6 --max-radius-mm 0.05
}

# The first request after a device came back: $1 the request function (bore, object_request,
# head_request), $2 its JSON file, $3 its id, $4 what came back. Under emulation on a loaded runner
# a CAN heartbeat (300 ms) or a Modbus reply can miss its deadline just after the device returns:
# one more try, logged with the first answer's reason. Returns the last request's exit code.
ask_after_recovery() {
  local request=$1 out=$2 id=$3 what=$4 rc
  "$request" "$out" "$id"; rc=$?
  if ((rc != 0)); then
    log "after $what: $(grep -o '"reason": "[^"]*"' "$out"); asking once more"
    "$request" "$out" "$id-2"; rc=$?
  fi
  return "$rc"
}

log "bore request"
bore "$work/bore1.json" first; rc=$?
cat "$work/bore1.json" "$work/bore1.json.err" | head -60
check "bore request over DDS answered (exit $rc)" test $rc -eq 0
check "bore found from the real-driver scan within the simulated cell's accuracy" \
  accurate "$work/bore1.json"

# 5. Unplug the CSS mid-scan: an error result naming the device; then the next request succeeds.
bore "$work/unplug.json" unplugged & req=$!
sleep 3; echo unplug >&7; sleep 1; echo replug >&7
wait $req; rc=$?
cat "$work/unplug.json" | head -20
check "request during unplug gives an error result (exit $rc)" test $rc -eq 1
ask_after_recovery bore "$work/bore2.json" after-unplug "replug"; rc=$?
check "request after replug succeeds (exit $rc)" test $rc -eq 0

# 5b. The stripe cell: an object request answered from the ranger's CAN FD profiles while the
# service drives the table through the laser plane over Modbus TCP; then the axis' server stops
# mid-sweep.
log "object request (stripe cell)"
object_request "$work/cone1.json" cone-first; rc=$?
head -40 "$work/cone1.json" "$work/cone1.json.err"
check "object request over DDS answered (exit $rc)" test $rc -eq 0
check "cone found from the real-driver stripe scan within the simulated cell's accuracy" \
  cone_accurate "$work/cone1.json"

"$rangefit" watch --seconds 60 > "$work/watch.log" 2>&1 & watch_pid=$!
# The peer stops its Modbus server the moment the sweep (150 -> 230 mm) passes 170 mm.
echo "axis-stop-past 170" >&7
object_request "$work/cone-fault.json" cone-axis-lost; rc=$?
log "after the request: $(axis_status); starting the axis' server again"
echo axis-start >&7
head -20 "$work/cone-fault.json" "$work/cone-fault.json.err"
check "request during the axis outage gives an error result (exit $rc)" test $rc -eq 1
check "the error result names the axis" grep -q '"reason": "[^"]*axis' "$work/cone-fault.json"
ask_after_recovery object_request "$work/cone2.json" cone-after "the axis came back"; rc=$?
check "object request after the axis came back succeeds (exit $rc)" test $rc -eq 0
check "cone found again within the simulated cell's accuracy" cone_accurate "$work/cone2.json"
kill "$watch_pid" 2>/dev/null; wait "$watch_pid" 2>/dev/null
check "diagnostics reported the axis at ERROR during the outage, then OK" \
  device_diagnostics "$work/watch.log" axis

# 5b'. Both cameras of the laser plane: one sweep of the table, each camera's CAN FD profiles
# fused with its own geometry.
# The second camera is silent until now (its traffic would load the emulated CPUs): its driver
# reported the node lost and takes it back at its boot-up heartbeat.
echo camera-b-on >&7
sleep 2
log "object request (both cameras of the stripe cell)"
ask_after_recovery two_camera_request "$work/cone-both.json" cone-both "the second camera came on"
rc=$?
log "after the request: $(axis_status)"
echo camera-b-off >&7
head -40 "$work/cone-both.json" "$work/cone-both.json.err"
check "two-camera object request over DDS answered (exit $rc)" test $rc -eq 0
check "cone found from both cameras' real-driver scans within the simulated cell's accuracy" \
  cone_accurate "$work/cone-both.json"

# 5c. The pan-tilt head: an object request answered from the head's CAN FD profiles and its two
# CiA 402 axes while the cell program pans it; then the tilt axis stops answering mid-stroke.
echo head-on >&7
sleep 2
log "object request (pan-tilt head)"
head_request "$work/head1.json" head-first; rc=$?
head -40 "$work/head1.json" "$work/head1.json.err"
check "pan-tilt object request over DDS answered (exit $rc)" test $rc -eq 0
check "cone found from the real-driver pan-tilt scan within the simulated head's accuracy" \
  head_accurate "$work/head1.json"

"$rangefit" watch --seconds 90 > "$work/watch-head.log" 2>&1 & watch_pid=$!
echo tilt-stop-mid-stroke >&7
head_request "$work/head-fault.json" head-tilt-lost; rc=$?
echo status >&7
sleep 0.5
log "after the request: $(grep -o 'head profiles.*' "$work/peer.log" | tail -1); the tilt axis answers again"
echo tilt-start >&7
head -20 "$work/head-fault.json" "$work/head-fault.json.err"
check "request while the tilt axis is silent gives an error result (exit $rc)" test $rc -eq 1
check "the error result names the head" grep -q '"reason": "[^"]*head' "$work/head-fault.json"
ask_after_recovery head_request "$work/head2.json" head-after "the tilt axis came back"; rc=$?
check "pan-tilt request after the tilt axis came back succeeds (exit $rc)" test $rc -eq 0
check "cone found again within the simulated head's accuracy" head_accurate "$work/head2.json"
kill "$watch_pid" 2>/dev/null; wait "$watch_pid" 2>/dev/null
check "diagnostics reported the head's axes at ERROR while the tilt was silent, then OK" \
  device_diagnostics "$work/watch-head.log" head/angles

# 5c'. Both cameras of the head's laser plane: one pan of the head, each camera's CAN FD profiles
# fused with its own side of the plane. The second camera is silent until now (its traffic would
# load the emulated CPUs), as the stripe cell's.
echo head-camera-b-on >&7
sleep 2
log "object request (both cameras of the pan-tilt head)"
ask_after_recovery two_head_camera_request "$work/head-both.json" head-both \
  "the head's second camera came on"
rc=$?
echo head-camera-b-off >&7
head -40 "$work/head-both.json" "$work/head-both.json.err"
check "two-camera pan-tilt object request over DDS answered (exit $rc)" test $rc -eq 0
check "cone found from both head cameras' real-driver scans within the simulated head's accuracy" \
  head_accurate "$work/head-both.json"
check "both head cameras filled the cloud (points per second of scan against one camera's)" \
  both_head_cameras "$work/head1.json" "$work/head-both.json"
echo head-off >&7

# 6. Journal: the service's lines with their priorities.
journalctl -u rangefitd --no-pager -o short-monotonic | tail -30
# PRIORITY as journald stored it (the service logs through spdlog's systemd sink).
priority_of() {
  journalctl -u rangefitd -o json --no-pager | python3 -c '
import json, sys
for line in sys.stdin:
    e = json.loads(line)
    if sys.argv[1] in str(e.get("MESSAGE", "")):
        print(e.get("PRIORITY")); break' "$1"
}
p=$(priority_of 'css driver on usb:1d6b:0105 started')
check "journal: the driver start at info (PRIORITY $p)" test "$p" = 6
p=$(priority_of 'scan incomplete (unplugged)')
check "journal: the failed scan of the unplug at err (PRIORITY $p)" test "$p" = 3

# 7. A broken configuration on reload: the old one stays, the service answers.
echo 'this is = = not toml' > "$config"
systemctl reload rangefitd; sleep 1
cp "$work/good.toml" "$config"
check "service still active after a broken reload" systemctl is-active -q rangefitd
check "journal says the reload was refused" \
  bash -c "journalctl -u rangefitd -p err --no-pager | grep -qi 'reload'"

# 8. The sandbox: systemd's score, and what the shipped sandbox lets a process do.
systemd-analyze security --no-pager rangefitd.service > "$work/security.txt" 2>&1
grep -E "Overall exposure" "$work/security.txt"
score=$(sed -n 's/.*Overall exposure level for rangefitd.service: \([0-9.]*\).*/\1/p' "$work/security.txt")
check "systemd-analyze security $score <= 1.5" python3 -c "import sys; sys.exit(0 if float('$score' or 9) <= 1.5 else 1)"
pid=$(systemctl show -P MainPID rangefitd)
gid=$(getent group rangefit | cut -d: -f3)
check "service runs in group rangefit" bash -c "grep '^Groups:' /proc/$pid/status | grep -qw $gid"
css_dev="" other_dev=""
for d in /sys/bus/usb/devices/*; do
  [[ -f $d/idVendor && -f $d/devnum ]] || continue
  node=$(printf '/dev/bus/usb/%03d/%03d' "$(cat "$d/busnum")" "$(cat "$d/devnum")")
  if [[ $(cat "$d/idVendor"):$(cat "$d/idProduct") == 1d6b:0105 ]]; then css_dev=$node; else other_dev=$node; fi
done
log "CSS at $css_dev ($(stat -c '%G %a' "$css_dev")), another USB device at $other_dev"
# A probe with the unit's own sandbox (its [Service] lines, not its program): open and write.
props=()
while IFS= read -r line; do props+=(-p "$line"); done < <(
  sed -n '/^\[Service\]/,/^\[/p' "$unit" | grep -E '^[A-Z][A-Za-z]+=' |
    grep -vE '^(Type|NotifyAccess|ExecStart|ExecReload|Restart|RestartSec|WatchdogSec|TimeoutStopSec)=')
# systemd-run takes no symbolic IPAddressAllow= names: the same networks as prefixes.
props=("${props[@]/localhost/127.0.0.0/8 ::1/128}")
props=("${props[@]/link-local/169.254.0.0/16 fe80::/64}")
props=("${props[@]/multicast/224.0.0.0/4 ff00::/8}")
# Prints ran:0 when the action succeeded in the sandbox, ran:1 when it was refused; anything
# else (systemd-run failed) passes neither check.
probe() {
  systemd-run --quiet --wait --pipe --collect "${props[@]}" /bin/bash -c "$1 2>/dev/null; echo ran:\$?" 2>&1
}
allowed() { probe "$1" | tee /dev/stderr | grep -qx 'ran:0'; }
denied() { probe "$1" | tee /dev/stderr | grep -qx 'ran:1'; }
check "sandbox opens the CSS read-write" allowed "exec 3<> $css_dev"
check "sandbox cannot open another USB device" denied "exec 3<> $other_dev"
check "sandbox writes its state directory" allowed "touch /var/lib/rangefitd/probe"
# (/tmp and /var/tmp are the unit's own, PrivateTmp=; they are removed when it stops.)
for dir in /etc /usr/local /var/lib /root /; do
  check "sandbox cannot write $dir" denied "touch $dir/rangefitd-probe"
done

# 9. The watchdog: a stopped process stops its WATCHDOG=1; systemd kills and restarts it.
mkdir -p /run/systemd/system/rangefitd.service.d
printf '[Service]\nWatchdogSec=4s\n' > /run/systemd/system/rangefitd.service.d/hil-watchdog.conf
systemctl daemon-reload && systemctl restart rangefitd
old=$(systemctl show -P MainPID rangefitd)
systemctl kill -s SIGSTOP rangefitd
deadline=$((SECONDS + 60))  # WatchdogSec 4 s, RestartSec 2 s, start-up; slow under emulation
while ((SECONDS < deadline)); do
  new=$(systemctl show -P MainPID rangefitd)
  [[ $new != 0 && $new != "$old" ]] && systemctl is-active -q rangefitd && break
  sleep 1
done
check "watchdog restarted the stopped service (pid $old -> $new)" test "$new" != "$old"
check "journal shows the watchdog timeout" \
  bash -c "journalctl -u rangefitd --no-pager | grep -qi 'watchdog timeout'"
journalctl -u rangefitd --no-pager | grep -i watchdog | tail -3
rm -rf /run/systemd/system/rangefitd.service.d; systemctl daemon-reload

log "$failures failure(s)"
exit $((failures > 0))
