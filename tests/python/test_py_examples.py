"""The package's documented examples run: the docstring examples (doctest), the plotting
example (examples/plot_lobes.py) and the binding's benchmark (tools/bench/bench_python.py)
on a small size. No timing is judged."""
import doctest
import os
import subprocess
import sys

import abrdf


def test_docstring_examples():
    assert doctest.testmod(abrdf, verbose=False).failed == 0
    assert doctest.testmod(abrdf, verbose=False).attempted >= 4


def test_the_installed_package_is_tested():
    # CTest runs the suite on what pip installed (PYTHONPATH), not on the source tree's copy.
    site = os.environ.get("PYTHONPATH", "").split(os.pathsep)[0]
    assert site and os.path.realpath(abrdf.__file__).startswith(os.path.realpath(site))
    assert os.path.isfile(os.path.join(os.path.dirname(abrdf.__file__), "data", "materials.csv"))


def run_script(source_dir, path, *args):
    env = dict(os.environ, MPLBACKEND="Agg")
    r = subprocess.run([sys.executable, os.path.join(source_dir, path), *args], env=env,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r.stdout


def test_plot_example(source_dir, tmp_path):
    out = tmp_path / "plots.png"
    run_script(source_dir, "examples/plot_lobes.py", "-o", str(out))
    with open(out, "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"


def test_binding_benchmark_runs(source_dir):
    text = run_script(source_dir, "tools/bench/bench_python.py", "--n", "512", "--rounds", "1",
                      "--calls", "20")
    assert "per call" in text and "per element" in text and "disney_specular" in text


def test_threads_benchmark_runs(source_dir):
    text = run_script(source_dir, "tools/bench/threads_python.py", "--sizes", "512,40000",
                      "--rounds", "1", "--idle", "0.001")
    assert "| 512 |" in text and "| 40000 |" in text and "threads in a row" in text
