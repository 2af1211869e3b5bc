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

source scripts/venv_common.sh
# Shared libraries the bpy wheel links from the system (X11/GL client libraries; Cycles
# renders on the CPU without a display) and the venv module.
apt_missing setup_bpy python3-venv libx11-6 libxrender1 libxfixes3 libxi6 libxkbcommon0 \
  libxext6 libxcb1 libsm6 libice6 libgl1
# The wheel is built for CPython 3.11 only.
py=$(python311 setup_bpy "bpy $BPY_VERSION")

[ -x "$venv/bin/python" ] || "$py" -m venv "$venv"
echo "setup_bpy: installing bpy $BPY_VERSION into $venv (about 1 GB)"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "bpy==$BPY_VERSION"
"$venv/bin/python" -c "import bpy; print('setup_bpy: bpy', bpy.app.version_string)"
