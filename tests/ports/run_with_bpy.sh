#!/bin/sh
# Runs a Python test with the project's venv, which holds bpy (scripts/setup_bpy.sh).
# A missing venv is a failure, not a skip: the OSL port is checked only in a real host.
#   run_with_bpy.sh SOURCE_DIR SCRIPT [ARGS...]
src=$1
shift
py="$src/.venv/bin/python"
if [ ! -x "$py" ]; then
  echo "run_with_bpy: $py is missing; run scripts/setup_bpy.sh (installs bpy from PyPI)" >&2
  exit 1
fi
exec "$py" "$@"
