#!/usr/bin/env bash
# kconfig-audit.sh CONFIG FRAGMENT…: check that every option the fragments
# ask for is in the final .config with the value asked (what Yocto's kconfig
# audit does after olddefconfig). An option whose dependencies are not met is
# silently dropped or changed by olddefconfig; this names each one and fails.
# A later fragment overrides an earlier one, as when they were merged.
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 CONFIG FRAGMENT..." >&2; exit 2; }
config=$1; shift

awk '
  # Value of a config line: "y", "m", "\"text\"", a number, or "n" (not set).
  function parse(line) {
    if (match(line, /^CONFIG_[A-Za-z0-9_]+=/)) {
      opt = substr(line, 1, RLENGTH - 1); val = substr(line, RLENGTH + 1); return 1
    }
    if (match(line, /^# CONFIG_[A-Za-z0-9_]+ is not set/)) {
      opt = line; sub(/^# /, "", opt); sub(/ is not set.*/, "", opt); val = "n"; return 1
    }
    return 0
  }
  FNR == 1 { file++; name[file] = FILENAME }
  file == 1 { if (parse($0)) have[opt] = val; next }
  parse($0) { if (!(opt in want)) order[++n] = opt; want[opt] = val; f = FILENAME; sub(/.*\//, "", f); from[opt] = f }
  END {
    bad = 0
    for (i = 1; i <= n; i++) {
      o = order[i]; got = (o in have) ? have[o] : "n"
      if (got != want[o]) {
        printf "kconfig audit: %s=%s requested by %s, but the .config has %s\n",
               o, want[o], from[o], (got == "n" ? "it unset" : o "=" got) > "/dev/stderr"
        bad++
      }
    }
    if (bad) { printf "kconfig audit: %d of %d requested options did not survive\n", bad, n > "/dev/stderr"; exit 1 }
    printf "kconfig audit: all %d requested options survived\n", n > "/dev/stderr"
  }
' "$config" "$@"
