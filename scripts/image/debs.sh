#!/usr/bin/env bash
# debs.sh: the project's Debian packages (knoblab-hapticd, knoblab-cli,
# knoblab-modbus-sim), built by CMake and CPack in the SDK sysroot, which is
# trixie like the image, so the libraries the packages depend on are the
# image's. Release build without tests, in its own build dir. Prints the
# directory holding the .debs.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

bdir=$build_dir/deb
out=$image_dir/debs
rm -rf "$out"
mkdir -p "$out"
t=$(now)
log "debs: building in $bdir"
KNOBLAB_BUILD_DIR=$build_dir "$repo/run" shell bash -c "
  set -e
  cmake -S '$repo' -B '$bdir' -G Ninja -DCMAKE_BUILD_TYPE=Release -DKNOBLAB_TESTS=OFF
  cmake --build '$bdir'
  cd '$bdir' && cpack -G DEB -B '$out'" >"$image_dir/debs.log" 2>&1 ||
  { tail -40 "$image_dir/debs.log" >&2; die "debs: build failed (log: $image_dir/debs.log)"; }
rm -rf "$out/_CPack_Packages"
log "debs: $(cd "$out" && echo *.deb) in $(took "$t")"
echo "$out"
