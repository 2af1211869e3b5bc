#!/usr/bin/env bash
# Installs Blender's Cycles + OSL as the Python module `bpy` (PyPI, Blender 5.0.1, a
# Python 3.11 wheel) into the project's venv .venv, for the OSL port's tests (docs/OSL.md).
# Idempotent: does nothing when .venv/bin/python already imports bpy. Large (~1 GB).
#   scripts/setup_bpy.sh
set -euo pipefail
cd "$(dirname "$0")/.."

BPY_VERSION=5.0.1
venv=.venv

if [ -x "$venv/bin/python" ] && "$venv/bin/python" -c "import bpy" >/dev/null 2>&1; then
  exit 0
fi

# Shared libraries the bpy wheel links from the system (X11/GL client libraries; Cycles
# renders on the CPU without a display) and the venv module.
debs=(python3-venv libx11-6 libxrender1 libxfixes3 libxi6 libxkbcommon0 libxext6 libxcb1
      libsm6 libice6 libgl1)
if command -v dpkg-query >/dev/null; then
  missing=()
  for p in "${debs[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if ((${#missing[@]})); then
    echo "setup_bpy: installing ${missing[*]}"
    sudo=""
    if [ "$(id -u)" -ne 0 ]; then
      command -v sudo >/dev/null || { echo "setup_bpy: need root or sudo to install ${missing[*]}" >&2; exit 1; }
      sudo=sudo
    fi
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  fi
fi

# The wheel is built for CPython 3.11 only.
py=""
for c in python3.11 python3; do
  if command -v "$c" >/dev/null && "$c" -c 'import sys; sys.exit(sys.version_info[:2] != (3, 11))'; then
    py=$c
    break
  fi
done
[ -n "$py" ] || { echo "setup_bpy: bpy $BPY_VERSION needs Python 3.11 (python3.11 not found)" >&2; exit 1; }

[ -x "$venv/bin/python" ] || "$py" -m venv "$venv"
echo "setup_bpy: installing bpy $BPY_VERSION into $venv (about 1 GB)"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "bpy==$BPY_VERSION"
"$venv/bin/python" -c "import bpy; print('setup_bpy: bpy', bpy.app.version_string)"
