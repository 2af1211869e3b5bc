#!/usr/bin/env python3
"""What the binding's threads gain over one thread (docs/BENCHMARKS.md, section 4, "Threads
kept between calls").

For each array size, on float32 unit rows of `disney_specular` (r = 0.3) into a reused output,
wall time per call, the median of ROUNDS calls:
  one thread   BRDF.eval(wi, wo, threads=1, out=out)
  T, in a row  BRDF.eval(..., threads=T): calls one after another, as a loop over chunks makes
               them (the threads are still awake from the call before)
  T, after a pause   the same, each call after IDLE seconds of sleep (the threads, and on a
               virtual machine the cores, have gone to sleep)
and the speed-up of each over one thread, measured in the same run, interleaved size by size.

usage: PYTHONPATH=<installed abrdf> python threads_python.py [--threads 2] [--rounds 31]
       [--idle 0.002] [--sizes 32768,65536,262144,1000000]
"""
import argparse
import os
import platform
import statistics
import time

import numpy as np

import abrdf


def directions(n, seed):
    rng = np.random.default_rng(seed)
    v = rng.normal(size=(n, 3))
    v[:, 2] = np.abs(v[:, 2]) + 0.05
    return (v / np.linalg.norm(v, axis=1, keepdims=True)).astype(np.float32)


def per_call(fn, rounds, idle):
    times = []
    for _ in range(rounds):
        if idle:
            time.sleep(idle)
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--rounds", type=int, default=31)
    ap.add_argument("--idle", type=float, default=0.002)
    ap.add_argument("--sizes", default="32768,65536,262144,1000000")
    a = ap.parse_args()
    sizes = [int(s) for s in a.sizes.split(",")]
    b = abrdf.BRDF("disney_specular", r=0.3)
    print(f"# abrdf {abrdf.__version__}, {platform.machine()}, {os.cpu_count()} cores, "
          f"disney_specular, float32 rows, out=; median of {a.rounds} calls, wall time; "
          f"load average {os.getloadavg()[0]:.1f}")
    print(f"# command: python tools/bench/threads_python.py --threads {a.threads} "
          f"--rounds {a.rounds} --idle {a.idle} --sizes {a.sizes}")
    print()
    print(f"| pairs | one thread, us | {a.threads} threads in a row, us | "
          f"{a.threads} threads after {a.idle * 1e3:g} ms idle, us |")
    print("|---:|---:|---:|---:|")
    for n in sizes:
        wi, wo = directions(n, 1), directions(n, 2)
        out = np.empty((n, 3), np.float32)
        one = b.eval(wi, wo, threads=1)
        assert np.array_equal(b.eval(wi, wo, threads=a.threads, out=out), one)
        t1 = per_call(lambda: b.eval(wi, wo, threads=1, out=out), a.rounds, 0)
        tr = per_call(lambda: b.eval(wi, wo, threads=a.threads, out=out), a.rounds, 0)
        tp = per_call(lambda: b.eval(wi, wo, threads=a.threads, out=out), a.rounds, a.idle)
        print(f"| {n} | {t1 * 1e6:.1f} | {tr * 1e6:.1f} ({t1 / tr:.2f}x) | "
              f"{tp * 1e6:.1f} ({t1 / tp:.2f}x) |")


if __name__ == "__main__":
    main()
