#!/usr/bin/env bash
# pov_roughness_check.sh - renders POV-Ray's native `specular ... roughness` highlight and
# compares it with abrdf's Blinn-Phong lobe at n = 1/roughness (abrdf_pov_roughness_to_n).
# Prints the Markdown table quoted in docs/MODELS.md, "n and POV-Ray `roughness`".
#   tools/measure/pov_roughness_check.sh [path/to/abrdf]     (needs povray and oiiotool)
# Scene: a unit sphere seen head-on by an orthographic camera (one pixel: N = V = +z), lit by
# a parallel light at theta_i from the normal; only the specular term is on.
set -euo pipefail
abrdf=${1:-build/bin/abrdf}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "| theta_i | roughness | n = 1/roughness | POV-Ray pixel | abrdf blinn_phong f_r | rel. diff | f_r * N.wi |"
echo "|---|---|---|---|---|---|---|"
for cfg in "60 0.05" "20 0.01" "40 0.2" "12 0.002"; do
  set -- $cfg
  th=$1 rough=$2
  cat > "$tmp/s.pov" <<POV
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { orthographic location <0,0,10> look_at <0,0,0> right <0.001,0,0> up <0,0.001,0> }
light_source { <sin(radians($th)),0,cos(radians($th))>*1000 color rgb 1 parallel point_at <0,0,0> }
sphere { 0, 1 pigment { rgb 0 } finish { ambient 0 diffuse 0 specular 1 roughness $rough } }
POV
  povray +I"$tmp/s.pov" +O"$tmp/s.exr" +FE +W1 +H1 -D -V >/dev/null 2>&1
  pix=$(oiiotool "$tmp/s.exr" --printstats | awk '/Stats Avg/ {print $3}')
  read -r wi n <<<"$(awk -v t="$th" -v r="$rough" 'BEGIN { d = atan2(0, -1) / 180; printf "%.17g,0,%.17g %.17g", sin(t*d), cos(t*d), 1/r }')"
  f=$("$abrdf" eval blinn_phong --wi "$wi" --wo 0,0,1 --set n="$n" --set ks=1 --json | sed 's/.*\[\([^,]*\),.*/\1/')
  awk -v t="$th" -v r="$rough" -v n="$n" -v p="$pix" -v f="$f" 'BEGIN {
    d = atan2(0, -1) / 180
    printf "| %g | %g | %g | %.6g | %.6g | %.1e | %.6g |\n", t, r, n, p, f, (p - f) / f, f * cos(t * d) }'
done
