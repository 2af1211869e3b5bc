#!/usr/bin/env python3
"""POV-Ray's abrdf_belcour (povray_macros/abrdf_belcour.inc) against `abrdf eval belcour` on
layer stacks built from the hard cases of the stability grid (docs/SPECIAL_CLOTH_LAYERED.md):
every depth 1-4, eta in {0.25, 0.7, 1, 1.5, 4}, kappa in {0, 1e-3, 10}, r in {0, 1e-3, 0.5,
1}, sigma_a in {0, 1, 1e4} per channel, depth in {0, 1e-3, 100}, at generic, grazing,
normal and mirror direction pairs. Abrdf_Eval runs at parse time in the real povray binary
(double precision, printed to 17 digits), so this checks the twin's guards and clamps where
the grid of pov_models does not reach.

    test_pov_belcour.py ABRDF POVRAY INCLUDE_DIR WORK_DIR
"""
import json
import math
import os
import random
import subprocess
import sys
import unittest

ABRDF, POVRAY, INC, WORK = sys.argv[1:5]
del sys.argv[1:5]

ETA = [0.25, 0.7, 1, 1.5, 4]
KAPPA = [0, 1e-3, 10]
R = [0, 1e-3, 0.5, 1]
SIGMA = [0, 1, 1e4]
DEPTH = [0, 1e-3, 100]
DIRS = [((-0.3, 0.1, 1), (0.4, -0.2, 0.9)), ((0.999, 0, 0.02), (-0.999, 0.01, 0.03)),
        ((0, 0, 1), (0, 0, 1)), ((0.7, 0.1, 0.2), (0.1, 0.6, 0.3)), ((0.2, 0, 1), (-0.19, 0, 1))]
STACKS = 40
REL = 1e-9  # measured worst: 1.9e-12


def stacks():
    rnd = random.Random(3)
    out = []
    for _ in range(STACKS):
        layers = [(rnd.choice(ETA), rnd.choice(KAPPA), rnd.choice(R),
                   (rnd.choice(SIGMA), rnd.choice(SIGMA), rnd.choice(SIGMA)), rnd.choice(DEPTH))
                  for _ in range(4)]
        out.append((rnd.randint(1, 4), layers))
    return out


def run_pov(cases):
    lines = ['#version 3.7;', 'global_settings { assumed_gamma 1 }', '#include "abrdf.inc"',
             # x as mantissa and decimal exponent, so that tiny values keep their digits
             '#macro S(X) #if (X > 0) #local E = floor(log(X));'
             ' #local Q = concat(str(X / pow(10, E), 0, 16), "e", str(E, 0, 0));'
             ' #else #local Q = "0"; #end Q #end']
    for i, (count, layers) in enumerate(cases):
        lines.append('#declare D = Abrdf_Default(ABRDF_ID_BELCOUR);')
        lines.append('#declare D[ABRDF_SLOT_LAYER_COUNT] = %d;' % count)
        for k, (eta, kappa, r, sig, depth) in enumerate(layers):
            for j, v in enumerate((eta, kappa, r, sig[0], sig[1], sig[2], depth)):
                lines.append('#declare D[ABRDF_SLOT_LAYER0_ETA + %d] = %r;' % (7 * k + j, float(v)))
        lines.append('Abrdf__Check(D, "test_pov_belcour")')
        for j, (wi, wo) in enumerate(DIRS):
            lines.append('#declare V = Abrdf_Eval(D, <%r, %r, %r>, <%r, %r, %r>);' % (*wi, *wo))
            lines.append('#debug concat("F %d %d ", S(V.x), " ", S(V.y), " ", S(V.z), "\\n")' % (i, j))
    path = os.path.join(WORK, "belcour_check.pov")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    p = subprocess.run([POVRAY, "-D", "+I" + path, "+L" + INC, "-F", "+W1", "+H1"],
                       capture_output=True, text=True)
    out = p.stdout + p.stderr
    got = {}
    for line in out.splitlines():
        if line.startswith("F "):
            _, i, j, rest = line.split(" ", 3)
            got[(int(i), int(j))] = [float(v) for v in rest.split()]
    return got, out


def c_eval(count, layers, wi, wo):
    cmd = [ABRDF, "eval", "belcour", "--wi", "%r,%r,%r" % wi, "--wo", "%r,%r,%r" % wo, "--json",
           "--set", "layer_count=%d" % count]
    for k, (eta, kappa, r, sig, depth) in enumerate(layers):
        cmd += ["--set", "layer%d_eta=%r" % (k, eta), "--set", "layer%d_kappa=%r" % (k, kappa),
                "--set", "layer%d_r=%r" % (k, r), "--set", "layer%d_sigma_a=%r,%r,%r" % (k, *sig),
                "--set", "layer%d_depth=%r" % (k, depth)]
    return json.loads(subprocess.run(cmd, capture_output=True, text=True, check=True).stdout)["f_r"]


class PovBelcour(unittest.TestCase):
    def test_hard_stacks_match_c(self):
        cases = stacks()
        got, log = run_pov(cases)
        self.assertEqual(len(got), len(cases) * len(DIRS), "povray output:\n" + log[-3000:])
        worst, nonzero = 0.0, 0
        for i, (count, layers) in enumerate(cases):
            for j, (wi, wo) in enumerate(DIRS):
                ref = c_eval(count, layers, wi, wo)
                for a, b in zip(ref, got[(i, j)]):
                    self.assertTrue(math.isfinite(b) and b >= 0, (i, j, b))
                    big = max(abs(a), abs(b))
                    if big > 0:
                        nonzero += 1
                        worst = max(worst, abs(a - b) / big)
                        self.assertLess(abs(a - b) / big, REL, (count, layers, wi, wo, ref, got[(i, j)]))
        # most values are not zero: the comparison is not vacuous
        self.assertGreater(nonzero, len(cases) * len(DIRS) * 3 // 2)
        print("\n%d stacks x %d direction pairs: %d nonzero values, worst relative difference %.2e"
              % (len(cases), len(DIRS), nonzero, worst))


if __name__ == "__main__":
    unittest.main()
