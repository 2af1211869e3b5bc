#!/usr/bin/env bash
# advise_file_bench.sh - the time `abrdf advise FILE` takes for a file of many materials
# (docs/GLTF.md, "Advising a file"; the goal: 100 glTF materials in under a second without
# --budget).
#   tools/bench/advise_file_bench.sh [BUILD_DIR] [MATERIALS] [REPEATS]
# Writes, in a scratch directory, a glTF file (one quad, MATERIALS materials of a spread of
# base colours, metallic and roughness values, one primitive each) and a scene file with the
# same materials as `material NAME pbr` lines, then times, side by side in one run (the
# median wall time of REPEATS runs each):
#   abrdf advise FILE.gltf    and  --goal performance, --json
#   abrdf advise FILE.scene   (the scene reader instead of glTF's)
#   abrdf advise gold         (one material of the table: the process's fixed cost)
# and prints each with its time per material.
set -euo pipefail
build=${1:-build}
count=${2:-100}
repeats=${3:-5}
abrdf=$build/bin/abrdf
[ -x "$abrdf" ] || { echo "advise_file_bench: no $abrdf (build first)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

python3 - "$work" "$count" <<'EOF'
import base64, json, struct, sys
work, count = sys.argv[1], int(sys.argv[2])
# one quad with normals and texture coordinates, in one buffer (data URI)
pos = [-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0]
nrm = [0, 0, 1] * 4
uv = [0, 1, 1, 1, 1, 0, 0, 0]
idx = [0, 1, 2, 0, 2, 3]
blob = struct.pack("<12f", *pos) + struct.pack("<12f", *nrm) + struct.pack("<8f", *uv) + \
    struct.pack("<6H", *idx) + b"\0\0"
views = [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
         {"buffer": 0, "byteOffset": 96, "byteLength": 32}, {"buffer": 0, "byteOffset": 128, "byteLength": 12}]
acc = [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
       {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
       {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
       {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]
mats, prims, lines = [], [], []
for i in range(count):
    base = [round(0.1 + 0.8 * ((i * k) % 7) / 6, 4) for k in (1, 2, 3)]
    metallic = round((i % 5) / 4, 4)
    rough = round(0.01 + 0.98 * ((i * 37) % 100) / 99, 4)
    mats.append({"name": "m%03d" % i, "pbrMetallicRoughness": {
        "baseColorFactor": base + [1], "metallicFactor": metallic, "roughnessFactor": rough}})
    prims.append({"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": i})
    lines.append("material m%03d pbr base_color=%g,%g,%g metallic=%g roughness=%g"
                 % (i, base[0], base[1], base[2], metallic, rough))
doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
       "nodes": [{"mesh": 0}], "meshes": [{"primitives": prims}],
       "buffers": [{"byteLength": len(blob),
                    "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
       "bufferViews": views, "accessors": acc, "materials": mats}
with open(work + "/many.gltf", "w") as f:
    json.dump(doc, f)
with open(work + "/many.scene", "w") as f:
    f.write("camera position=0,0,4 look_at=0,0,0\n" + "\n".join(lines) +
            "\nsphere material=m000 radius=1\n")
EOF

# median wall seconds of $repeats runs of the command
median() {
  local times=()
  for ((i = 0; i < repeats; ++i)); do
    local t0 t1
    t0=$(date +%s.%N)
    "$@" > /dev/null
    t1=$(date +%s.%N)
    times+=("$(echo "$t1 - $t0" | bc -l)")
  done
  printf '%s\n' "${times[@]}" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'
}

echo "abrdf advise over $count materials (median of $repeats runs, wall seconds)"
printf '%-40s %10s %14s\n' "command" "seconds" "ms/material"
for args in "many.gltf" "many.gltf --goal performance" "many.gltf --json" "many.scene"; do
  # shellcheck disable=SC2086
  s=$(median "$abrdf" advise "$work"/$args)
  printf '%-40s %10.3f %14.3f\n' "advise $args" "$s" "$(echo "1000 * $s / $count" | bc -l)"
done
s=$(median "$abrdf" advise gold)
printf '%-40s %10.3f %14s\n' "advise gold (one table material)" "$s" "-"
