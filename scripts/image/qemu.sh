#!/usr/bin/env bash
# qemu.sh [QEMU ARGS…]: boots the image in build/image/ (./run image) under
# QEMU's software emulation (no KVM here): two CPUs, since the kernel command
# line isolates CPU 1 for hapticd's loop, the root disk read-only, the store
# disk writable. By default the serial console is this terminal (Ctrl-A X
# quits QEMU; `poweroff` in the guest ends it too); extra arguments go to
# QEMU, e.g. -snapshot to leave the store disk as it was.
#
#   KNOBLAB_QEMU_CONSOLE=unix:PATH  serial console on a unix socket that QEMU
#                                   listens on and waits for (the image test)
#   KNOBLAB_QEMU_STORE=FILE         the store disk, instead of the image's
#                                   store.img (the image test boots a copy)
#   KNOBLAB_QEMU_QMP=unix:PATH      a QMP socket (the image test takes the
#                                   kiosk's screendump through it)
#
# The display is QEMU's standard VGA, where the kiosk draws; with the serial
# console here it is not shown (-display none), only dumped over QMP.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
for f in bzImage cmdline root.img store.img; do
  [ -f "$image_dir/$f" ] || die "qemu: no $image_dir/$f; run ./run image first"
done
need_host_tool qemu-system-x86_64 qemu-system-x86

console=${KNOBLAB_QEMU_CONSOLE:-stdio}
case "$console" in
  stdio) io=(-nographic -vga std) ;;
  unix:*) io=(-display none -vga std -monitor none
              -chardev "socket,id=con,path=${console#unix:},server=on,wait=on"
              -serial chardev:con) ;;
  *) die "qemu: KNOBLAB_QEMU_CONSOLE is stdio or unix:PATH, not $console" ;;
esac
qmp=${KNOBLAB_QEMU_QMP:-}
case "$qmp" in
  "") ;;
  unix:*) io+=(-qmp "$qmp,server=on,wait=off") ;;
  *) die "qemu: KNOBLAB_QEMU_QMP is unix:PATH, not $qmp" ;;
esac

exec qemu-system-x86_64 \
  -machine q35 -accel tcg,thread=multi -cpu max -smp 2 -m 1024 \
  -kernel "$image_dir/bzImage" -append "$(cat "$image_dir/cmdline")" \
  -drive "file=$image_dir/root.img,format=raw,if=virtio,readonly=on" \
  -drive "file=${KNOBLAB_QEMU_STORE:-$image_dir/store.img},format=raw,if=virtio" \
  -device virtio-rng-pci -nic none -no-reboot \
  "${io[@]}" "$@"
