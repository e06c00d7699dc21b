#!/usr/bin/env bash
# Packages the hardware-in-the-loop VM needs on the host (kept out of scripts/deps.sh: the normal
# suite does not boot a VM). --no-install-recommends keeps qemu from pulling in GTK (~280 MiB).
set -euo pipefail
pkgs=(qemu-system-x86 busybox-static can-utils cpio kmod iproute2 udev xz-utils)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""; [[ $(id -u) == 0 ]] || sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
