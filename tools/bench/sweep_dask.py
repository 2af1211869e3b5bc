#!/usr/bin/env python3
"""abrdf.sweep on dask.distributed against its serial loop (docs/PYTHON.md, "Measured materials
and library sweeps"): wall-clock time of one sweep of a material library by candidate models,
  serial    scheduler="serial": the plain loop in this process;
  cluster   a LocalCluster of WORKERS processes (one thread each) started beforehand and
            reused, the sweep alone timed;
  cold      scheduler=None: the same with the cluster's start and stop counted, what one call
            of abrdf.sweep costs;
each the median of ROUNDS rounds, interleaved. Every round checks that the cluster's result
equals the loop's (the same numbers in the same order).

The library: --library files (default) tabulates FILES materials with `abrdf tabulate` (varied
models and parameters, on --grid, MERL's 90,90,180 by default: 17 MB each, read by the workers
from their paths), fitted through abrdf_fit_to; --library names takes FILES entries of the
material table (data/materials.csv) instead, fitted through abrdf_fit to their photoreal
choice. The candidates are the first MODELS of CANDIDATES.

usage: PYTHONPATH=<installed abrdf> python sweep_dask.py --abrdf build/bin/abrdf
           [--library files|names] [--files 8] [--models 10] [--grid 90,90,180]
           [--workers 2] [--rounds 3] [--metric auto] [--resolution 0]
           [--budget noticeable]
"""
import argparse
import os
import platform
import statistics
import subprocess
import tempfile
import time

import distributed

import abrdf

# What a file of the library is: a model and its parameters for `abrdf tabulate`.
TABULATED = (
    ("disney_specular", ("r=0.2", "f0=0.9,0.6,0.3")),
    ("lambert", ("kd=0.6,0.3,0.2",)),
    ("blinn_phong", ("n=60", "ks=0.5")),
    ("disney_specular", ("r=0.5", "f0=0.04")),
    ("oren_nayar", ("sigma=0.4",)),
    ("f_ge", ("n=200",)),
    ("cook_torrance", ("r=0.35",)),
    ("disney_specular", ("r=0.8", "f0=0.95,0.64,0.54")),
    ("phong", ("n=20",)),
    ("disney_diffuse", ("r=0.6",)),
)
CANDIDATES = ("lambert", "blinn_phong", "f_ge", "disney_specular", "lambert+blinn_phong",
              "lambert+f_ge", "lambert+disney_specular", "oren_nayar+disney_specular",
              "lambert+cook_torrance", "disney_diffuse+disney_specular", "lambert+f2",
              "lambert+f_2e")


def tabulated_library(cli, n, grid, where):
    paths = []
    for i in range(n):
        model, sets = TABULATED[i % len(TABULATED)]
        path = os.path.join(where, "m%02d_%s.binary" % (i, model))
        args = [cli, "tabulate", model, "-o", path, "--grid", grid, "--seed", str(i + 1),
                "--noise", "0.05"]
        for s in sets:
            args += ["--set", s]
        subprocess.run(args, check=True, capture_output=True)
        paths.append(path)
    return paths


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--abrdf", help="the abrdf command (for --library files)")
    ap.add_argument("--library", choices=("files", "names"), default="files")
    ap.add_argument("--files", type=int, default=8)
    ap.add_argument("--models", type=int, default=10)
    ap.add_argument("--grid", default="90,90,180")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--metric", default="auto")
    ap.add_argument("--resolution", type=int, default=0, help="abrdf.fit's, 0 = default (3)")
    ap.add_argument("--budget", default="noticeable")
    a = ap.parse_args()
    models = list(CANDIDATES[:a.models])
    with tempfile.TemporaryDirectory() as where:
        if a.library == "files":
            if not a.abrdf:
                ap.error("--library files needs --abrdf")
            materials = tabulated_library(a.abrdf, a.files, a.grid, where)
        else:
            materials = list(abrdf.materials())[:a.files]

        def run(scheduler):
            t = time.perf_counter()
            s = abrdf.sweep(materials, models, a.budget, metric=a.metric,
                            resolution=a.resolution, scheduler=scheduler,
                            workers=a.workers if scheduler is None else None)
            return time.perf_counter() - t, s

        times = {"serial": [], "cluster": [], "cold": []}
        with distributed.LocalCluster(n_workers=a.workers, threads_per_worker=1,
                                      processes=True, dashboard_address=None) as cluster, \
                distributed.Client(cluster) as client:
            for _ in range(a.rounds):
                t, ref = run("serial")
                times["serial"].append(t)
                t, got = run(client)
                times["cluster"].append(t)
                assert got == ref, "the cluster's sweep differs from the loop's"
                t, got = run(None)
                times["cold"].append(t)
                assert got == ref, "the cold cluster's sweep differs from the loop's"
    med = {k: statistics.median(v) for k, v in times.items()}
    print("# abrdf.sweep: %d %s x %d candidates = %d fits (metric %s, resolution %d), "
          "%d workers; %s, %d cores usable; medians of %d rounds"
          % (len(materials), "tabulated files (grid %s)" % a.grid if a.library == "files"
             else "table materials", len(models), len(materials) * len(models), a.metric,
             a.resolution, a.workers, platform.machine(), len(os.sched_getaffinity(0)),
             a.rounds))
    print("%-8s %9s %9s" % ("run", "seconds", "speed-up"))
    for k in ("serial", "cluster", "cold"):
        print("%-8s %9.2f %8.2fx" % (k, med[k], med["serial"] / med[k]))
    best = [b.candidate if b else "-" for b in ref.best]
    print("cheapest within %r:" % a.budget, ", ".join(best))


if __name__ == "__main__":
    main()
