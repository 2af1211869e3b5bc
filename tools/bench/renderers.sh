#!/usr/bin/env bash
# renderers.sh - the built-in ray tracer against POV-Ray 3.7 (and Blender Cycles) on the same
# images, one thread each (docs/BENCHMARKS.md, "Renderer speed").
#   tools/bench/renderers.sh [BUILD_DIR] [REPEATS] [SCENES...]
# SCENES default to sphere and robot (scenes/NAME.scene) at their own resolution; every
# material Lambert + Blinn-Phong (n = 100):
#   abrdf    `abrdf render --model blinn_phong --spp 4 --threads 1 --stats`, once with the
#            default float shading and once with --precision double: the renderer's own
#            CPU time of the ray tracing (parsing, start-up and EXR writing excluded)
#   povray   the same scene exported twice, `abrdf export --pov --native` (POV-Ray's own
#            `specular` finish: its fastest form) and the default export (function pigments
#            evaluating the port's SDL macros, what the port cross-checks), rendered at 2x
#            the resolution without antialiasing (4 rays per pixel, the same footprint as
#            --spp 4), +WT1: its trace CPU time = user + sys of the run minus that of a 1x1
#            run of the same file (parsing and start-up removed)
#   cycles   tools/bench/cycles_scene.py in .venv (bpy): Principled BSDF, 4 samples, CPU,
#            1 thread, no bounces: the wall time of bpy.ops.render.render; skipped without bpy
# Each figure is the best of REPEATS runs (other jobs on a shared machine only ever add
# time). Ratios are printed; absolute times only as the inputs of the ratios.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-build}
repeats=${2:-5}
shift $(($# > 2 ? 2 : $#))
names=("$@")
[ ${#names[@]} -gt 0 ] || names=(sphere robot)
abrdf="$build/bin/abrdf"
py="$root/.venv/bin/python"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

min() { sort -g | head -n1; }

for name in "${names[@]}"; do
  scene="$root/scenes/$name.scene"
  res=$(sed -n 's/^camera .*resolution=\([0-9]*\),\([0-9]*\).*/\1 \2/p' "$scene")
  read -r w h <<<"$res"
  abrdf_cpu() { # PRECISION: the renderer's CPU time of the ray tracing
    "$abrdf" render "$scene" -o "$out/a.exr" --model blinn_phong --set n=100 --spp 4 \
      --threads 1 --precision "$1" --stats --no-preview 2>&1 >/dev/null |
      sed -n 's/.*s wall, \([0-9.]*\) s CPU.*/\1/p'
  }
  pov_cpu() { # FILE W H: user + sys seconds of one povray run, one thread, no antialiasing
    (cd "$out" && /usr/bin/time -f "cpu %U %S" povray +I"$1" +O"$name.png" +W"$2" +H"$3" \
      -D -A +WT1 +L"$root/povray_macros" 2>&1 | sed -n 's/^cpu \([0-9.]*\) \([0-9.]*\)$/\1 \2/p' |
      awk '{print $1 + $2}')
  }
  "$abrdf" export --pov "$scene" -o "$out/native.pov" --model blinn_phong --set n=100 --native
  "$abrdf" export --pov "$scene" -o "$out/function.pov" --model blinn_phong --set n=100
  : >"$out/af" && : >"$out/ad" && : >"$out/pn" && : >"$out/pn1" && : >"$out/pf" && : >"$out/pf1"
  for ((i = 0; i < repeats; ++i)); do # interleaved, so drift of the load affects all alike
    abrdf_cpu float >>"$out/af"
    abrdf_cpu double >>"$out/ad"
    pov_cpu native.pov $((2 * w)) $((2 * h)) >>"$out/pn"
    pov_cpu native.pov 1 1 >>"$out/pn1"
    pov_cpu function.pov $((2 * w)) $((2 * h)) >>"$out/pf"
    pov_cpu function.pov 1 1 >>"$out/pf1"
  done
  af=$(min <"$out/af")
  ad=$(min <"$out/ad")
  pn=$(awk -v a="$(min <"$out/pn")" -v b="$(min <"$out/pn1")" 'BEGIN{print a - b}')
  pf=$(awk -v a="$(min <"$out/pf")" -v b="$(min <"$out/pf1")" 'BEGIN{print a - b}')
  c_render=NA
  if [ -x "$py" ] && "$py" -c 'import bpy' 2>/dev/null; then
    c_render=$("$py" "$here/cycles_scene.py" "$scene" --samples 4 --threads 1 --reps "$repeats" \
      2>/dev/null | sed -n 's/^cycles_render_seconds //p' | min)
  fi
  echo "$name ${w}x${h}, 4 samples per pixel, 1 thread, best of $repeats (trace CPU seconds):"
  awk -v af="$af" -v ad="$ad" -v pn="$pn" -v pf="$pf" -v cr="$c_render" 'BEGIN {
    printf "  abrdf float %.4f s, double %.4f s; POV-Ray --native %.4f s, function pigments %.4f s\n", af, ad, pn, pf
    printf "  POV-Ray --native / abrdf            x%.1f (float)  x%.1f (double)\n", pn / af, pn / ad
    printf "  POV-Ray function pigments / abrdf   x%.1f (float)  x%.1f (double)\n", pf / af, pf / ad
    if (cr != "NA") printf "  Cycles render (wall) / abrdf float  x%.1f\n", cr / af
    else printf "  Cycles: not measured (no bpy in .venv; scripts/setup_bpy.sh)\n"
  }'
done
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
echo "command: $0 $build $repeats ${names[*]}"
