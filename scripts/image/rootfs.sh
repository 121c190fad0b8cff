#!/usr/bin/env bash
# rootfs.sh DEBS_DIR [MODULES_TAR]: the QEMU image's root filesystem as a directory: Debian
# 13 by mmdebstrap with systemd as init, images/qemu/packages.txt, the
# project's .debs (apt brings their library dependencies), and the files in
# images/qemu/rootfs/ (hapticd's config, the gpio-sim, Modbus-simulator and
# ready units, fstab). The read-only root must already hold every mount
# point (the store's /var/lib/knoblab) and an empty machine-id (systemd then
# makes one up at each boot); root has no password, for the serial console's
# emergency shell: a development and CI image. The kernel has no virtual
# terminals and the guest no network, so their gettys and apt's timers are
# masked, and so is e2scrub (nothing to scrub on a read-only root). Prints
# the directory.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
[ $# -ge 1 ] && [ $# -le 2 ] || die "usage: rootfs.sh DEBS_DIR [MODULES_TAR]"
# Absolute paths: mmdebstrap takes only those (or ./…) for .deb files.
debs=$(cd "$1" && pwd)
modules=${2:+$(realpath "$2")}
img=$repo/images/qemu
root=$image_dir/rootfs

includes=(--include="$(list_packages "$img/packages.txt" | paste -sd,)")
for d in "$debs"/*.deb; do includes+=(--include="$d"); done
hooks=()
# The kernel's modules, when it has any (KNOBLAB_KERNEL_DAQ=1).
[ -n "$modules" ] && hooks+=(--customize-hook="tar -C \"\$1\" -xf '$modules'")
[ ${#includes[@]} -gt 1 ] || die "rootfs: no .deb in $debs"

need_host_tool mmdebstrap mmdebstrap
t=$(now)
rm -rf "$root"
log "rootfs: mmdebstrap $suite into $root"
# Documentation and translations are left out: nobody reads them on the
# appliance, and they would make the disk image larger and slower to write.
mmdebstrap --quiet --variant=minbase "${includes[@]}" \
  --hook-dir=/usr/share/mmdebstrap/hooks/file-mirror-automount \
  --dpkgopt='path-exclude=/usr/share/man/*' \
  --dpkgopt='path-exclude=/usr/share/locale/*' \
  --dpkgopt='path-exclude=/usr/share/doc/*' \
  --customize-hook="sync-in '$img/rootfs' /" \
  --customize-hook='chroot "$1" systemd-sysusers' \
  --customize-hook='chroot "$1" systemctl enable knoblab-gpio-sim knoblab-modbus-sim hapticd knoblab-ready knoblab-ui' \
  --customize-hook=': >"$1/etc/machine-id"' \
  --customize-hook='mkdir -p "$1/var/lib/knoblab"' \
  --customize-hook='chroot "$1" systemctl mask getty-static.service getty@tty1.service apt-daily.timer apt-daily-upgrade.timer e2scrub_all.timer e2scrub_reap.service' \
  --customize-hook='chroot "$1" passwd --quiet --delete root' \
  "${hooks[@]}" \
  "$suite" "$root" ${mirror:+"$mirror"} >&2
log "rootfs: $(du -sh "$root" | cut -f1) in $(took "$t")"
echo "$root"
