#!/usr/bin/env bash
# texture_budget_proof.sh - the budget mode over a roughness map, proved on the rendered image
# (docs/GLTF.md, "Selection over a texture").
#   tools/bench/texture_budget_proof.sh [BUILD_DIR] [BUDGETS]
# A 96 x 96 camera-facing quad whose roughness map runs from 0.3 to 0.7 across its 16 x 16
# texels (a dielectric, base 0.7,0.2,0.1) under a directional and a point light. For each
# budget (default "0.005 0.002"): the pair `abrdf advise FILE --budget B` chooses and its
# predicted NMSE over the map, then the measured NMSE of `abrdf render --adaptive --budget B`
# against `abrdf render --adaptive --goal photoreal` (abrdf compare, which exits 1 above its
# pass mark: not an error here), side by side.
set -euo pipefail
build=${1:-build}
budgets=${2:-"0.005 0.002"}
abrdf=$(cd "$build" && pwd)/bin/abrdf
[ -x "$abrdf" ] || { echo "texture_budget_proof: no $abrdf (build first)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
/usr/bin/python3 - <<'PY'
import OpenImageIO as oiio, numpy as np
n = 16
r = np.tile(0.3 + 0.4 * np.arange(n) / (n - 1), (n, 1))
buf = oiio.ImageBuf(oiio.ImageSpec(n, n, 3, "uint8"))
buf.set_pixels(oiio.ROI(0, n, 0, n, 0, 1, 0, 3), np.stack([r, r, r], -1).astype(np.float32))
assert buf.write("rough.png")
PY
printf 'v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\n' > quad.obj
cat > quad.scene <<'SCENE'
camera position=0,0,3.2 look_at=0,0,0 fov=40 resolution=96,96
light directional direction=-0.4,0.5,1 intensity=3
light point position=1,1,2 intensity=4
material t pbr base_color=0.7,0.2,0.1 metallic=0 roughness=1 roughness_map=rough.png
mesh file=quad.obj material=t
SCENE
"$abrdf" render quad.scene -o ref.exr --adaptive --goal photoreal --no-preview
printf '%-8s %-32s %14s %14s\n' budget "pair (advise)" "predicted" "measured"
for b in $budgets; do
  read -r pair pred < <("$abrdf" advise quad.scene --budget "$b" --json | python3 -c '
import json, sys
m = json.load(sys.stdin)["materials"][0]
print(" + ".join(x for x in (m["diffuse"], m["specular"]) if x).replace(" ", ""), m["error"]["nmse_pred"])')
  "$abrdf" render quad.scene -o "b$b.exr" --adaptive --budget "$b" --no-preview
  meas=$({ "$abrdf" compare ref.exr "b$b.exr" || true; } | awk '/^NMSE/ {print $2}')
  printf '%-8s %-32s %14.3g %14.3g\n' "$b" "$pair" "$pred" "$meas"
done
