#!/usr/bin/env bash
# Installs what abrdf needs on a Debian machine, only what is missing. Idempotent.
#   scripts/setup.sh            build + test dependencies (Debian packages, then bpy in .venv
#                               and the Python route's tools in .venv-python)
#   scripts/setup.sh --no-bpy   the Debian packages only (enough to build and render)
set -euo pipefail
with_bpy=1
[ "${1:-}" = "--no-bpy" ] && with_bpy=0

debs=(build-essential g++ cmake pkg-config check python3 povray
      libopenimageio-dev openimageio-tools libopenexr-dev libopencolorio-dev
      python3-openimageio python3-numpy   # independent image checks in tests
      python3-dev   # the Python module (python/src), which the sanitizer build compiles
      libsleef-dev   # tools/bench/vmath_choice: SLEEF timed against the library's own vector math
      libembree-dev        # ray queries of the built-in renderer (tools/render/accel.c)
      libtinyobjloader-dev # OBJ meshes (tools/render/mesh_obj.cpp)
      libtinygltf-dev # glTF files (tools/gltf/)
      clang-format  # the C style, checked by the test check_format
      emscripten    # the browser explorer: libabrdf to WebAssembly (tools/web)
      chromium      # the explorer's tests, in headless Chromium (tests/web)
      time)  # /usr/bin/time: POV-Ray's CPU time in tools/bench/renderers.sh (bpy: scripts/setup_bpy.sh)

missing=()
for p in "${debs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "setup: need root or sudo to install ${missing[*]}" >&2; exit 1; }
    sudo=sudo
  fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# The OSL port's tests render in Blender's Cycles: bpy from PyPI in .venv. The Python package,
# its tests and the Blender extension's wheel are built with .venv-python.
if ((with_bpy)); then
  "$(dirname "$0")/setup_bpy.sh"
  "$(dirname "$0")/setup_python.sh"
fi
