#!/usr/bin/env bash
# Installs the Python route's build and test tools into the project's venv .venv-python
# (docs/PYTHON.md): a Python 3.11 (the Python of Blender 4.2 to 5.0, so the wheel it builds
# also goes into the Blender extension) with pip, scikit-build-core, NumPy, OpenImageIO's
# bindings, pytest and matplotlib, pinned. Kept apart from .venv, whose bpy pins NumPy < 2
# and brings its own OpenImageIO bindings (oslquery needs those, not PyPI's).
# Idempotent: does nothing when .venv-python already has these versions.
#   scripts/setup_python.sh
set -euo pipefail
cd "$(dirname "$0")/.."

venv=.venv-python
pins=(numpy==2.4.6 scikit-build-core==1.1.2 OpenImageIO==3.2.2.0 pytest==9.2.0 matplotlib==3.11.2)

if [ -x "$venv/bin/python" ] && "$venv/bin/python" - "${pins[@]}" <<'PY'
import sys
from importlib.metadata import version, PackageNotFoundError
try:
    ok = all(version(p.split("==")[0]) == p.split("==")[1] for p in sys.argv[1:])
except PackageNotFoundError:
    ok = False
sys.exit(0 if ok else 1)
PY
then
  exit 0
fi

# Headers for the extension module and the venv module (Debian).
debs=(python3-venv python3-dev)
if command -v dpkg-query >/dev/null; then
  missing=()
  for p in "${debs[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if ((${#missing[@]})); then
    echo "setup_python: installing ${missing[*]}"
    sudo=""
    if [ "$(id -u)" -ne 0 ]; then
      command -v sudo >/dev/null || { echo "setup_python: need root or sudo to install ${missing[*]}" >&2; exit 1; }
      sudo=sudo
    fi
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  fi
fi

py=""
for c in python3.11 python3; do
  if command -v "$c" >/dev/null && "$c" -c 'import sys; sys.exit(sys.version_info[:2] != (3, 11))'; then
    py=$c
    break
  fi
done
[ -n "$py" ] || { echo "setup_python: needs Python 3.11 (python3.11 not found)" >&2; exit 1; }

[ -x "$venv/bin/python" ] || "$py" -m venv "$venv"
echo "setup_python: installing ${pins[*]} into $venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "${pins[@]}"
