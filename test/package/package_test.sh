#!/usr/bin/env bash
# Installs rangefit as a package would and checks that what the systemd unit runs and reads is
# what was installed: ExecStart is the installed rangefitd, --config, CYCLONEDDS_URI and
# Documentation= name installed files, the configuration's scenes exist. Three roots:
#   1. DESTDIR install of BUILD_DIR (its own prefix, the programs included);
#   2. the Debian package `cpack -G DEB` makes from BUILD_DIR, installed by dpkg into a fresh
#      root (and purged again); skipped, with a message, when dpkg-dev is missing;
#   3. a configure-only tree with prefix /usr, installing the non-program files: the unit must
#      run /usr/sbin/rangefitd and read /etc/rangefitd.
# The unit is checked with `systemd-analyze verify` when it is available. rangefitd is never
# started here (only --version); the service tests do that.
#
#   package_test.sh BUILD_DIR SOURCE_DIR VERSION
set -euo pipefail
build=$1 src=$2 version=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/rangefit_package_test.XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
field() { sed -n "s|^$1=||p" "$2" | head -n 1; }
# GNUInstallDirs: sysconfdir is /etc for the prefix /usr, PREFIX/etc otherwise (and /etc/opt/...
# for /opt/..., which this project does not special-case).
confdir_of() { if [[ $1 == /usr ]]; then echo /etc/rangefitd; else echo "$1/etc/rangefitd"; fi; }

# check_root ROOT PREFIX PROGRAMS(yes|no): the installed tree below ROOT for install prefix PREFIX.
check_root() {
  local root=$1 prefix=$2 programs=$3
  local confdir
  confdir=$(confdir_of "$prefix")
  local unit=$root$prefix/lib/systemd/system/rangefitd.service
  echo "-- $root (prefix $prefix)"
  [[ -f $unit ]] || { fail "no unit at $unit"; return; }

  local exec_start exe config doc uri
  exec_start=$(field ExecStart "$unit")
  exe=${exec_start%% *}
  config=$(sed -n 's|.*--config \([^ ]*\).*|\1|p' <<<"$exec_start")
  doc=$(field Documentation "$unit")
  uri=$(field Environment=CYCLONEDDS_URI "$unit")
  echo "   ExecStart=$exec_start"
  [[ $exe == "$prefix/sbin/rangefitd" ]] || fail "ExecStart runs $exe, not $prefix/sbin/rangefitd"
  [[ $config == "$confdir/rangefitd.toml" ]] || fail "unit reads $config, not $confdir/rangefitd.toml"
  [[ -f $root$config ]] || fail "the unit's --config $config is not installed"
  [[ $doc == file://* && -f $root${doc#file://} ]] || fail "Documentation=$doc is not installed"
  [[ $uri == file://* && -f $root${uri#file://} ]] || fail "CYCLONEDDS_URI=$uri is not installed"
  if [[ -f $root$config ]]; then
    grep -q "^config_uri = \"$uri\"" "$root$config" || fail "config's config_uri is not $uri"
    ! grep -n "@[A-Z_]*@" "$root$config" || fail "unfilled placeholders in $config"
    local scene
    for scene in $(sed -n 's|^scene = "\([^"]\+\)".*|\1|p' "$root$config"); do
      [[ -f $root$scene ]] || fail "config names scene $scene, which is not installed"
    done
  fi
  ! grep -n "@[A-Z_]*@" "$unit" || fail "unfilled placeholders in the unit"
  local share=$root$prefix/share/rangefit
  [[ -f $share/models/mallet.toml && -f $share/scenes/bore_plate.toml ]] ||
    fail "models or scenes missing under $share"
  [[ -f $root$prefix/share/doc/rangefit/README.md ]] || fail "README.md not in share/doc/rangefit"

  if [[ $programs == yes ]]; then
    [[ -x $root$exe ]] || fail "$root$exe is not an executable"
    [[ $("$root$exe" --version) == "rangefitd $version" ]] || fail "rangefitd --version"
    [[ $("$root$prefix/bin/rangefit" --version) == "rangefit $version" ]] || fail "rangefit --version"
    [[ -f $share/idl/rangefit_msgs.idl && -f $share/rangefit_msgs/package.xml ]] ||
      fail "message definitions (idl, rangefit_msgs) missing under $share"
    verify_unit "$root" "$prefix" "$unit"
  fi
}

# systemd-analyze verify needs the binary at the path ExecStart names; verify a copy of the unit
# whose ExecStart points into ROOT (the rest of the unit unchanged). Any message is a failure.
verify_unit() {
  local root=$1 prefix=$2 unit=$3
  if ! command -v systemd-analyze >/dev/null; then
    echo "   systemd-analyze missing: unit not verified"
    return
  fi
  mkdir -p "$work/verify"
  sed "s|^ExecStart=$prefix/|ExecStart=$root$prefix/|" "$unit" >"$work/verify/rangefitd.service"
  local out
  out=$(systemd-analyze verify "$work/verify/rangefitd.service" 2>&1) || fail "systemd-analyze verify failed"
  [[ -z $out ]] || fail "systemd-analyze verify: $out"
  echo "   systemd-analyze verify: clean"
}

prefix=$(sed -n 's|^CMAKE_INSTALL_PREFIX:PATH=||p' "$build/CMakeCache.txt")

# 1. DESTDIR install of the build.
DESTDIR=$work/root cmake --install "$build" >"$work/install.log" ||
  { cat "$work/install.log"; fail "cmake --install failed (rangefit and rangefitd built?)"; }
check_root "$work/root" "$prefix" yes

# 2. The Debian package.
if command -v dpkg-deb >/dev/null && command -v dpkg-shlibdeps >/dev/null; then
  (cd "$build" && cpack -G DEB -B "$work/deb") >"$work/cpack.log" 2>&1 ||
    { cat "$work/cpack.log"; fail "cpack -G DEB failed"; }
  deb=$work/deb/rangefit_${version}_amd64.deb
  if [[ -f $deb ]]; then
    echo "-- $(basename "$deb"): contents"
    dpkg-deb --contents "$deb" | awk '{print "   " $1, $3, $6}'
    depends=$(dpkg-deb --field "$deb" Depends)
    echo "   Depends: $depends"
    [[ $depends == *libc6* && $depends == *libddsc0debian* ]] || fail "Depends lacks shlibdeps"
    mkdir -p "$work/control"
    dpkg-deb --control "$deb" "$work/control"
    echo "   conffiles: $(tr '\n' ' ' <"$work/control/conffiles")"
    for f in rangefitd.toml cyclonedds.xml; do
      grep -qx "$(confdir_of "$prefix")/$f" "$work/control/conffiles" || fail "$f is not a conffile"
    done
    # Every dependency is a Debian package this host has installed, or one an installed package
    # provides (libspdlog1.10 provides libspdlog1.10-fmt9): the host runs the binaries just built.
    installed=$(dpkg-query -W -f='${db:Status-Abbrev} ${Package} ${Provides}\n' |
      sed -n 's/^ii  //p' | sed 's/([^)]*)//g; s/:[a-z0-9]*//g' | tr ', ' '\n\n' | sed '/^$/d')
    for dep in $(tr ',' '\n' <<<"$depends" | sed 's/ *(.*//; s/^ *//'); do
      grep -qx -- "$dep" <<<"$installed" || fail "dependency $dep is not an installed Debian package"
    done
    for script in postinst prerm postrm; do
      [[ -x $work/control/$script ]] || fail "the package has no executable $script"
    done
    # Installed by dpkg into a fresh root (an empty dpkg database; the dependencies are the
    # host's, hence --force-depends; the root has no shell to chroot into, so the maintainer
    # scripts run outside it with DPKG_ROOT set): dpkg records the conffiles, postinst creates
    # the group in that root, and purge removes every file but the group's.
    fresh=$work/fresh-root
    mkdir -p "$fresh/etc" "$fresh/var/lib/dpkg/info" "$fresh/var/lib/dpkg/updates"
    touch "$fresh/var/lib/dpkg/status"
    dpkg --root="$fresh" --log=/dev/null --force-depends --force-script-chrootless -i "$deb" \
      >"$work/dpkg.log" 2>&1 || { cat "$work/dpkg.log"; fail "dpkg -i into a fresh root failed"; }
    if command -v systemd-sysusers >/dev/null; then
      grep -q '^rangefit:' "$fresh/etc/group" 2>/dev/null ||
        fail "postinst did not create the group rangefit in the fresh root"
    fi
    status=$(dpkg-query --admindir="$fresh/var/lib/dpkg" -W -f='${Status}' rangefit)
    [[ $status == "install ok installed" ]] || fail "dpkg status in the fresh root: $status"
    dpkg-query --admindir="$fresh/var/lib/dpkg" -W -f='${Conffiles}\n' rangefit |
      grep -q "$(confdir_of "$prefix")/rangefitd.toml" || fail "dpkg records no conffile"
    check_root "$fresh" "$prefix" yes
    dpkg --root="$fresh" --log=/dev/null --force-script-chrootless --purge rangefit \
      >>"$work/dpkg.log" 2>&1 || fail "dpkg --purge failed"
    left=$(find "$fresh" -type f ! -path "$fresh/var/lib/dpkg/*" \
      ! -regex "$fresh/etc/\(group\|gshadow\|passwd\|shadow\)-?" ! -path "$fresh/etc/.pwd.lock" | head -n 5)
    [[ -z $left ]] || fail "purge left files: $left"
    echo "   dpkg -i into a fresh root, then --purge: clean"
  else
    fail "cpack made no $deb: $(ls "$work/deb")"
  fi
else
  echo "-- dpkg-deb or dpkg-shlibdeps missing (Debian: dpkg-dev): Debian package not built"
fi

# 3. Prefix /usr, configured only: the generated files and the data, without programs.
if [[ $prefix != /usr ]]; then
  cmake -S "$src" -B "$work/usr-build" -DCMAKE_INSTALL_PREFIX=/usr -DRANGEFIT_BUILD_TESTS=OFF \
    -DRANGEFIT_BUILD_BENCHMARKS=OFF >"$work/usr-configure.log" 2>&1 ||
    { cat "$work/usr-configure.log"; fail "configure with prefix /usr failed"; }
  DESTDIR=$work/usr-root cmake --install "$work/usr-build" --component files >/dev/null
  check_root "$work/usr-root" /usr no
fi

echo "$failures failures"
((failures == 0))
