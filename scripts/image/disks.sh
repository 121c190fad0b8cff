#!/usr/bin/env bash
# disks.sh ROOTFS_DIR: the image's two raw disks in $image_dir: root.img, an
# ext4 filesystem made from the rootfs directory by mke2fs -d (no loop
# device, no mount), mounted read-only as /dev/vda; and store.img, an empty
# ext4 filesystem for the store (/var/lib/knoblab on /dev/vdb), new on each
# build. Prints the directory.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
[ $# -eq 1 ] || die "usage: disks.sh ROOTFS_DIR"
root=$1
need_host_tool mke2fs e2fsprogs
t=$(now)
# The root filesystem's contents plus a quarter, and room for its metadata.
mb=$(( $(du -sm "$root" | cut -f1) * 5 / 4 + 64 ))
rm -f "$image_dir/root.img" "$image_dir/store.img"
mke2fs -q -t ext4 -L knoblab-root -d "$root" "$image_dir/root.img" "${mb}M" >&2
mke2fs -q -t ext4 -L knoblab-store "$image_dir/store.img" 256M >&2
log "disks: root.img ${mb} MiB, store.img 256 MiB in $(took "$t")"
echo "$image_dir"
