#!/usr/bin/env bash
# hair_table_build.sh - what a huang table costs to build, before and after a change, side by
# side in one run (docs/MODELS.md, "A tabulated huang", "What it costs").
#   tools/bench/hair_table_build.sh BEFORE_ABRDF AFTER_ABRDF [REPEATS]
# Each binary renders scenes/mixed.scene, whose lock of hair is its one huang material, with
# `--hair-table` (the default sizes, 24,9,32,16; SIZES in the environment sets others) on one
# thread at 8 x 6 pixels, so that the scene's preparation, which builds the table, is nearly
# all of the run; the runs alternate, REPEATS (default 3) of each. Prints each binary's median
# preparation time (wall, one thread) and their ratio.
# BEFORE is typically an `abrdf` built from an older commit in a scratch directory:
#   git archive COMMIT | tar -x -C /tmp/before
#   cmake -S /tmp/before -B /tmp/before/b -DCMAKE_BUILD_TYPE=Release -DABRDF_BUILD_TESTS=OFF
#   cmake --build /tmp/before/b --target abrdf_cli        # then /tmp/before/b/bin/abrdf
set -euo pipefail
. "$(dirname "$0")/before_after.sh"
before_after_args 3 "$@"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
scene=$here/../../scenes/mixed.scene
sizes=${SIZES:-24,9,32,16}

prepare() { # BIN -> the preparation's wall seconds of one render, or one line and exit 1
  local p bin=$1
  stats_render "$bin" "$scene" --width 8 --height 6 --hair-table-sizes "$sizes"
  p=$(sed -n 's/.*prepared in \([0-9.]*\) s wall.*/\1/p' "$out/err")
  if [[ -z $p ]]; then
    echo "$0: $bin render $scene: no preparation time in its --stats" >&2
    exit 1
  fi
  echo "$p"
}

t_before="" t_after=""
for ((i = 0; i < repeats; ++i)); do
  t_before+="$(prepare "$before") "
  t_after+="$(prepare "$after") "
done
b=$(echo "$t_before" | median) a=$(echo "$t_after" | median)
echo "| huang table ($sizes), one thread | before, s | after, s | before / after |"
echo "|---|---:|---:|---:|"
awk -v b="$b" -v a="$a" 'BEGIN { printf "| scenes/mixed.scene, the lock | %.1f | %.1f | %.2f |\n", b, a, b / a }'
echo
echo "median of $repeats preparations per binary, interleaved (before: $t_before; after: $t_after);" \
  "load average $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
