#!/usr/bin/env bash
# hair_cost.sh - what the photoreal hair (huang) costs per light, before and after a change,
# side by side in one run (docs/BENCHMARKS.md, "What hair costs").
#   tools/bench/hair_cost.sh BEFORE_ABRDF AFTER_ABRDF [REPEATS]
# Two scenes, each rendered by both binaries (one thread, 4 spp, runs interleaved, median of
# REPEATS ray-tracing CPU times):
#   - tools/bench/hair_robot.scene (the robot in three hair materials under four lights, 96 x 96):
#     everything shaded is hair;
#   - scenes/mixed.scene (160 x 120) and the same scene without its lock of hair: the lock's
#     CPU is the difference.
# The CPU is divided by the hair's lit (hit, light) pairs, the render's "integration evals"
# counter (on mixed.scene: its difference with and without the lock): nanoseconds per light.
# AFTER_ARGS (environment) adds render options to AFTER's renders, e.g. AFTER_ARGS=--hair-table
# (huang tabulated once per material, docs/MODELS.md, "A tabulated huang"): the table's build
# is part of the scene's preparation, which is not ray tracing, so each binary's preparation
# time (wall, one thread) is printed below the table.
# BEFORE is typically an `abrdf` built from an older commit in a scratch directory:
#   git archive e929a63 | tar -x -C /tmp/before
#   cmake -S /tmp/before -B /tmp/before/b -DCMAKE_BUILD_TYPE=Release -DABRDF_BUILD_TESTS=OFF
#   cmake --build /tmp/before/b --target abrdf_cli        # then /tmp/before/b/bin/abrdf
set -euo pipefail
. "$(dirname "$0")/before_after.sh"
before_after_args 3 "$@"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
robot=$here/hair_robot.scene mixed=$here/../../scenes/mixed.scene
nohair=$out/mixed_nohair.scene # without the lock (its only object of material hair)
grep -v '^capsule  *material=hair ' "$mixed" >"$nohair"
if cmp -s "$mixed" "$nohair"; then
  echo "$0: $mixed has no 'capsule material=hair' line to remove" >&2
  exit 1
fi

read -r -a after_args <<<"${AFTER_ARGS:-}"
run() { # BIN SCENE W H [ARGS...] -> "CPU_SECONDS INTEGRATION_EVALS PREPARE_SECONDS" of one
  # render, or one line naming what failed and exit 1
  local s n p bin=$1 scene=$2 w=$3 h=$4
  shift 4
  stats_render "$bin" "$scene" --width "$w" --height "$h" "$@"
  s=$(sed -n 's/.*: \([0-9.]*\) s wall, \([0-9.]*\) s CPU.*/\2/p' "$out/err")
  n=$(sed -n 's/^ *integration evals *\([0-9]*\).*/\1/p' "$out/stdout" "$out/err" | head -n 1)
  p=$(sed -n 's/.*prepared in \([0-9.]*\) s wall.*/\1/p' "$out/err")
  if [[ -z $s || -z $n || -z $p ]]; then
    echo "$0: $bin render $scene: no CPU time, preparation time or 'integration evals'" \
      "counter in its --stats" >&2
    exit 1
  fi
  echo "$s $n $p"
}

declare -A t n prep
cases=(robot mixed nohair)
for ((i = 0; i < repeats; ++i)); do
  for c in "${cases[@]}"; do
    case $c in
      robot) scene=$robot w=96 h=96 ;;
      mixed) scene=$mixed w=160 h=120 ;;
      nohair) scene=$nohair w=160 h=120 ;;
    esac
    for b in before after; do
      if [[ $b == after ]]; then
        read -r s k p < <(run "$after" "$scene" "$w" "$h" "${after_args[@]}")
      else
        read -r s k p < <(run "$before" "$scene" "$w" "$h")
      fi
      t[$c,$b]+="$s "
      prep[$c,$b]=$p
      n[$c,$b]=$k
    done
  done
done
declare -A m
for c in "${cases[@]}"; do
  for b in before after; do m[$c,$b]=$(echo "${t[$c,$b]}" | median); done
done
for b in before after; do
  if [[ ${n[robot,$b]} != "${n[robot,before]}" || ${n[mixed,$b]} != "${n[mixed,before]}" ||
    ${n[nohair,$b]} != "${n[nohair,before]}" ]]; then
    echo "$0: the two binaries shade different numbers of hair pairs" >&2
    exit 1
  fi
done
echo "| scene | hair lights shaded | before, us per light | after, us per light | before / after |"
echo "|---|---:|---:|---:|---:|"
row() { # NAME PAIRS BEFORE_CPU AFTER_CPU
  awk -v name="$1" -v p="$2" -v b="$3" -v a="$4" 'BEGIN {
    printf "| %s | %d | %.1f | %.1f | %.2f |\n", name, p, 1e6 * b / p, 1e6 * a / p, b / a }'
}
row "hair_robot (96 x 96)" "${n[robot,before]}" "${m[robot,before]}" "${m[robot,after]}"
pairs=$((n[mixed,before] - n[nohair,before]))
row "mixed, the lock (160 x 120)" "$pairs" \
  "$(awk "BEGIN{print ${m[mixed,before]} - ${m[nohair,before]}}")" \
  "$(awk "BEGIN{print ${m[mixed,after]} - ${m[nohair,after]}}")"
echo
echo "median of $repeats runs per cell, interleaved; 1 thread, 4 spp; CPU of ray tracing;" \
  "load average $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
echo "scene preparation (last run, s wall, one thread): hair_robot ${prep[robot,before]} before," \
  "${prep[robot,after]} after; mixed ${prep[mixed,before]} before, ${prep[mixed,after]} after" \
  "${AFTER_ARGS:+(after with $AFTER_ARGS)}"
