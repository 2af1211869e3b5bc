#!/usr/bin/env python3
"""POV-Ray's abrdf_belcour (povray_macros/abrdf_belcour.inc) against `abrdf slice belcour`
on layer stacks built from the hard cases of the stability grid (docs/MODELS.md, "Hard
cases"): every depth 1-4, eta in {0.25, 0.7, 1, 1.5, 4}, kappa in
{0, 1e-3, 10}, r in {0, 1e-3, 0.5, 1}, sigma_a in {0, 1, 1e4} per channel, depth in {0,
1e-3, 100}. Each stack is compared on one slice of the plane of incidence (theta_o from -90
to 90 degrees, so grazing, normal, mirror and back-scattering directions; theta_i varies
from stack to stack). povray evaluates Abrdf_Fn at parse time (double precision, printed to
17 digits), so this checks the twin's guards and clamps where the grid of pov_models does
not reach. One `abrdf` process per stack keeps the test short in the sanitizer build.

    test_pov_belcour.py ABRDF POVRAY INCLUDE_DIR WORK_DIR
"""
import json
import math
import os
import random
import subprocess
import sys
import unittest

from pov_parse import parse_run

ABRDF, POVRAY, INC, WORK = sys.argv[1:5]
del sys.argv[1:5]

ETA = [0.25, 0.7, 1, 1.5, 4]
KAPPA = [0, 1e-3, 10]
R = [0, 1e-3, 0.5, 1]
SIGMA = [0, 1, 1e4]
DEPTH = [0, 1e-3, 100]
THETA_I = [0, 30, 60, 80, 89]
STEPS = 36  # theta_o in 5 degree steps
STACKS = 24
REL = 1e-9  # measured worst: 1.9e-12


def stacks():
    rnd = random.Random(3)
    out = []
    for i in range(STACKS):
        layers = [(rnd.choice(ETA), rnd.choice(KAPPA), rnd.choice(R),
                   (rnd.choice(SIGMA), rnd.choice(SIGMA), rnd.choice(SIGMA)), rnd.choice(DEPTH))
                  for _ in range(4)]
        out.append((rnd.randint(1, 4), layers, THETA_I[i % len(THETA_I)]))
    return out


def directions(theta_i):
    """wi and the wo of each row, as cmd_slice.c computes them."""
    deg = 3.14159265358979323846 / 180.0
    wi = (-math.sin(theta_i * deg), 0.0, math.cos(theta_i * deg))
    wos = []
    for s in range(STEPS + 1):
        th = -90.0 + 180.0 * s / STEPS
        wos.append((math.sin(th * deg), 0.0, math.cos(th * deg)))
    return wi, wos


def run_pov(cases):
    lines = ['#version 3.7;', 'global_settings { assumed_gamma 1 }', '#include "abrdf.inc"',
             # x as mantissa and decimal exponent, so that tiny values keep their digits
             '#macro S(X) #if (X > 0) #local E = floor(log(X));'
             ' #local Q = concat(str(X / pow(10, E), 0, 16), "e", str(E, 0, 0));'
             ' #else #local Q = "0"; #end Q #end']
    for i, (count, layers, theta_i) in enumerate(cases):
        lines.append('#declare D = Abrdf_Default(ABRDF_ID_BELCOUR);')
        lines.append('#declare D[ABRDF_SLOT_LAYER_COUNT] = %d;' % count)
        for k, (eta, kappa, r, sig, depth) in enumerate(layers):
            for j, v in enumerate((eta, kappa, r, sig[0], sig[1], sig[2], depth)):
                lines.append('#declare D[ABRDF_SLOT_LAYER0_ETA + %d] = %r;' % (7 * k + j, float(v)))
        lines.append('Abrdf__Check(D, "test_pov_belcour")')
        lines.append('#ifdef(Fr) #undef Fr #undef Fg #undef Fb #end')
        lines.append('#declare Fr = Abrdf_Fn(D, 0); #declare Fg = Abrdf_Fn(D, 1); #declare Fb = Abrdf_Fn(D, 2);')
        wi, wos = directions(theta_i)
        for j, wo in enumerate(wos):
            a = "%r, %r, %r, %r, %r, %r" % (*wi, *wo)
            lines.append('#debug concat("F %d %d ", S(Fr(%s)), " ", S(Fg(%s)), " ", S(Fb(%s)), "\\n")'
                         % (i, j, a, a, a))
    out = parse_run(POVRAY, INC, WORK, "belcour_check.pov", lines)
    got = {}
    for line in out.splitlines():
        if line.startswith("F "):
            _, i, j, rest = line.split(" ", 3)
            got[(int(i), int(j))] = [float(v) for v in rest.split()]
    return got, out


def c_slice(count, layers, theta_i):
    cmd = [ABRDF, "slice", "belcour", "--theta-i", repr(float(theta_i)), "--steps", str(STEPS), "--csv",
           "--set", "layer_count=%d" % count]
    for k, (eta, kappa, r, sig, depth) in enumerate(layers):
        cmd += ["--set", "layer%d_eta=%r" % (k, eta), "--set", "layer%d_kappa=%r" % (k, kappa),
                "--set", "layer%d_r=%r" % (k, r), "--set", "layer%d_sigma_a=%r,%r,%r" % (k, *sig),
                "--set", "layer%d_depth=%r" % (k, depth)]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    rows = [l.split(",") for l in out.splitlines() if l and not l.startswith("#") and not l.startswith("theta")]
    return [[float(v) for v in r[1:4]] for r in rows]


class PovBelcour(unittest.TestCase):
    def test_hard_stacks_match_c(self):
        cases = stacks()
        got, log = run_pov(cases)
        self.assertEqual(len(got), len(cases) * (STEPS + 1), "povray output:\n" + log[-3000:])
        worst, nonzero = 0.0, 0
        for i, (count, layers, theta_i) in enumerate(cases):
            ref = c_slice(count, layers, theta_i)
            self.assertEqual(len(ref), STEPS + 1)
            for j in range(STEPS + 1):
                for a, b in zip(ref[j], got[(i, j)]):
                    self.assertTrue(math.isfinite(b) and b >= 0, (i, j, b))
                    big = max(abs(a), abs(b))
                    if big > 0:
                        nonzero += 1
                        worst = max(worst, abs(a - b) / big)
                        self.assertLess(abs(a - b) / big, REL,
                                        (count, layers, theta_i, j, ref[j], got[(i, j)]))
        # most values are not zero: the comparison is not vacuous
        self.assertGreater(nonzero, len(cases) * (STEPS + 1) * 3 // 2)
        print("\n%d stacks x %d directions: %d nonzero values, worst relative difference %.2e"
              % (len(cases), STEPS + 1, nonzero, worst))


if __name__ == "__main__":
    unittest.main()
