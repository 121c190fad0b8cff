#!/usr/bin/env bash
# debs.sh: the project's Debian packages (knoblab-hapticd, knoblab-cli,
# knoblab-modbus-sim), built by CMake and CPack in the SDK sysroot, which is
# trixie like the image, so the libraries the packages depend on are the
# image's. The packages are made from the test build (./run build): the image
# carries the very binaries the tests ran, and CI compiles the programs once.
# Prints the directory holding the .debs.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

out=$image_dir/debs
rm -rf "$out"
mkdir -p "$out"
t=$(now)
log "debs: packaging the build in $build_dir"
{ KNOBLAB_BUILD_DIR=$build_dir "$repo/run" build &&
  KNOBLAB_BUILD_DIR=$build_dir "$repo/run" shell bash -c "cd '$build_dir' && cpack -G DEB -B '$out'"
} >"$image_dir/debs.log" 2>&1 ||
  { tail -40 "$image_dir/debs.log" >&2; die "debs: build failed (log: $image_dir/debs.log)"; }
rm -rf "$out/_CPack_Packages"
log "debs: $(cd "$out" && echo *.deb) in $(took "$t")"
echo "$out"
