# Shared by the image scripts (sourced, not run): paths, logging, timing, and
# trixie chroots made with mmdebstrap and cached by the hash of their package
# list, the way ./run caches the SDK.
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
suite=trixie
# The Debian mirror: mmdebstrap's own default unless KNOBLAB_MIRROR names one.
mirror=${KNOBLAB_MIRROR:-}
cache=${KNOBLAB_CACHE:-/var/cache/knoblab}
build_dir=${KNOBLAB_BUILD_DIR:-$repo/build}
image_dir=${KNOBLAB_IMAGE_DIR:-$build_dir/image}

log() { echo "image: $*" >&2; }
die() { log "$*"; exit 1; }

# Seconds since the epoch, and "Nm SSs" for a duration: each step prints how
# long it took, since CI has a time budget for all of it.
now() { date +%s; }
took() { local s=$(( $(now) - $1 )); printf '%dm%02ds' $((s / 60)) $((s % 60)); }

# need_host_tool CMD PACKAGE: install PACKAGE on this (Debian) machine with
# apt-get if CMD is missing, as ./run does for mmdebstrap. QEMU and mke2fs run
# on the host: they only read and write files, so they need not match trixie.
need_host_tool() {
  command -v "$1" >/dev/null && return 0
  [ "$(id -u)" = 0 ] || die "$1 is missing; install $2"
  log "installing $2"
  apt-get update -qq >&2 && apt-get install -y -qq --no-install-recommends "$2" >&2
}

# Package names from a list file: one a line, # comments.
list_packages() { grep -v -e '^#' -e '^[[:space:]]*$' "$1" | sort -u; }

# ensure_chroot NAME LIST: a minbase trixie chroot with LIST's packages,
# built once per list (its hash names it) under the cache; prints its path.
# Concurrent callers wait on the cache's lock.
ensure_chroot() {
  local name=$1 list=$2 hash root
  hash=$( { echo "$suite"; list_packages "$list"; } | sha256sum | cut -c1-12)
  root=$cache/$name-$suite-$hash
  if [ ! -f "$root/.complete" ]; then
    [ "$(id -u)" = 0 ] || die "creating a chroot needs root (chroot, mmdebstrap)"
    need_host_tool mmdebstrap mmdebstrap
    mkdir -p "$cache"
    (
      flock 9
      if [ ! -f "$root/.complete" ]; then
        local t; t=$(now)
        log "creating the $name chroot at $root"
        rm -rf "$root.partial"
        mmdebstrap --quiet --variant=minbase \
          --include="$(list_packages "$list" | paste -sd,)" \
          "$suite" "$root.partial" ${mirror:+"$mirror"} >&2
        touch "$root.partial/.complete"
        mv "$root.partial" "$root"
        log "$name chroot made in $(took "$t")"
      fi
    ) 9>"$cache/.lock"
  fi
  echo "$root"
}

# in_chroot ROOT DIR… -- CMD…: run CMD in ROOT with each DIR bind-mounted at
# its own path (so paths mean the same inside and out), in a private mount
# namespace that vanishes with the command.
in_chroot() {
  local root=$1; shift
  local setup="set -e; mount -t proc proc '$root/proc'; mount --rbind /dev '$root/dev';"
  while [ "$1" != -- ]; do
    setup+=" mkdir -p '$root$1'; mount --bind '$1' '$root$1';"
    shift
  done
  shift
  unshare --mount --propagation private --fork -- bash -c \
    "$setup exec chroot '$root' /usr/bin/env -i HOME=/root LANG=C.UTF-8 \
       PATH=/usr/local/bin:/usr/bin:/bin:/usr/sbin:/sbin \"\$@\"" _ "$@"
}
