#!/usr/bin/env bash
# build.sh: the whole QEMU image into $image_dir (build/image/): the kernel
# (kernel.sh, cached), the project's .debs (debs.sh), the root filesystem
# (rootfs.sh) and the disks (disks.sh), plus the kernel command line. Prints
# the image directory; times each step on stderr.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
here=$repo/scripts/image
t0=$(now)
mkdir -p "$image_dir"

t=$(now)
bz=$("$here/kernel.sh")
cp "$bz" "$image_dir/bzImage"
kernel_s=$(( $(now) - t ))

t=$(now); debs=$("$here/debs.sh"); debs_s=$(( $(now) - t ))
# A kernel with modules (KNOBLAB_KERNEL_DAQ=1) leaves them beside the bzImage.
modules=$(dirname "$bz")/modules.tar
[ -f "$modules" ] || modules=
t=$(now); rootfs=$("$here/rootfs.sh" "$debs" $modules); rootfs_s=$(( $(now) - t ))
t=$(now); "$here/disks.sh" "$rootfs" >/dev/null; disks_s=$(( $(now) - t ))

# The kernel command line: the serial console, the read-only root on the
# first virtio disk (no initramfs), and the loop core's isolation.
echo "console=ttyS0 root=/dev/vda ro rootfstype=ext4 panic=5 loglevel=4 $(cat "$repo/kernel-config/cmdline.txt")" \
  >"$image_dir/cmdline"
cat >"$image_dir/build-times.json" <<JSON
{"kernel_s": $kernel_s, "debs_s": $debs_s, "rootfs_s": $rootfs_s, "disks_s": $disks_s, "total_s": $(( $(now) - t0 )),
 "kernel_build_info": "$(dirname "$bz")/build-info"}
JSON
log "image built in $(took "$t0") (kernel ${kernel_s}s, debs ${debs_s}s, rootfs ${rootfs_s}s, disks ${disks_s}s)"
echo "$image_dir"
