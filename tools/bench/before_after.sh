# before_after.sh - sourced by the benchmarks that run two builds of `abrdf` side by side
# (selection_render.sh, hair_cost.sh, hair_table_build.sh): checks "BEFORE_ABRDF AFTER_ABRDF
# [REPEATS]" and sets before, after, repeats (default $1 of before_after_args) and here (the
# caller's folder); `median` prints the median of the numbers on its input (blank- or
# line-separated; of an even count, the mean of the two middle ones).
#   . "$(dirname "$0")/before_after.sh"; before_after_args DEFAULT_REPEATS "$@"
# stats_render BIN SCENE [ARGS...]: one render of SCENE by BIN with --stats, one thread, no
# preview, in the caller's scratch folder $out: its stdout in $out/stdout and its --stats in
# $out/err; or one line naming what failed and exit 1.
stats_render() {
  local bin=$1 scene=$2
  shift 2
  if ! "$bin" render "$scene" -o "$out/r.exr" --no-preview --stats --threads 1 "$@" \
    >"$out/stdout" 2>"$out/err"; then
    echo "$0: $bin render $scene $* failed: $(tail -n 1 "$out/err")" >&2
    exit 1
  fi
}
median() {
  tr ' ' '\n' | sed '/^$/d' | sort -g |
    awk '{v[NR] = $1} END {print NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'
}
before_after_args() {
  local default=$1
  shift
  if (($# < 2)); then
    echo "usage: $0 BEFORE_ABRDF AFTER_ABRDF [REPEATS]" >&2
    exit 2
  fi
  before=$1 after=$2 repeats=${3:-$default}
  local b
  for b in "$before" "$after"; do
    [[ -x $b ]] || { echo "$0: $b: not an executable" >&2; exit 2; }
  done
  if ! [[ $repeats =~ ^[1-9][0-9]*$ ]]; then
    echo "$0: REPEATS must be a positive whole number, not '$repeats'" >&2
    exit 2
  fi
  here=$(cd "$(dirname "$0")" && pwd)
}
