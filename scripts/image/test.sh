#!/usr/bin/env bash
# test.sh: boots the image in build/image/ headless and checks the appliance
# (image_test.py says what); writes build/image/report.json and the serial
# console's log beside it. Builds the image first if there is none.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
[ -f "$image_dir/root.img" ] || "$repo/scripts/image/build.sh" >/dev/null
need_host_tool qemu-system-x86_64 qemu-system-x86
need_host_tool python3 python3
exec python3 "$repo/scripts/image/image_test.py" --image-dir "$image_dir" \
  --qemu "$repo/scripts/image/qemu.sh" "$@"
