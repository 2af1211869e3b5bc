#!/usr/bin/env bash
# scale_bench.sh - how the built-in renderer's cost grows with the scene, and abrdf against
# POV-Ray 3.7 on two large scenes (docs/BENCHMARKS.md, "Geometry at scale").
#   tools/bench/scale_bench.sh [BUILD_DIR] [REPEATS] [PARTS] [BEFORE]
# PARTS (default "spheres teapot povray") chooses what runs:
#   spheres  N = 100, 1000, 10000, 100000 objects: a floor and N - 1 spheres of radius 0.35 at
#            pseudo-random places (a fixed linear congruential sequence) on a floor of side
#            1.25 sqrt(N), so that the density stays the same; one directional light with
#            shadows; the camera frames the floor. 256x256, 1 sample per pixel, 1 thread: the
#            renderer's CPU time of the ray tracing (and shading) divided by the rays it cast
#            (camera + shadow rays, --stats): ns per ray; and the wall time to read the scene
#            and to prepare it (materials, the Embree scene, the effect plan).
#   teapot   gen_teapot at 4, 13, 40 and 128 segments (992, 10 712, 102 080 and 1 047 552
#            triangles) in scenes/teapot.scene's place: 256x192, 1 spp, 1 thread, ns per ray;
#            read and prepare times; the bytes Embree holds per triangle (its memory monitor:
#            vertex copy, BVH) and the bytes of the mesh as read (positions, normals, uv,
#            three index triples per triangle).
#   povray   the 4000-sphere scene and the dense teapot (128 segments), 256x256 with 4
#            samples per pixel, one thread each, every material Lambert + Blinn-Phong n = 100
#            (--model blinn_phong --set n=100, as tools/bench/renderers.sh): abrdf render
#            --spp 4 against povray on `abrdf export --pov --native` (POV-Ray's own finish,
#            light, shadows and bounding hierarchy) at 512x512 without antialiasing (the same
#            4 rays per pixel). CPU seconds: abrdf's own timer of the ray tracing; POV-Ray's
#            process CPU (user + sys) minus that of a 1x1 run of the same file (start-up,
#            parsing and its bounding-hierarchy build removed).
# BEFORE (optional): an `abrdf` binary of the renderer before the BVH (per-pixel lists of the
# objects whose bounding balls project onto the pixel, per-(light, receiver) occluder lists,
# every triangle of a mesh tested in turn), e.g. built from commit 0cae737; its runs are
# interleaved with the new ones and printed beside them, for the sizes it finishes in
# reasonable time (spheres up to 10^4, teapots up to 10^4 triangles).
# Peak memory: the process's maximum resident set (GNU time %M).
# Each figure is the median of REPEATS runs (default 3), the runs of the sizes interleaved
# (a shared machine's load then spreads over all of them). Ratios are printed.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$(dirname "$here")")
build=${1:-build}
repeats=${2:-3}
parts=${3:-spheres teapot povray}
before=${4:-}
abrdf="$build/bin/abrdf"
gen="$build/bin/gen_teapot"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

median() { sort -g | awk '{v[NR] = $1} END {print NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

# spheres N FILE [RES]: a floor and N - 1 spheres, lambert + blinn_phong, one directional light
spheres() {
  awk -v n="$1" -v res="${3:-256}" 'BEGIN {
    side = 1.25 * sqrt(n); h = side / 2; s = 12345
    printf "camera position=0,%.6g,%.6g look_at=0,0,0 fov=40 resolution=%d,%d\n", 0.95 * side, 1.1 * side, res, res
    print "light directional direction=-0.4,0.85,0.35 intensity=2.5"
    print "ambient 0.05"
    print "material ball diffuse=lambert specular=blinn_phong kd=0.6,0.25,0.15 ks=0.3 n=60"
    print "material ground model=lambert kd=0.5"
    printf "box material=ground size=%.6g,0.2,%.6g translate=0,-0.1,0\n", 1.1 * side, 1.1 * side
    for (i = 1; i < n; ++i) {
      s = (s * 1103515245 + 12345) % 2147483648; x = s / 2147483648 * side - h
      s = (s * 1103515245 + 12345) % 2147483648; z = s / 2147483648 * side - h
      printf "sphere material=ball radius=0.35 translate=%.6g,0.35,%.6g\n", x, z
    }
  }' >"$2"
}

# teapot SEGMENTS FILE [W H]: the teapot scene with a generated teapot, lambert + blinn_phong
teapot() {
  [ -f "$out/teapot_$1.obj" ] || "$gen" --segments "$1" -o "$out/teapot_$1.obj" 2>/dev/null
  sed -e "s|file=teapot.obj|file=$out/teapot_$1.obj|" \
      -e "s|resolution=512,384|resolution=${3:-256},${4:-192}|" \
      -e "s|^material glaze .*|material glaze diffuse=lambert specular=blinn_phong kd=0.5,0.09,0.06 ks=0.3 n=60|" \
      "$root/scenes/teapot.scene" >"$2"
}

# run [--before] SCENE ARGS...: "CPU_SECONDS RAYS READ_SECONDS PREPARE_SECONDS EMBREE_BYTES
# PEAK_RSS_KB" of one render (NA where the binary does not print it)
run() {
  local bin=$abrdf
  if [ "$1" = --before ]; then bin=$before && shift; fi
  local scene=$1
  shift
  /usr/bin/time -f "maxrss %M" "$bin" render "$scene" -o "$out/r.exr" --no-preview --stats \
    --threads 1 "$@" 2>&1 | awk '
    BEGIN {rd = pr = b = "NA"}
    /^  primary rays/ {r += $3} /^  shadow rays / {r += $3}
    /s CPU \(ray tracing only\)/ {for (i = 1; i <= NF; ++i) if ($(i) == "CPU") cpu = $(i - 2)}
    /scene read in/ {rd = $6; pr = $10; b = $(NF - 1)}
    /^maxrss/ {rss = $2}
    END {printf "%s %d %s %s %s %s\n", cpu, r, rd, pr, b, rss}'
}
# ns FILE: median ns per ray of the runs in FILE, or "-" if there are none
ns() {
  [ -s "$1" ] || { echo -; return; }
  awk '{print $1 * 1e9 / $2}' "$1" | median | awk '{printf "%.0f", $1}'
}

col() { cut -d' ' -f"$1" "$2" | median; }

if [[ " $parts " == *" spheres "* ]]; then
  sizes=(100 1000 10000 100000)
  for n in "${sizes[@]}"; do spheres "$n" "$out/s$n.scene" && : >"$out/s$n.txt" && : >"$out/s$n.b"; done
  for ((i = 0; i < repeats; ++i)); do
    for n in "${sizes[@]}"; do
      run "$out/s$n.scene" --spp 1 >>"$out/s$n.txt"
      if [ -n "$before" ] && [ "$n" -le 10000 ]; then run --before "$out/s$n.scene" --spp 1 >>"$out/s$n.b"; fi
    done
  done
  echo "spheres on a floor, 256x256, 1 spp, 1 thread, median of $repeats:"
  echo "| objects | rays (camera + shadow) | trace CPU s | ns per ray | x of 100 | read s | prepare s | peak RSS MiB | before: ns per ray | before: trace CPU s | before / now (ns per ray) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
  base=""
  for n in "${sizes[@]}"; do
    f="$out/s$n.txt"
    cpu=$(col 1 "$f")
    rays=$(cut -d' ' -f2 "$f" | head -n1)
    now=$(ns "$f")
    base=${base:-$now}
    old=$(ns "$out/s$n.b")
    oldcpu=$([ -s "$out/s$n.b" ] && col 1 "$out/s$n.b" || echo -)
    ratio=$([ "$old" = - ] && echo - || awk "BEGIN{printf \"x%.1f\", $old / $now}")
    echo "| $n | $rays | $cpu | $now | $(awk "BEGIN{printf \"%.2f\", $now / $base}") | $(col 3 "$f") | $(col 4 "$f") | $(awk "BEGIN{printf \"%.0f\", $(col 6 "$f") / 1024}") | $old | $oldcpu | $ratio |"
  done
fi

if [[ " $parts " == *" teapot "* ]]; then
  segs=(4 13 40 128)
  for g in "${segs[@]}"; do teapot "$g" "$out/t$g.scene" && : >"$out/t$g.txt" && : >"$out/t$g.b"; done
  for ((i = 0; i < repeats; ++i)); do
    for g in "${segs[@]}"; do
      run "$out/t$g.scene" --spp 1 >>"$out/t$g.txt"
      if [ -n "$before" ] && [ "$g" -le 13 ]; then run --before "$out/t$g.scene" --spp 1 >>"$out/t$g.b"; fi
    done
  done
  echo "teapot, 256x192, 1 spp, 1 thread, median of $repeats:"
  echo "| segments | triangles | rays | ns per ray | x of 4 | read s | prepare s | Embree bytes per triangle | mesh bytes per triangle | peak RSS MiB | before: ns per ray | before / now |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
  base=""
  for g in "${segs[@]}"; do
    f="$out/t$g.txt"
    obj="$out/teapot_$g.obj"
    # the mesh as read (mesh.h): 12 bytes per position and normal, 8 per uv, 3 index
    # triples (position, normal, uv) of 12 bytes per triangle
    read -r tris mesh <<<"$(awk '/^v / {v++} /^vn / {n++} /^vt / {t++} /^f / {f += NF - 3}
      END {print f, (12 * v + 12 * n + 8 * t + 36 * f) / f}' "$obj")"
    rays=$(cut -d' ' -f2 "$f" | head -n1)
    bytes=$(cut -d' ' -f5 "$f" | head -n1)
    now=$(ns "$f")
    base=${base:-$now}
    old=$(ns "$out/t$g.b")
    ratio=$([ "$old" = - ] && echo - || awk "BEGIN{printf \"x%.0f\", $old / $now}")
    echo "| $g | $tris | $rays | $now | $(awk "BEGIN{printf \"%.2f\", $now / $base}") | $(col 3 "$f") | $(col 4 "$f") | $(awk "BEGIN{printf \"%.1f\", $bytes / $tris}") | $(awk "BEGIN{printf \"%.1f\", $mesh}") | $(awk "BEGIN{printf \"%.0f\", $(col 6 "$f") / 1024}") | $old | $ratio |"
  done
fi

if [[ " $parts " == *" povray "* ]]; then
  spheres 4000 "$out/p_spheres.scene"
  teapot 128 "$out/p_teapot.scene" 256 256
  pov() { # NAME W H: POV-Ray's own CPU seconds of the trace (one thread, no antialiasing)
    (cd "$out" && /usr/bin/time -f "cpu %U %S" povray +I"$1.pov" +O"$1.png" +W"$2" +H"$3" \
      -D -A +WT1 +L"$root/povray_macros" 2>&1 | sed -n 's/^cpu \([0-9.]*\) \([0-9.]*\)$/\1 \2/p' |
      awk '{print $1 + $2}')
  }
  model=(--model blinn_phong --set n=100)
  echo "abrdf vs POV-Ray 3.7 --native, 256x256, 4 rays per pixel, 1 thread, median of $repeats (trace CPU s):"
  echo "| scene | objects, triangles | abrdf render | POV-Ray (run - 1x1 run) | POV-Ray / abrdf |"
  echo "|---|---|---|---|---|"
  for name in p_spheres p_teapot; do
    "$abrdf" export --pov "$out/$name.scene" -o "$out/$name.pov" --native "${model[@]}" \
      --width 512 --height 512
    : >"$out/$name.a" && : >"$out/$name.p"
    for ((i = 0; i < repeats; ++i)); do
      run "$out/$name.scene" --spp 4 --width 256 --height 256 "${model[@]}" | cut -d' ' -f1 >>"$out/$name.a"
      echo "$(pov "$name" 512 512) $(pov "$name" 1 1)" | awk '{print $1 - $2}' >>"$out/$name.p"
    done
    a=$(median <"$out/$name.a")
    p=$(median <"$out/$name.p")
    what=$([ "$name" = p_spheres ] && echo "4000, 0" || echo "2, 1047552")
    echo "| $name | $what | $a | $p | x$(awk "BEGIN{printf \"%.1f\", $p / $a}") |"
  done
fi
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
echo "command: $0 $build $repeats \"$parts\"${before:+ BEFORE}"
