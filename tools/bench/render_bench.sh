#!/usr/bin/env bash
# render_bench.sh - built-in renderer timings as side-by-side ratios in one run.
#   tools/bench/render_bench.sh [BUILD_DIR] [REPEATS]
# Renders scenes/robot.scene at 512x512, 4 spp: 1 vs 2 threads, and the effect plan vs
# --full (every effect everywhere). Reports the best of REPEATS runs of the ray tracing
# alone (file writing excluded): wall time, and CPU time summed over threads (robust when
# other jobs share the machine).
set -euo pipefail
build=${1:-build}
repeats=${2:-5}
abrdf="$build/bin/abrdf"
scene="$(dirname "$0")/../../scenes/robot.scene"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

best() { # "WALL CPU": the best of each over REPEATS runs of abrdf render robot ARGS...
  for ((i = 0; i < repeats; ++i)); do
    "$abrdf" render "$scene" -o "$out/r.exr" --no-preview --stats "$@" 2>&1 >/dev/null |
      sed -n 's/.*: \([0-9.]*\) s wall, \([0-9.]*\) s CPU.*/\1 \2/p'
  done | sort -g -k1,1 | awk 'NR == 1 {w = $1} {c = (NR == 1 || $2 < c) ? $2 : c} END {print w, c}'
}

read -r w1 c1 <<<"$(best --threads 1)"
read -r w2 c2 <<<"$(best --threads 2)"
read -r wf cf <<<"$(best --threads 2 --full)"
echo "robot 512x512 4 spp, best of $repeats (wall s / CPU s):"
echo "  1 thread          $w1 / $c1"
echo "  2 threads         $w2 / $c2   wall speed-up x$(awk "BEGIN{printf \"%.2f\", $w1/$w2}")"
echo "  2 threads --full  $wf / $cf   plan saves x$(awk "BEGIN{printf \"%.2f\", $cf/$c2}") CPU"
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
echo "command: $0 $build $repeats"
