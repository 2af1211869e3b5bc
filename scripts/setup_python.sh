#!/usr/bin/env bash
# Installs the Python route's build and test tools into the project's venv .venv-python
# (docs/PYTHON.md): a Python 3.11 (the Python of Blender 4.2 to 5.0, so the wheel it builds
# also goes into the Blender extension) with pip, scikit-build-core, NumPy, OpenImageIO's
# bindings, pytest, matplotlib, Mitsuba 3 (the oracle of the RGL .bsdf reader,
# tests/cli/test_rgl_mitsuba.py; its scalar variants need no LLVM) and dask.distributed
# (abrdf.sweep's cluster, tests/python/test_py_sweep.py) and MaterialX (abrdf.load_materialx,
# tests/python/test_py_materialx.py) and Playwright (the explorer page's browser tests,
# tests/web/: its wheel brings its own driver; the browser is Debian's chromium, scripts/setup.sh),
# pinned. Kept apart from .venv, whose bpy pins NumPy < 2
# and brings its own OpenImageIO bindings (oslquery needs those, not PyPI's).
# Idempotent: does nothing when .venv-python already has these versions.
#   scripts/setup_python.sh
set -euo pipefail
cd "$(dirname "$0")/.."

venv=.venv-python
pins=(numpy==2.4.6 scikit-build-core==1.1.2 OpenImageIO==3.2.2.0 pytest==9.2.0 matplotlib==3.11.2
      mitsuba==3.9.1 dask==2026.8.0 distributed==2026.8.0 materialx==1.39.5 playwright==1.65.2)

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

source scripts/venv_common.sh
# Headers for the extension module and the venv module (Debian).
apt_missing setup_python python3-venv python3-dev
py=$(python311 setup_python "the Python route")

[ -x "$venv/bin/python" ] || "$py" -m venv "$venv"
echo "setup_python: installing ${pins[*]} into $venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "${pins[@]}"
