#!/usr/bin/env python3
"""Which "highlight zone" reproduces the paper's Table 2? An independent re-computation (pure
Python, no library code) of the maximum relative error of f2, f4, f8, f16 and fs against
Blinn-Phong cos^n for several candidate zone definitions, each scored by the mean and the
largest |computed - published| over the 50 published cells. Also scores the fit level of the
cubic fkub (tools/gen/fit_fkub.c) against the paper's fkub rows of Tables 2 and 3.

    python3 tools/measure/zone_candidates.py [path/to/paper_tables.csv]

docs/TABLES.md quotes its output. Sampling: 1200 points per zone plus the zone ends; the
relative errors of these forms are monotone near the zone end, so this is accurate to
about 0.01 points."""
import math
import os
import sys

NS = [2, 5, 10, 20, 50, 100, 200, 500, 700, 1000]
ROWS = ["f2", "f4", "f8", "f16", "fs"]


def fm(m):
    return lambda n, c: max(0.0, (n / m) * (c - 1.0) + 1.0) ** m


F = {"f2": fm(2), "f4": fm(4), "f8": fm(8), "f16": fm(16), "fs": lambda n, c: c / (n - n * c + c)}


def load(path):
    pub = {}
    for line in open(path):
        if line[0].isdigit():
            t, row, col, val = line.rstrip("\n").split(",", 3)
            try:
                pub[(int(t), row, col)] = float(val)
            except ValueError:
                pass
    return pub


def max_rel(f, n, c0, samples=1200):
    best = 0.0
    for i in range(samples + 1):
        c = c0 + (1.0 - c0) * i / samples
        g = c ** n
        if g <= 0.0:
            return math.inf  # the zone reaches c = 0 where cos^n vanishes
        best = max(best, abs(f(n, c) - g) / g)
    return 100.0 * best


def score(pub, zone):
    diffs = []
    for row in ROWS:
        for n in NS:
            c0 = zone(row, n)
            diffs.append(abs(max_rel(F[row], n, c0) - pub[(2, row, str(n))]))
    return sum(diffs) / len(diffs), max(diffs)


def fkub_fit(n, level, samples=2048):
    """tools/gen/fit_fkub.c's constrained least squares, re-done: f = 1 + t(a + t(b + t d))."""
    x0 = level ** (1.0 / n)
    w = 1.0 - x0
    s11 = s12 = s22 = r1 = r2 = 0.0
    for i in range(samples):
        s = (i + 0.5) / samples
        t = s * w
        p1, p2 = s - s ** 3 * w * w, s * s - s ** 3 * w
        y = (1.0 - t) ** n - 1.0 + t ** 3
        s11 += p1 * p1; s12 += p1 * p2; s22 += p2 * p2; r1 += p1 * y; r2 += p2 * y
    det = s11 * s22 - s12 * s12
    a, b = (r1 * s22 - r2 * s12) / det / w, (s11 * r2 - s12 * r1) / det / (w * w)
    d = -(1.0 + a + b)

    def f(n_, c):
        if c < x0:
            return 0.0
        t = 1.0 - c
        return min(1.0, max(0.0, 1.0 + t * (a + t * (b + t * d))))
    return f


def fkub_score(pub, level):
    d2, d3 = [], []
    for n in NS:
        f = fkub_fit(n, level)
        zc = max(0.5 ** (1.0 / n), math.sqrt(1.0 - 1.0 / n))
        d2.append(abs(max_rel(f, n, zc, 600) - pub[(2, "fkub", str(n))]))
        cs = [i / 3000 for i in range(3001)] + [1 - min(1.0, 64.0 / n) * i / 3000 for i in range(3001)]
        ab = max(abs(f(n, c) - c ** n) for c in cs)
        d3.append(abs(ab - pub[(3, "fkub", str(n))]))
    return sum(d2) / len(d2), sum(d3) / len(d3)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "..", "data", "paper_tables.csv")
    pub = load(path)
    cand = [
        ("cos^n >= 0.5 (half maximum)", lambda r, n: 0.5 ** (1 / n)),
        ("cos^n >= 1/e", lambda r, n: math.exp(-1 / n)),
        ("cos^n >= 0.1", lambda r, n: 0.1 ** (1 / n)),
        ("cos^n >= e^-1/2", lambda r, n: math.exp(-0.5 / n)),
        ("n (1 - c) <= 1/2", lambda r, n: 1 - 0.5 / n),
        ("theta_h <= 10 deg", lambda r, n: math.cos(math.radians(10))),
        ("theta_h <= 30 deg", lambda r, n: math.cos(math.radians(30))),
        ("theta_h <= 1/sqrt(n) rad", lambda r, n: math.cos(min(math.pi / 2, 1 / math.sqrt(n)))),
        ("before the approximation's zero (c >= 1 - m/n)",
         lambda r, n: max(0.0, 1 - int(r[1:]) / n) if r != "fs" else 0.0),
        ("CHOSEN: concave core, sin^2 theta_h <= 1/n, within cos^n >= 1/2",
         lambda r, n: max(0.5 ** (1 / n), math.sqrt(1 - 1 / n))),
    ]
    print("Table 2, f2 f4 f8 f16 fs (50 cells): mean and largest |computed - published| (points)")
    for name, zone in cand:
        mad, worst = score(pub, zone)
        print(f"  {name:66s} {mad:9.4g} {worst:9.4g}")
    print("fkub fit level L (fit on cos^n >= L, zero below): mean |diff| Table 2 (points), Table 3")
    for level in (0.01, 0.03, 0.05, 0.08, 0.1, 0.12, 0.15, 0.2):
        m2, m3 = fkub_score(pub, level)
        print(f"  L = {level:<5g} {m2:8.3f} {m3:8.4f}")


if __name__ == "__main__":
    main()
