#!/usr/bin/env bash
# selection_render.sh - what a renderer pays for the selection's goal, before and after a change,
# side by side in one run (docs/BENCHMARKS.md, "What a renderer pays").
#   tools/bench/selection_render.sh BEFORE_ABRDF AFTER_ABRDF [REPEATS]
# Renders scenes/robot16.scene (the robot under 16 lights: shadow rays dominate) and
# tools/bench/sphere16.scene (one sphere under 16 lights, no shadow rays: shading dominates)
# with --adaptive --goal performance and --goal photoreal, one thread, 512 x 512, 4 spp, with
# each binary; the runs of every (scene, goal, binary) are interleaved, and each cell is the
# median of REPEATS ray-tracing CPU times (file writing excluded). BEFORE is typically an
# `abrdf` built from an older commit in a scratch directory:
#   git archive e929a63 | tar -x -C /tmp/before
#   cmake -S /tmp/before -B /tmp/before/b -DCMAKE_BUILD_TYPE=Release -DABRDF_BUILD_TESTS=OFF
#   cmake --build /tmp/before/b --target abrdf_cli        # then /tmp/before/b/bin/abrdf
set -euo pipefail
. "$(dirname "$0")/before_after.sh"
before_after_args 5 "$@"
scenes=("$here/../../scenes/robot16.scene" "$here/sphere16.scene")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

cpu() { # BIN SCENE GOAL -> ray-tracing CPU seconds of one render (the scene's resolution,
  # the default 4 spp), or one line naming what failed and exit 1
  local s
  stats_render "$1" "$2" --adaptive --goal "$3"
  s=$(sed -n 's/.*: \([0-9.]*\) s wall, \([0-9.]*\) s CPU.*/\2/p' "$out/err")
  if [[ -z $s ]]; then
    echo "$0: $1 render $2: no 'N s wall, N s CPU' line in its --stats" >&2
    exit 1
  fi
  echo "$s"
}

declare -A t
for ((i = 0; i < repeats; ++i)); do
  for s in "${scenes[@]}"; do
    for g in performance photoreal; do
      for b in before after; do
        bin=$before
        [[ $b == after ]] && bin=$after
        t[$s,$g,$b]+="$(cpu "$bin" "$s" "$g") "
      done
    done
  done
done

echo "| scene | goal | before, CPU s | after, CPU s | after / before |"
echo "|---|---|---:|---:|---:|"
declare -A m
for s in "${scenes[@]}"; do
  for g in performance photoreal; do
    for b in before after; do m[$s,$g,$b]=$(echo "${t[$s,$g,$b]}" | median); done
    printf '| %s | %s | %.3f | %.3f | %.2f |\n' "$(basename "$s" .scene)" "$g" \
      "${m[$s,$g,before]}" "${m[$s,$g,after]}" "$(awk "BEGIN{print ${m[$s,$g,after]}/${m[$s,$g,before]}}")"
  done
done
echo
echo "| scene | performance / photoreal, before | after |"
echo "|---|---:|---:|"
for s in "${scenes[@]}"; do
  printf '| %s | %.2f | %.2f |\n' "$(basename "$s" .scene)" \
    "$(awk "BEGIN{print ${m[$s,performance,before]}/${m[$s,photoreal,before]}}")" \
    "$(awk "BEGIN{print ${m[$s,performance,after]}/${m[$s,photoreal,after]}}")"
done
echo
echo "median of $repeats runs per cell, interleaved; 1 thread, 512 x 512, 4 spp;" \
  "load average $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
