#!/usr/bin/env bash
# kernel.sh: the CI image's kernel, built from Debian 13's linux-source-6.12
# (PREEMPT_RT is mainline there) on `make tinyconfig` + kernel-config/ci-base.cfg
# (+ ci-modules.cfg) + the fragments the Yocto image uses (rt, loop-core,
# sim-io, display, daq), built in a trixie chroot so the toolchain matches the rootfs.
# Prints the bzImage's path on stdout; everything else goes to stderr.
#
# Cached under $KNOBLAB_CACHE/kernel/<key>/, the key a hash of the kernel
# package's version, the fragments and the recipe below: a second call with
# nothing changed prints the cached bzImage at once.
#
# daq.cfg's Comedi, IIO and counter are modules; they go into modules.tar
# beside the bzImage (usr/lib/modules/…) and from there into the image.
#
#   KNOBLAB_KERNEL_DAQ=0  leave out daq.cfg and ci-modules.cfg (about a tenth
#                         less build time, no modules)
#   KNOBLAB_KERNEL_BASE=defconfig  x86_64_defconfig + kvm_guest.config instead
#                         of tinyconfig + ci-base.cfg (to compare build times)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

base=${KNOBLAB_KERNEL_BASE:-tiny}
kc=$repo/kernel-config
case "$base" in
  tiny) fragments=("$kc/ci-base.cfg") ;;
  defconfig) fragments=() ;;
  *) die "KNOBLAB_KERNEL_BASE is tiny or defconfig, not $base" ;;
esac
daq=${KNOBLAB_KERNEL_DAQ:-1}
[ "$daq" = 1 ] && [ "$base" = tiny ] && fragments+=("$kc/ci-modules.cfg")
fragments+=("$kc/rt.cfg" "$kc/loop-core.cfg" "$kc/sim-io.cfg" "$kc/display.cfg")
targets=bzImage
if [ "$daq" = 1 ]; then fragments+=("$kc/daq.cfg"); targets="bzImage modules"; fi
# Bump when the steps below change what gets built from the same inputs.
recipe="base=$base make=$targets v1"

kroot=$(ensure_chroot kbuild "$repo/scripts/image/kernel-packages.txt")
version=$(chroot "$kroot" dpkg-query -W -f='${Version}' linux-source-6.12)
# Only the settings count: editing a comment rebuilds nothing.
key=$( { echo "linux-source-6.12 $version"; echo "$recipe"
         for f in "${fragments[@]}"; do
           echo "== ${f##*/}"; grep -E '^(CONFIG_|# CONFIG_.* is not set)' "$f" || true
         done; } | sha256sum | cut -c1-16)
out=$cache/kernel/$key
if [ -f "$out/bzImage" ]; then
  log "kernel: cached ($out)"
  echo "$out/bzImage"; exit 0
fi

mkdir -p "$cache/kernel"
exec 8>"$cache/kernel/.lock-$key"
flock 8
if [ ! -f "$out/bzImage" ]; then
  work=$cache/kernel/$key.work
  rm -rf "$work" "$out.partial"
  mkdir -p "$work/fragments" "$out.partial"
  cp "${fragments[@]}" "$work/fragments/"
  src=$work/linux-source-6.12
  kmake="make -C $src -j$(nproc) KBUILD_BUILD_USER=knoblab KBUILD_BUILD_HOST=ci"
  blog=$out.partial/build.log
  t0=$(now)
  log "kernel: linux-source-6.12 $version, fragments: ${fragments[*]##*/} (key $key)"
  in_chroot "$kroot" "$work" -- bash -c "cd '$work' && tar xaf /usr/src/linux-source-6.12.tar.xz" >&2
  log "kernel: source unpacked in $(took "$t0")"

  if [ "$base" = tiny ]; then basecmd="$kmake tinyconfig"
  else basecmd="$kmake x86_64_defconfig && $kmake kvm_guest.config"; fi
  frag_paths=$(for f in "${fragments[@]}"; do printf "'%s' " "$work/fragments/${f##*/}"; done)
  in_chroot "$kroot" "$work" -- bash -c "
    set -e; $basecmd
    cd '$src' && scripts/kconfig/merge_config.sh -m .config $frag_paths
    $kmake olddefconfig" >"$work/config.log" 2>&1 ||
    { tail -30 "$work/config.log" >&2; die "kernel: configuration failed"; }
  cp "$src/.config" "$out.partial/config"
  "$repo/scripts/image/kconfig-audit.sh" "$src/.config" "${fragments[@]}" ||
    die "kernel: options were dropped or changed by olddefconfig (above); fix the fragment or its dependencies"

  t1=$(now)
  log "kernel: building bzImage on $(nproc) cores (log: $blog)"
  # The CPU time too: on a machine shared with other builds the wall time
  # says more about the neighbours than about the kernel.
  in_chroot "$kroot" "$work" -- bash -c "TIMEFORMAT='%U %S'; { time $kmake $targets 2>&1; } 2>'$work/cpu'" \
    >"$blog" 2>&1 || { tail -40 "$blog" >&2; die "kernel: build failed (log: $blog)"; }
  cpu_s=$(awk '{ printf "%d", $1 + $2 }' "$work/cpu")
  cp "$src/arch/x86/boot/bzImage" "$out.partial/bzImage"
  if [ "$daq" = 1 ]; then
    # usr/lib/modules/VERSION: trixie's /lib is a symlink into /usr.
    in_chroot "$kroot" "$work" -- bash -c \
      "$kmake modules_install INSTALL_MOD_PATH='$work/modroot/usr' INSTALL_MOD_STRIP=1" >>"$blog" 2>&1 ||
      { tail -20 "$blog" >&2; die "kernel: modules_install failed (log: $blog)"; }
    tar -C "$work/modroot" -cf "$out.partial/modules.tar" usr
  fi
  printf 'version=%s\nkey=%s\nrecipe=%s\nfragments=%s\nbuild_seconds=%d\ncpu_seconds=%d\ntotal_seconds=%d\ncores=%d\nloadavg=%s\n' \
    "$version" "$key" "$recipe" "${fragments[*]##*/}" $(( $(now) - t1 )) "$cpu_s" $(( $(now) - t0 )) \
    "$(nproc)" "$(cut -d' ' -f1-3 /proc/loadavg)" >"$out.partial/build-info"
  log "kernel: bzImage built in $(took "$t1") ($(took "$t0") with unpacking and configuring);" \
      "$(awk -v s="$cpu_s" -v n="$(nproc)" 'BEGIN { printf "%.1f CPU-minutes, about %.1f minutes on %d idle cores", s / 60, s / 60 / n, n }');" \
      "load average now $(cut -d' ' -f1-3 /proc/loadavg)"
  rm -rf "$work"
  mv "$out.partial" "$out"
fi
echo "$out/bzImage"
