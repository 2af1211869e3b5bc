#!/usr/bin/env bash
# renderers.sh - the built-in ray tracer against POV-Ray 3.7 and Blender Cycles on the same
# images (docs/BENCHMARKS.md, "Renderer speed").
#   tools/bench/renderers.sh [BUILD_DIR] [REPEATS]
# For scenes/sphere.scene and scenes/robot.scene at their own resolution, 1 sample per
# pixel, 2 threads, every material Lambert + Blinn-Phong (n = 100):
#   abrdf    `abrdf render --model blinn_phong --spp 1 --threads 2 --stats`: the renderer's
#            own timer of the ray tracing (wall and CPU over threads), and the process wall
#            time (start-up and EXR writing included)
#   povray   the same scene from `abrdf export --pov --native` (POV-Ray's own `specular`
#            finish, its lights and shadows), -A (one ray per pixel), +WT2: POV-Ray's own
#            "Trace Time" (wall), its CPU time (user + sys of the run minus that of a 1x1
#            run of the same file: parsing and start-up removed), and the process wall time
#   cycles   tools/bench/cycles_scene.py in .venv (bpy; scripts/setup_bench.sh): Principled BSDF,
#            1 sample, CPU, 2 threads, no bounces: the wall time of bpy.ops.render.render
#            (sync + BVH + tracing); skipped if .venv has no bpy
# Each figure is the best of REPEATS runs (other jobs on a shared machine only ever add
# time). Ratios are printed; absolute times only as the inputs of the ratios.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
build=${1:-build}
repeats=${2:-5}
abrdf="$build/bin/abrdf"
py="$root/.venv/bin/python"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

min() { sort -g | head -n1; }
now() { date +%s.%N; }

for name in sphere robot; do
  scene="$root/scenes/$name.scene"
  res=$(sed -n 's/^camera .*resolution=\([0-9]*\),\([0-9]*\).*/\1 \2/p' "$scene")
  read -r w h <<<"$res"
  # abrdf: in-process ray tracing time (wall, CPU) and process wall time
  : >"$out/a"
  for ((i = 0; i < repeats; ++i)); do
    t0=$(now)
    line=$("$abrdf" render "$scene" -o "$out/a.exr" --model blinn_phong --set n=100 --spp 1 \
      --threads 2 --stats --no-preview 2>&1 >/dev/null | sed -n 's/.*: \([0-9.]*\) s wall, \([0-9.]*\) s CPU.*/\1 \2/p')
    echo "$line $(awk "BEGIN{print $(now) - $t0}")" >>"$out/a"
  done
  a_wall=$(cut -d' ' -f1 "$out/a" | min)
  a_cpu=$(cut -d' ' -f2 "$out/a" | min)
  a_proc=$(cut -d' ' -f3 "$out/a" | min)
  # POV-Ray: native finish, 1 ray per pixel, 2 threads
  "$abrdf" export --pov "$scene" -o "$out/$name.pov" --model blinn_phong --set n=100 --native
  : >"$out/p"
  : >"$out/p1"
  pov() { # W H: "TRACE_WALL PROCESS_WALL PROCESS_CPU" of one povray run
    local t0 trace cpu
    t0=$(now)
    trace=$(cd "$out" && /usr/bin/time -f "cpu %U %S" povray +I"$name.pov" +O"$name.png" +W"$1" +H"$2" \
      -D -A +WT2 +L"$root/povray_macros" 2>&1 | sed -n -e 's/.*Trace Time:.*(\([0-9.]*\) seconds).*/\1/p' \
      -e 's/^cpu \([0-9.]*\) \([0-9.]*\)$/cpu \1 \2/p' | tr '\n' ' ')
    echo "$trace $(awk "BEGIN{print $(now) - $t0}")" |
      awk '{print $1, $5, $3 + $4}'
  }
  for ((i = 0; i < repeats; ++i)); do
    pov "$w" "$h" >>"$out/p"
    pov 1 1 >>"$out/p1" # parsing and start-up only: subtracted from the CPU time
  done
  p_trace=$(cut -d' ' -f1 "$out/p" | min)
  p_proc=$(cut -d' ' -f2 "$out/p" | min)
  p_cpu=$(awk -v a="$(cut -d' ' -f3 "$out/p" | min)" -v b="$(cut -d' ' -f3 "$out/p1" | min)" 'BEGIN{print a - b}')
  # Cycles
  c_render=NA
  c_proc=NA
  if [ -x "$py" ] && "$py" -c 'import bpy' 2>/dev/null; then
    t0=$(now)
    c_render=$("$py" "$here/cycles_scene.py" "$scene" --samples 1 --threads 2 --reps "$repeats" 2>/dev/null |
      sed -n 's/^cycles_render_seconds //p' | min)
    c_proc=$(awk "BEGIN{print $(now) - $t0}")
  fi
  echo "$name ${w}x${h}, 1 spp, 2 threads, best of $repeats:"
  awk -v aw="$a_wall" -v ac="$a_cpu" -v ap="$a_proc" -v pt="$p_trace" -v pp="$p_proc" -v pc="$p_cpu" \
      -v cr="$c_render" -v cp="$c_proc" 'BEGIN {
    printf "  abrdf ray tracing (renderer timer)      wall %.4f s, CPU %.4f s; process %.3f s\n", aw, ac, ap
    printf "  POV-Ray trace time / abrdf ray tracing  x%.1f wall, x%.1f CPU   (process wall: x%.1f)\n", pt / aw, pc / ac, pp / ap
    if (cr != "NA")
      printf "  Cycles render / abrdf ray tracing       x%.1f   (Cycles render / POV-Ray trace: x%.2f)\n", cr / aw, cr / pt
    else
      printf "  Cycles: not measured (no bpy in .venv; scripts/setup_bench.sh)\n"
  }'
done
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
echo "command: $0 $build $repeats"
