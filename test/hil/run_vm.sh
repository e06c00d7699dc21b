#!/usr/bin/env bash
# Hardware-in-the-loop runner: boots a Debian kernel under qemu (TCG), shares the host root
# read-only over 9p (tmpfs overlay on top) and the build folder read-write, boots the host's
# systemd as PID 1 on it (journald, udevd, sysusers: what rangefitd.service runs under on a cell
# PC) into a target that creates vcan0 and vcan1, loads dummy_hcd/libcomposite/usb_f_fs with configfs
# mounted, and runs the ctest tests labelled `hil`. Exits with their exit code; 124 when the VM
# timed out, 125 when it never reported one. Facts behind each step: ../shared/HIL.md.
# Usage: bash test/hil/run_vm.sh BUILD_DIR   (build first: cmake --build BUILD_DIR)
#   HIL_CMD="..." runs that command in the VM instead of the hil tests (e.g. a benchmark).
set -euo pipefail
build=$(realpath "${1:?usage: run_vm.sh BUILD_DIR}")
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../.." && pwd)
bash "$here/deps.sh"
cache=$build/hil-cache
mkdir -p "$cache"

# 1. Kernel: the package linux-image-amd64 depends on, cached by its name and the module list.
pkg=$(apt-cache depends linux-image-amd64 | awk '/Depends: linux-image-[0-9]/{print $2; exit}')
mods=(net/can drivers/net/can net/9p fs/9p fs/netfs fs/fscache fs/overlayfs drivers/virtio
      drivers/usb/common drivers/usb/core drivers/usb/gadget fs/configfs fs/autofs)
tree=$cache/$pkg-$(echo "${mods[*]}" | md5sum | cut -c1-8)
if [[ ! -f $tree/.done ]]; then
  rm -rf "$tree" && mkdir -p "$tree/deb"
  (cd "$tree/deb" && apt-get download -o APT::Sandbox::User=root "$pkg" >/dev/null)
  ex=$tree/x && mkdir -p "$ex"
  dpkg-deb --fsys-tarfile "$tree"/deb/*.deb | tar -x -C "$ex" --wildcards './boot/vmlinuz-*' \
    "${mods[@]/#/./lib/modules/*/kernel/}" './lib/modules/*/modules.*' 2>/dev/null || true
  ver=$(ls "$ex/lib/modules")
  depmod -b "$ex" "$ver"
  mv "$ex"/boot/vmlinuz-* "$tree/vmlinuz"
  # The uncompressed vmlinux boots via PVH and skips ~2.5 s of emulated decompression.
  off=$(LC_ALL=C grep -abo -m1 $'\xfd7zXZ' "$tree/vmlinuz" | head -1 | cut -d: -f1 || true)
  if [[ -n $off ]]; then
    tail -c +$((off + 1)) "$tree/vmlinuz" | xz -dcq > "$tree/vmlinux" 2>/dev/null || true
  fi
  mv "$ex/lib/modules/$ver" "$tree/modules" && echo "$ver" > "$tree/version"
  rm -rf "$ex" "$tree/deb" && touch "$tree/.done"
fi
kernel=$tree/vmlinuz
[[ -s $tree/vmlinux ]] && kernel=$tree/vmlinux
ver=$(cat "$tree/version")

# 2. Initramfs: busybox, the 9p/overlay modules, and an init that chroots into the host root.
work=$build/hil-run && rm -rf "$work" && mkdir -p "$work/initrd"/{bin,modules,proc,sys,dev,host,ovl,newroot}
cp /bin/busybox "$work/initrd/bin/busybox"
for m in virtio_ring virtio virtio_pci_modern_dev virtio_pci_legacy_dev virtio_pci netfs fscache \
         9pnet 9pnet_virtio 9p overlay autofs4; do
  f=$(find "$tree/modules" -name "$m.ko*" | head -1)
  [[ -n $f ]] && cp "$f" "$work/initrd/modules/$m.ko"
done
cat > "$work/initrd/init" <<INIT
#!/bin/busybox sh
/bin/busybox --install -s /bin
mount -t proc proc /proc; mount -t sysfs sys /sys; mount -t devtmpfs dev /dev
for m in virtio_ring virtio virtio_pci_modern_dev virtio_pci_legacy_dev virtio_pci netfs fscache 9pnet 9pnet_virtio 9p overlay autofs4; do
  [ -f /modules/\$m.ko ] && insmod /modules/\$m.ko 2>/dev/null
done
mount -t 9p -o trans=virtio,version=9p2000.L,ro hostroot /host
mount -t tmpfs tmpfs /ovl && mkdir -p /ovl/up /ovl/work
mount -t overlay overlay -o lowerdir=/host,upperdir=/ovl/up,workdir=/ovl/work /newroot
for d in proc sys dev tmp run; do mkdir -p /newroot/\$d; done
mount -t proc proc /newroot/proc; mount -t sysfs sys /newroot/sys; mount --bind /dev /newroot/dev
mount -t tmpfs tmpfs /newroot/tmp; mount -t tmpfs tmpfs /newroot/run
# The checkout and the build folder go on top of the fresh /tmp and /run: either may live there.
mkdir -p /newroot$src && mount --bind /host$src /newroot$src
mkdir -p /newroot$build
mount -t 9p -o trans=virtio,version=9p2000.L,msize=262144 build /newroot$build
mkdir -p /newroot/lib/modules/$ver && mount --bind /newroot$tree/modules /newroot/lib/modules/$ver
# systemd boots the host's units into rangefit-hil.target (kernel command line), not the host's
# default target; the run unit reports the exit code on the console and powers off.
# The host root may be a container's: systemd must not take the VM for one (it would skip udev).
mkdir -p /newroot/etc/systemd/system && rm -f /newroot/.dockerenv /newroot/run/.containerenv
cp /newroot$work/rangefit-hil.target /newroot$work/rangefit-hil.service /newroot/etc/systemd/system/
exec switch_root /newroot /lib/systemd/systemd
INIT
chmod +x "$work/initrd/init"
(cd "$work/initrd" && find . | cpio -o -H newc --quiet) > "$work/initramfs.cpio"

# The Debian package (`cpack -G DEB`, prefix /usr: the programs in /usr/sbin and /usr/bin, the
# configuration as conffiles in /etc/rangefitd, unit, udev rule and sysusers file under
# /usr/lib), built here on the host; the service test installs it with dpkg into the VM's root.
# A build configured for another prefix (the default /usr/local) gets a sibling build tree
# BUILD_DIR-deb with prefix /usr and only the two programs; at the same depth as BUILD_DIR, its
# compiles hit the compiler cache of BUILD_DIR's (only the programs' mains differ).
if [[ -x $build/daemon/rangefitd/rangefitd && -x $build/daemon/cli/rangefit ]]; then
  t_deb=$SECONDS
  cache_of() { sed -n "s|^$1:[A-Z]*=||p" "$build/CMakeCache.txt"; }
  deb_build=$build
  if [[ $(cache_of CMAKE_INSTALL_PREFIX) != /usr ]]; then
    deb_build=$build-deb
    cmake -S "$src" -B "$deb_build" -DCMAKE_INSTALL_PREFIX=/usr \
      -DCMAKE_BUILD_TYPE="$(cache_of CMAKE_BUILD_TYPE)" -DRANGEFIT_SANITIZE="$(cache_of RANGEFIT_SANITIZE)" \
      -DRANGEFIT_WITH_SIM="$(cache_of RANGEFIT_WITH_SIM)" -DRANGEFIT_BUILD_TESTS=OFF \
      -DRANGEFIT_BUILD_BENCHMARKS=OFF > "$work/deb-configure.log" 2>&1 ||
      { cat "$work/deb-configure.log"; exit 1; }
    cmake --build "$deb_build" -j"$(nproc)" --target rangefit rangefitd > "$work/deb-build.log" 2>&1 ||
      { tail -50 "$work/deb-build.log"; exit 1; }
  fi
  (cd "$deb_build" && cpack -G DEB -B "$work/deb") > "$work/cpack.log" 2>&1 ||
    { cat "$work/cpack.log"; exit 1; }
  rm -rf "$work/deb/_CPack_Packages"
  echo "HIL: $(cd "$work/deb" && ls ./*.deb) built from $deb_build in $((SECONDS - t_deb)) s"
fi

# 3. The command the VM runs (a file in the share: the kernel command line cannot carry spaces),
# as a unit of the target systemd boots into.
cat > "$work/rangefit-hil.target" <<UNIT
[Unit]
Description=rangefit hardware-in-the-loop run
Requires=rangefit-hil.service
After=rangefit-hil.service
AllowIsolate=yes
UNIT
cat > "$work/rangefit-hil.service" <<UNIT
[Unit]
Description=rangefit hardware-in-the-loop tests
After=systemd-udevd.service systemd-journald.service systemd-sysusers.service dbus.socket
Wants=systemd-udevd.service dbus.socket
[Service]
Type=oneshot
StandardOutput=tty
StandardError=tty
TTYPath=/dev/ttyS0
ExecStart=/bin/bash $work/run.sh
UNIT
cat > "$work/run.sh" <<RUN
bash $work/cmd.sh
echo EXIT_CODE=\$?
systemctl --force --force poweroff
RUN
cat > "$work/cmd.sh" <<CMD
set -e
export PATH=/usr/sbin:/usr/bin:/sbin:/bin
modprobe vcan; modprobe can_raw
# vcan0: the CSS cell's robot joint and the stripe cell; vcan1: the pan-tilt head's own bus.
for can in vcan0 vcan1; do
  ip link add dev \$can type vcan && ip link set \$can mtu 72 && ip link set up \$can
done
ip link set lo up
# USB: a dummy host+device controller pair, configfs gadgets with FunctionFS, udevd for hotplug.
modprobe dummy_hcd; modprobe libcomposite; modprobe usb_f_fs
mountpoint -q /sys/kernel/config || mount -t configfs none /sys/kernel/config
systemctl is-active -q systemd-udevd || echo "HIL: udevd is not running"
${HIL_CMD:-ctest --test-dir $build -L hil --output-on-failure ${HIL_CTEST_ARGS:-}}
CMD

# Host units the run does not need (and that fail or wait in the VM).
masks=""
for u in systemd-binfmt.service proc-sys-fs-binfmt_misc.automount systemd-timesyncd.service \
         systemd-update-utmp.service systemd-journal-flush.service systemd-random-seed.service \
         dev-hugepages.mount sys-kernel-debug.mount sys-kernel-tracing.mount; do
  masks+=" systemd.mask=$u"
done
log=$work/console.log
set +e
timeout "${HIL_TIMEOUT:-1500}" qemu-system-x86_64 -machine q35,accel=tcg -cpu max -smp 2 -m 1024 \
  -nodefaults -display none -serial stdio -no-reboot -kernel "$kernel" \
  -initrd "$work/initramfs.cpio" -append "console=ttyS0 panic=-1 quiet systemd.unit=rangefit-hil.target $masks ${HIL_KERNEL_ARGS:-systemd.show_status=0}" \
  -fsdev local,id=r,path=/,security_model=none,readonly=on,multidevs=remap \
  -device virtio-9p-pci,fsdev=r,mount_tag=hostroot \
  -fsdev local,id=b,path="$build",security_model=none,multidevs=remap \
  -device virtio-9p-pci,fsdev=b,mount_tag=build | tee "$log"
rc=${PIPESTATUS[0]}
set -e
[[ $rc == 124 ]] && { echo "HIL: VM timed out"; exit 124; }
code=$(tr -d '\r' < "$log" | sed -n 's/^EXIT_CODE=\([0-9]*\)$/\1/p' | tail -1)
[[ -z $code ]] && { echo "HIL: the VM never reported an exit code"; exit 125; }
exit "$code"
