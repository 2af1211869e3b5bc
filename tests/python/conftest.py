"""Shared fixtures of the Python package's tests (pytest, run by CTest: tests/python).

The package under test is the one on sys.path (CTest puts the pip-installed copy first);
the command `abrdf` ($ABRDF) is the reference the package must agree with, and
$ABRDF_SOURCE_DIR the source tree (scenes, data).
"""
import json
import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    """Run the command: cli("advise", "gold", "--json") -> parsed JSON, or text."""
    path = os.environ.get("ABRDF")
    if not path or not os.access(path, os.X_OK):
        pytest.fail("$ABRDF must name the built abrdf command (CTest sets it)")

    def run(*args, check=True, parse=True):
        r = subprocess.run([path, *map(str, args)], capture_output=True, text=True)
        if check and r.returncode != 0:
            raise AssertionError("abrdf %s failed (%d): %s" % (" ".join(map(str, args)),
                                                              r.returncode, r.stderr))
        return json.loads(r.stdout) if parse and "--json" in args else r
    return run


@pytest.fixture(scope="session")
def source_dir():
    d = os.environ.get("ABRDF_SOURCE_DIR")
    if not d or not os.path.isdir(d):
        pytest.fail("$ABRDF_SOURCE_DIR must name the source tree (CTest sets it)")
    return d


@pytest.fixture(scope="session")
def material_assets(source_dir, tmp_path_factory):
    """The files of tools/gen/gen_material_assets.py, generated into a temporary directory,
    and the generator itself as a module (its CONSTANTS table): (directory, module)."""
    import importlib.util
    import sys

    script = os.path.join(source_dir, "tools", "gen", "gen_material_assets.py")
    out = tmp_path_factory.mktemp("material_assets")
    r = subprocess.run([sys.executable, script, str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    spec = importlib.util.spec_from_file_location("gen_material_assets", script)
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    return out, gen
