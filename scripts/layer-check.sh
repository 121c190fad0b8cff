#!/usr/bin/env bash
# ./run layer-check: checks the Yocto layer meta-haptics and the kas files
# without building anything (no source is fetched; BB_NO_NETWORK).
#
#   kernel-config  every fragment line well formed, no option set two ways,
#                  option names checked against a kernel source's Kconfig
#                  when there is one (KNOBLAB_KERNEL_SRC: a tree or tarball;
#                  else Debian's linux-source in /usr/src, if installed)
#   kas-schema     kas/*.yml against kas's JSON schema
#   oelint         oelint-adv on every recipe, append and class
#   graph-MACHINE  bitbake -g haptics-image per kas configuration: every
#                  dependency resolves and the task graph is written; with
#                  meta-qt6 (the kas files have it) knoblab builds against
#                  qtdeclarative and the image installs knoblab-ui
#   graph-qemux86-64-no-qt6
#                  the same for kas/qemux86-64.yml without meta-qt6 (and
#                  meta-python): no Qt in the graph, no kiosk in the image
#   check-layer    yocto-check-layer on meta-haptics
#   graph-wrynose  (only when named in KNOBLAB_LAYER_CHECK_STEPS) bitbake -g
#                  haptics-image for qemux86-64 on Yocto 6.0 wrynose, from
#                  KNOBLAB_LAYERS_WRYNOSE (openembedded-core, meta-openembedded
#                  at wrynose, bitbake at 2.18)
#
# The upstream layers come from KNOBLAB_LAYERS (default
# /var/cache/knoblab/layers: poky, meta-openembedded, meta-qt6,
# meta-raspberrypi, checked out at the kas files' commits). Build directories
# go to KNOBLAB_YOCTO_BUILD (default /var/cache/knoblab/yocto-build); kas,
# oelint-adv and jsonschema to a venv in KNOBLAB_YOCTO_TOOLS. Needs root: it
# installs missing host tools, generates en_US.UTF-8 and creates the
# unprivileged user knoblab-bb, as which bitbake runs (bitbake refuses root).
# KNOBLAB_LAYER_CHECK_STEPS limits it to some steps (space-separated names).
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
layers=${KNOBLAB_LAYERS:-/var/cache/knoblab/layers}
work=${KNOBLAB_YOCTO_BUILD:-/var/cache/knoblab/yocto-build}
tools=${KNOBLAB_YOCTO_TOOLS:-/var/cache/knoblab/yocto-tools}
steps=${KNOBLAB_LAYER_CHECK_STEPS:-kernel-config kas-schema oelint graph-qemux86-64 graph-raspberrypi5 graph-qemux86-64-xenomai graph-qemux86-64-no-qt6 check-layer}
bb_user=knoblab-bb
venv=$tools/venv
# Versions this check was written against; a new one is a deliberate change.
py_tools="kas==5.5 oelint-adv==9.11.2 jsonschema==4.26.0"

die() { echo "layer-check: $*" >&2; exit 1; }
log() { echo "layer-check: $*" >&2; }

[ "$(id -u)" = 0 ] || die "needs root (host packages, the $bb_user user)"
for l in poky meta-openembedded meta-qt6 meta-raspberrypi; do
  [ -d "$layers/$l" ] || die "no $layers/$l (KNOBLAB_LAYERS names the upstream checkouts)"
done

# --- host setup (idempotent) -------------------------------------------------

# bitbake's HOSTTOOLS and sanity checks, and what the steps below run.
host_tools=(chrpath:chrpath diffstat:diffstat gawk:gawk cpio:cpio makeinfo:texinfo
  file:file lz4c:lz4 pzstd:zstd zstd:zstd rpcgen:rpcsvc-proto wget:wget git:git
  gcc:gcc g++:g++ make:make patch:patch perl:perl python3:python3 bzip2:bzip2
  xz:xz-utils unzip:unzip socat:socat locale-gen:locales runuser:util-linux)
setup_host() {
  local missing=() t
  for t in "${host_tools[@]}"; do
    command -v "${t%%:*}" >/dev/null || missing+=("${t#*:}")
  done
  python3 -c 'import ensurepip' 2>/dev/null || missing+=(python3-venv)
  if [ ${#missing[@]} -gt 0 ]; then
    log "installing ${missing[*]}"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null
  fi
  if ! locale -a 2>/dev/null | grep -qix 'en_US.utf8'; then
    log "generating the en_US.UTF-8 locale"
    sed -i 's/^# *\(en_US.UTF-8 UTF-8\)/\1/' /etc/locale.gen
    grep -q '^en_US.UTF-8 UTF-8' /etc/locale.gen || echo 'en_US.UTF-8 UTF-8' >> /etc/locale.gen
    locale-gen >/dev/null
  fi
  id "$bb_user" >/dev/null 2>&1 ||
    useradd --system --create-home --home-dir "$work/home" --shell /bin/bash "$bb_user"
  mkdir -p "$work"
  chown "$bb_user:" "$work"
  if ! "$venv/bin/python" -c 'import kas, oelint_adv, jsonschema' 2>/dev/null; then
    log "installing $py_tools into $venv"
    python3 -m venv "$venv"
    "$venv/bin/pip" install -q $py_tools
  fi
}

# Runs a shell command as the unprivileged user, in a clean environment.
as_bb() {
  runuser -u "$bb_user" -- env -i HOME="$work/home" LANG=en_US.UTF-8 LC_ALL=en_US.UTF-8 \
    PATH=/usr/local/bin:/usr/bin:/bin:/usr/sbin:/sbin TERM=dumb bash -c "$1"
}

# --- steps --------------------------------------------------------------------

step_kernel_config() {
  local src=${KNOBLAB_KERNEL_SRC:-} own
  [ -n "$src" ] || src=$(ls -d /usr/src/linux-source-*.tar.* 2>/dev/null | sort -V | tail -1) || true
  mapfile -t own < <(find "$repo/meta-haptics" -path '*/recipes-kernel/*' -name '*.cfg' | sort)
  python3 "$repo/scripts/kernel-config-audit.py" ${src:+--kernel-src "$src"} \
    --format-only "${own[@]}" -- "$repo/kernel-config"
}

step_kas_schema() {
  "$venv/bin/python" - "$repo"/kas/*.yml <<'EOF'
import json, sys, pathlib, yaml, jsonschema, kas
schema = json.loads((pathlib.Path(kas.__file__).parent / 'schema-kas.json').read_text())
bad = 0
for path in sys.argv[1:]:
    try:
        jsonschema.validate(yaml.safe_load(open(path)), schema)
        print(f'{path}: valid')
    except jsonschema.ValidationError as e:
        bad += 1
        print(f'{path}: {e.message} at {"/".join(map(str, e.absolute_path))}')
sys.exit(1 if bad else 0)
EOF
}

step_oelint() {
  local files
  mapfile -t files < <(cd "$repo/meta-haptics" && find . -name '*.bb' -o -name '*.bbappend' -o -name '*.bbclass' | sort)
  # .oelint.cfg in meta-haptics/ holds the settings; inline suppressions say why.
  (cd "$repo/meta-haptics" && "$venv/bin/oelint-adv" --release scarthgap --quiet "${files[@]}")
}

# A build directory from a kas configuration (written by kas as root: the
# checkout belongs to root), less the layers named after it (paths under the
# layers directory), then `bitbake -g` in it as the unprivileged user.
graph() {
  local name=$1 config=$2 build=$work/$1 l
  shift 2
  mkdir -p "$work/kas"
  ln -sfn "$layers" "$work/kas/layers"
  (cd "$repo" && KAS_WORK_DIR=$work/kas KAS_BUILD_DIR=$build \
     "$venv/bin/kas" checkout --skip repos_checkout "$config" 2>&1 | grep -v ' - INFO ' || true)
  [ -f "$build/conf/local.conf" ] || { echo "kas wrote no configuration for $config"; return 1; }
  for l in "$@"; do
    sed -i "\#/kas/layers/$l \\\\\$#d" "$build/conf/bblayers.conf"
    ! grep -q "/kas/layers/$l[ \"]" "$build/conf/bblayers.conf" || {
      echo "could not leave $l out of $build/conf/bblayers.conf"; return 1; }
  done
  # Parsing only: nothing is fetched. externalsrc hashes the whole source
  # tree when it cannot use git (the checkout is root's, not the bitbake
  # user's), build/ and its image rootfs included: parse a copy of the tracked
  # files instead.
  printf 'BB_NO_NETWORK = "1"\nCONNECTIVITY_CHECK_URIS = ""\nKNOBLAB_CHECKOUT = "%s"\n' \
    "$(tracked_tree)" > "$build/conf/site.conf"
  task_graph "$build" ". '$layers/poky/oe-init-build-env' . >/dev/null"
}

# The checkout's tracked files (as they are in the working tree) copied to
# $work/src, made once per run; prints the directory.
tracked_tree() {
  local src=$work/src
  if [ ! -f "$src/.made-$$" ]; then
    rm -rf "$src" && mkdir -p "$src"
    (cd "$repo" && git ls-files -z | tar --null --ignore-failed-read -T - -cf - 2>/dev/null) | tar -xf - -C "$src"
    touch "$src/.made-$$"
  fi
  echo "$src"
}

# `bitbake -g haptics-image` in build directory $1 as the unprivileged user,
# after the shell setup $2 (what puts bitbake on the PATH); the task graph must
# be written.
task_graph() {
  local build=$1 setup=$2
  chown -R "$bb_user:" "$build"
  as_bb "cd '$build' && $setup &&
         rm -f task-depends.dot pn-buildlist && bitbake -g haptics-image" > "$build/graph.log" 2>&1 || {
    tail -40 "$build/graph.log"; return 1; }
  grep -E '^(Parsing of|NOTE: Resolving|WARNING|ERROR)' "$build/graph.log" | head -20 || true
  [ -s "$build/task-depends.dot" ] || { echo "no task graph written"; return 1; }
  echo "$(wc -l < "$build/pn-buildlist") recipes in haptics-image's graph ($build/task-depends.dot)"
  kiosk_check "$build" "$setup"
}

# knoblab-ui (meta-haptics' dynamic-layers/qt6-layer) is in the image exactly
# when meta-qt6 is in build directory $1's layers: knoblab's build depends on
# qtdeclarative (and its host tools), haptics-image installs the kiosk's
# package and the graph has what that package needs at run time; without
# meta-qt6 none of it. $2 as for task_graph.
kiosk_check() {
  local build=$1 setup=$2 install qt bad=0 edge pn
  install=$(as_bb "cd '$build' && $setup && bitbake-getvar -r haptics-image --value IMAGE_INSTALL 2>getvar.log") || {
    tail -20 "$build/getvar.log"; return 1; }
  install=" $(tr -s ' \n\t' ' ' <<<"$install") "
  qt=$(grep '^qt' "$build/pn-buildlist" | sort | tr '\n' ' ')
  if grep -q '/meta-qt6[ "]' "$build/conf/bblayers.conf"; then
    for edge in '"knoblab.do_prepare_recipe_sysroot" -> "qtdeclarative.do_populate_sysroot"' \
                '"knoblab.do_prepare_recipe_sysroot" -> "qtdeclarative-native.do_populate_sysroot"' \
                '"knoblab.do_prepare_recipe_sysroot" -> "qtvirtualkeyboard.do_populate_sysroot"'; do
      grep -qF "$edge" "$build/task-depends.dot" || { echo "not in the graph: $edge"; bad=1; }
    done
    for pn in qtbase qtdeclarative qtsvg qtvirtualkeyboard ttf-dejavu; do
      grep -qx "$pn" "$build/pn-buildlist" || { echo "not in the graph: $pn"; bad=1; }
    done
    [[ $install == *" knoblab-ui "* ]] || { echo "haptics-image does not install knoblab-ui:$install"; bad=1; }
    [ $bad = 1 ] || echo "with meta-qt6: haptics-image installs knoblab-ui; in the graph: $qt"
  else
    [ -z "$qt" ] || { echo "without meta-qt6, yet in the graph: $qt"; bad=1; }
    ! grep -qx ttf-dejavu "$build/pn-buildlist" || { echo "without meta-qt6, yet ttf-dejavu in the graph"; bad=1; }
    [[ $install != *" knoblab-ui "* ]] || { echo "without meta-qt6, yet haptics-image installs knoblab-ui"; bad=1; }
    [ $bad = 1 ] || echo "without meta-qt6: no Qt recipe in the graph, no knoblab-ui in the image"
  fi
  return $bad
}

# The wrynose compatibility LAYERSERIES_COMPAT declares: no kas file pins
# wrynose, so the configuration is written here.
step_graph_wrynose() {
  local up=${KNOBLAB_LAYERS_WRYNOSE:-/var/cache/knoblab/layers-wrynose} build=$work/graph-wrynose l
  for l in openembedded-core bitbake meta-openembedded; do
    [ -d "$up/$l" ] || { echo "no $up/$l (KNOBLAB_LAYERS_WRYNOSE)"; return 1; }
  done
  mkdir -p "$build/conf"
  printf 'BBPATH = "${TOPDIR}"\nBBFILES ?= ""\nBBLAYERS = "%s %s %s"\n' "$up/openembedded-core/meta" \
    "$up/meta-openembedded/meta-oe" "$repo/meta-haptics" > "$build/conf/bblayers.conf"
  printf 'MACHINE = "qemux86-64"\nDISTRO = "knoblab"\nBB_NO_NETWORK = "1"\nCONNECTIVITY_CHECK_URIS = ""\n' \
    > "$build/conf/local.conf"
  task_graph "$build" "export PATH='$up/bitbake/bin':\$PATH BBPATH='$build'"
}

step_check_layer() {
  local build=$work/check-layer
  mkdir -p "$build/conf"
  printf 'BB_NO_NETWORK = "1"\nCONNECTIVITY_CHECK_URIS = ""\n' > "$build/conf/site.conf"
  chown -R "$bb_user:" "$build"
  as_bb "cd '$build' && . '$layers/poky/oe-init-build-env' . >/dev/null &&
         yocto-check-layer --no-auto-dependency --machines qemux86-64 \
           --dependency '$layers/meta-openembedded/meta-oe' \
           -o '$build/check-layer.log' -- '$repo/meta-haptics'" > "$build/output.log" 2>&1
  local rc=$?
  grep -E 'INFO: (test_|Ran|OK|FAILED)|^FAIL|^ERROR|INFO: meta-haptics' "$build/output.log" | tail -40
  [ $rc = 0 ] || tail -60 "$build/output.log"
  return $rc
}

# --- main ---------------------------------------------------------------------

t0=$SECONDS
setup_host
log "host setup: $((SECONDS - t0)) s"
runuser -u "$bb_user" -- test -r "$repo/meta-haptics/conf/layer.conf" ||
  die "$bb_user cannot read $repo (bitbake parses the layer as that user): make its directories world-readable"

failed=()
for s in $steps; do
  case $s in
    kernel-config) fn=step_kernel_config ;;
    kas-schema) fn=step_kas_schema ;;
    oelint) fn=step_oelint ;;
    graph-qemux86-64) fn="graph $s kas/qemux86-64.yml" ;;
    graph-raspberrypi5) fn="graph $s kas/raspberrypi5.yml" ;;
    graph-qemux86-64-xenomai) fn="graph $s kas/qemux86-64.yml:kas/xenomai.yml" ;;
    graph-qemux86-64-no-qt6) fn="graph $s kas/qemux86-64.yml meta-qt6 meta-openembedded/meta-python" ;;
    check-layer) fn=step_check_layer ;;
    graph-wrynose) fn=step_graph_wrynose ;;
    *) die "unknown step $s" ;;
  esac
  log "$s ..."
  t=$SECONDS
  if $fn; then log "$s: passed in $((SECONDS - t)) s"
  else failed+=("$s"); log "$s: FAILED after $((SECONDS - t)) s"; fi
done

log "total $((SECONDS - t0)) s"
[ ${#failed[@]} = 0 ] || die "failed: ${failed[*]}"
log "all steps passed"
