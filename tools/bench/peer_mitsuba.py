#!/usr/bin/env python3
"""abrdf against a peer, Mitsuba 3, on the same direction pairs (docs/BENCHMARKS.md, section 4).

On N float32 direction pairs (local frame, both above the surface, fixed seed), in one process,
rounds interleaved, the median of ROUNDS rounds per pair: the one-thread columns in CPU time
of the process (every thread's: Mitsuba's one worker included; time spent descheduled on a
busy machine is not counted), the all-threads columns in wall time:

  C batch          abrdf_eval_batch alone on structure-of-arrays copies, one thread
                   (abrdf._abrdf._time_eval_batch: the library without the binding; a
                   material: the sum of its lobes' calls)
  C rows           abrdf_eval_prepared_rows alone on the float32 rows, one thread (the same
                   timer, layout=1): the entry the binding calls, which reads interleaved rows
                   and makes them unit
  binding, 1 thread   X.eval(wi, wo, threads=1): float32 rows in, a new array out (np.empty)
  binding out=, 1 thread   X.eval(wi, wo, threads=1, out=out): into one reused array
  binding, all     X.eval(wi, wo): the binding's threads, one per core, a new array
  binding out=, all   the same into the reused array
  Mitsuba, 1 thread   the llvm_ad_rgb variant's compiled kernel, drjit limited to one thread
  Mitsuba, all     the same with drjit's thread pool (one per core)
X is an abrdf.BRDF, or for a material an abrdf.Lobes (its lobes in one pass over the rows).

Cases: GGX with F = 1 (Mitsuba's `roughconductor`, material "none", alpha = r^2) against
abrdf's `disney_specular` with ks = f0 = 1, whose values are compared too (median and 99.9th
percentile relative difference of f_r, Mitsuba's eval divided by its cosine); Mitsuba's
`principled` (base colour 0.5, roughness r, specular 0.5, metallic 0) against abrdf's
`disney_diffuse + disney_specular` as one abrdf.Lobes, a cost comparison of two complete
materials only (the lobes are not the same functions: no agreement is claimed); and the same
material as two BRDF.eval calls whose results are added (`d.eval(wi, wo) + s.eval(wi, wo)`,
the way before Lobes), for the reader.

Mitsuba comes from PyPI (`pip install mitsuba`); its LLVM variant needs an LLVM of version 16
or newer: Debian's libllvm19, found through DRJIT_LIBLLVM_PATH (set here when unset and the
library is at its Debian path). The abrdf package is the one on PYTHONPATH.

usage: PYTHONPATH=<installed abrdf> python peer_mitsuba.py [--n 1000000] [--rounds 5] [--r 0.3]
"""
import argparse
import os
import platform
import statistics
import sys
import time

DEBIAN_LLVM = "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1"
if "DRJIT_LIBLLVM_PATH" not in os.environ and os.path.exists(DEBIAN_LLVM):
    os.environ["DRJIT_LIBLLVM_PATH"] = DEBIAN_LLVM

import numpy as np  # noqa: E402

import abrdf  # noqa: E402
from abrdf import _abrdf  # noqa: E402

try:
    import drjit as dr  # noqa: E402
    import mitsuba as mi  # noqa: E402
except ImportError as e:
    sys.exit(f"peer_mitsuba: Mitsuba 3 is not installed ({e}); pip install mitsuba")


def directions(n, seed):
    rng = np.random.default_rng(seed)
    v = rng.normal(size=(n, 3))
    v[:, 2] = np.abs(v[:, 2]) + 0.05
    return (v / np.linalg.norm(v, axis=1, keepdims=True)).astype(np.float32)


class MitsubaCase:
    """One Mitsuba BSDF evaluated on the pairs: eval() returns f_r (cosine divided out)."""

    def __init__(self, desc, wi, wo):
        self.bsdf = mi.load_dict(desc)
        self.ctx = mi.BSDFContext()
        si = dr.zeros(mi.SurfaceInteraction3f, len(wi))
        si.n = mi.Normal3f(0, 0, 1)
        si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
        si.wi = mi.Vector3f(wo[:, 0], wo[:, 1], wo[:, 2])  # Mitsuba: si.wi toward the viewer
        self.si = si
        self.light = mi.Vector3f(wi[:, 0], wi[:, 1], wi[:, 2])
        self.cos = wi[:, 2].astype(np.float64)

    def run(self):
        v = self.bsdf.eval(self.ctx, self.si, self.light)
        dr.eval(v)
        dr.sync_thread()
        return v

    def values(self):
        v = self.run()
        return np.stack([np.array(v.x), np.array(v.y), np.array(v.z)], axis=1) / self.cos[:, None]


def wall(fn):
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def cpu(fn):
    t0 = time.process_time()
    fn()
    return time.process_time() - t0


def mitsuba(clock, threads, case):
    """One timed run of a Mitsuba case with drjit's pool at `threads`."""
    dr.set_thread_count(threads)
    return clock(case.run)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=1000000)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--r", type=float, default=0.3)
    o = ap.parse_args()
    if o.n < 1 or o.rounds < 1 or not 0.0 < o.r <= 1.0:
        sys.exit("peer_mitsuba: --n and --rounds >= 1, --r in (0, 1]")
    mi.set_variant("llvm_ad_rgb")
    cores = os.cpu_count() or 1
    wi, wo = directions(o.n, 1), directions(o.n, 2)
    alpha = o.r * o.r
    spec = abrdf.BRDF("disney_specular", r=o.r, ks=1.0, f0=(1.0, 1.0, 1.0))
    dif = abrdf.BRDF("disney_diffuse", r=o.r, kd=(0.5, 0.5, 0.5))
    spec_pair = abrdf.BRDF("disney_specular", r=o.r)
    ggx = MitsubaCase({"type": "roughconductor", "distribution": "ggx", "alpha": alpha,
                       "material": "none"}, wi, wo)
    principled = MitsubaCase({"type": "principled", "base_color": {"type": "rgb",
                              "value": [0.5, 0.5, 0.5]}, "roughness": o.r, "specular": 0.5,
                              "metallic": 0.0}, wi, wo)
    out = np.empty((o.n, 3), np.float32)
    material = abrdf.Lobes([dif, spec_pair])

    def c_batch(brdfs, layout=0):
        return sum(_abrdf._time_eval_batch(b.block, wi, wo, out, 1, layout) for b in brdfs)

    def ours(x):
        return {
            "binding, 1 thread": lambda: cpu(lambda: x.eval(wi, wo, threads=1)),
            "binding out=, 1 thread": lambda: cpu(lambda: x.eval(wi, wo, threads=1, out=out)),
            "binding, all": lambda: wall(lambda: x.eval(wi, wo)),
            "binding out=, all": lambda: wall(lambda: x.eval(wi, wo, out=out)),
        }

    cases = {
        "ggx": {
            "C batch": lambda: c_batch([spec]),
            "C rows": lambda: c_batch([spec], 1),
            **ours(spec),
            "Mitsuba, 1 thread": lambda: mitsuba(cpu, 1, ggx),
            "Mitsuba, all": lambda: mitsuba(wall, cores, ggx),
        },
        "principled": {
            "C batch": lambda: c_batch([dif, spec_pair]),
            "C rows": lambda: c_batch([dif, spec_pair], 1),
            **ours(material),
            "Mitsuba, 1 thread": lambda: mitsuba(cpu, 1, principled),
            "Mitsuba, all": lambda: mitsuba(wall, cores, principled),
        },
        "two calls": {
            "C batch": lambda: c_batch([dif, spec_pair]),
            "binding, 1 thread": lambda: cpu(lambda: dif.eval(wi, wo, threads=1)
                                             + spec_pair.eval(wi, wo, threads=1)),
            "binding, all": lambda: wall(lambda: dif.eval(wi, wo) + spec_pair.eval(wi, wo)),
        },
    }
    # warm-up: Mitsuba compiles its kernels on the first call (cached afterwards)
    for case in cases.values():
        for fn in case.values():
            fn()
    times = {c: {k: [] for k in fns} for c, fns in cases.items()}
    for _ in range(o.rounds):
        for c, fns in cases.items():
            for k, fn in fns.items():
                times[c][k].append(fn() / o.n)

    dr.set_thread_count(cores)
    mine = spec.eval(wi, wo).astype(np.float64)
    theirs = ggx.values()
    rel = np.abs(mine - theirs) / np.maximum(np.abs(theirs), 1e-30)
    rel = rel[theirs > 1e-6]

    print(f"# abrdf {abrdf.__version__} against Mitsuba {mi.__version__} (llvm_ad_rgb), "
          f"{platform.processor() or platform.machine()}, {cores} cores, "
          f"{o.n} float32 pairs, median of {o.rounds} rounds; 1 thread: process CPU time, "
          f"all: wall time; load average at the end {os.getloadavg()[0]:.1f}")
    print(f"# command: python tools/bench/peer_mitsuba.py --n {o.n} --rounds {o.rounds} --r {o.r}")
    print()
    cols = list(cases["ggx"])
    print("| case | " + " | ".join(f"{c}, ns/pair" for c in cols) + " |")
    print("|---|" + "---:|" * len(cols))
    labels = {"ggx": f"GGX r {o.r}, F = 1 (disney_specular / roughconductor)",
              "principled": f"material r {o.r} (Lobes([disney_diffuse, disney_specular]) / "
                            "principled)",
              "two calls": "the material as two BRDF.eval calls, added"}
    for c in cases:
        med = {k: 1e9 * statistics.median(v) for k, v in times[c].items()}
        base = med["C batch"]
        print(f"| {labels[c]} | " + " | ".join(
            "-" if k not in med else
            f"{med[k]:.2f}" + ("" if k == "C batch" else f" ({med[k] / base:.2f}x)")
            for k in cols) + " |")
        spread = max((max(v) - min(v)) / statistics.median(v) for v in times[c].values())
        print(f"<!-- {c}: largest spread (max - min over median) {100 * spread:.0f} % -->")
    print()
    print(f"GGX agreement (f_r, every channel, {rel.size} values above 1e-6): median relative "
          f"difference {np.median(rel):.2g}, 99.9th percentile {np.quantile(rel, 0.999):.2g}")


if __name__ == "__main__":
    main()
