#!/usr/bin/env python3
"""What the Python binding costs against the C batch path it calls (docs/BENCHMARKS.md, 4).

In one process, interleaved round by round (the median of ROUNDS rounds is reported):
  C batch    abrdf_eval_batch alone on structure-of-arrays copies of the directions, timed
             inside the extension module (abrdf._abrdf._time_eval_batch);
  binding    abrdf.BRDF.eval(wi, wo, threads=1): NumPy in, NumPy out (shape checks,
             broadcasting, conversion to C-contiguous rows, the GIL released around the C loop:
             float32 rows straight into abrdf_eval_prepared_rows, which makes them unit,
             float64 rows converted to float rows in chunks first); one thread, as the C column
             (the binding's threads for large arrays: tools/bench/peer_mitsuba.py);
  out=       abrdf.BRDF.eval(wi, wo, threads=1, out=out) on float32 rows: the binding into a
             reused output array (no allocation, no first touch of new pages);
  raw        abrdf._abrdf.eval_float on ready float32 rows and a preallocated output: the C
             binding without the package's Python layer.
Per call: one direction pair (the binding's fixed cost). Per element: N pairs, float64 rows
(what NumPy code usually holds) and float32 rows.

usage: PYTHONPATH=<installed abrdf> python bench_python.py [--n 65536] [--rounds 7]
"""
import argparse
import platform
import statistics
import time

import numpy as np

import abrdf
from abrdf import _abrdf

MODELS = (("blinn_phong", {"n": 100}), ("disney_specular", {"r": 0.3}))


def directions(n, seed):
    rng = np.random.default_rng(seed)
    v = rng.normal(size=(n, 3))
    v[:, 2] = np.abs(v[:, 2]) + 0.05
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def per_call(fn, calls):
    """ns per call on this thread's CPU-time clock (the C side's clock too)."""
    t0 = time.thread_time_ns()
    for _ in range(calls):
        fn()
    return (time.thread_time_ns() - t0) / calls


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=65536, help="pairs per call for the per-element cost")
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--calls", type=int, default=20000, help="calls per round for the per-call cost")
    a = ap.parse_args()
    print("abrdf %s, NumPy %s, Python %s, %s" % (abrdf.__version__, np.__version__,
                                                 platform.python_version(), platform.machine()))
    wi1, wo1 = directions(1, 1), directions(1, 2)
    wi, wo = directions(a.n, 3), directions(a.n, 4)
    wi32, wo32 = wi.astype(np.float32), wo.astype(np.float32)
    one32 = np.empty((1, 3), np.float32)
    out32 = np.empty((a.n, 3), np.float32)
    rows = []
    for name, params in MODELS:
        b = abrdf.BRDF(name, **params)
        p = b.block
        res = {k: [] for k in ("c1", "py1", "raw1", "cn", "py64", "py32", "py32o", "rawn")}
        for _ in range(a.rounds):
            res["c1"].append(_abrdf._time_eval_batch(
                p, wi1.astype(np.float32), wo1.astype(np.float32), one32, a.calls) * 1e9)
            res["py1"].append(per_call(lambda: b.eval(wi1[0], wo1[0]), a.calls))
            res["raw1"].append(per_call(lambda: _abrdf.eval_float(p, wi1, wo1, one32), a.calls))
            res["cn"].append(_abrdf._time_eval_batch(p, wi32, wo32, out32, 5) * 1e9 / a.n)
            res["py64"].append(per_call(lambda: b.eval(wi, wo, threads=1), 5) / a.n)
            res["py32"].append(per_call(lambda: b.eval(wi32, wo32, threads=1), 5) / a.n)
            res["py32o"].append(per_call(lambda: b.eval(wi32, wo32, threads=1, out=out32), 5)
                                / a.n)
            res["rawn"].append(per_call(lambda: _abrdf.eval_float(p, wi32, wo32, out32, 1), 5) / a.n)
        med = {k: statistics.median(v) for k, v in res.items()}
        spread = {k: (max(v) - min(v)) / statistics.median(v) for k, v in res.items()}
        rows.append((name, med, spread))
    print("\nper call, one pair (ns): C batch | binding (BRDF.eval) | raw _abrdf.eval_float")
    for name, med, spread in rows:
        print("  %-16s %7.0f | %7.0f (+%.0f) | %7.0f (+%.0f)" % (
            name, med["c1"], med["py1"], med["py1"] - med["c1"], med["raw1"],
            med["raw1"] - med["c1"]))
    print("\nper element, %d pairs (ns/pair): C batch | binding float64 rows | binding float32 "
          "rows | out= float32 | raw float32 (ratio to C)" % a.n)
    for name, med, spread in rows:
        print("  %-16s %6.2f | %6.2f (%.2fx) | %6.2f (%.2fx) | %6.2f (%.2fx) | %6.2f (%.2fx)" % (
            name, med["cn"], med["py64"], med["py64"] / med["cn"], med["py32"],
            med["py32"] / med["cn"], med["py32o"], med["py32o"] / med["cn"], med["rawn"],
            med["rawn"] / med["cn"]))
    worst = max(s for _, _, sp in rows for s in sp.values())
    print("\n%d rounds interleaved, medians; largest (max - min) / median of a cell: %.0f %%"
          % (a.rounds, 100 * worst))


if __name__ == "__main__":
    main()
