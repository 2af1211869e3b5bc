#!/usr/bin/env python3
"""POV-Ray's Abrdf_Select (povray_macros/abrdf_select.inc) against `abrdf advise`: the same
diffuse and specular model and the same exponent n for every case below, evaluated by the
real povray binary. Also Abrdf_Approx_Error against the C error analysis (tables 2-3).

    test_pov_select.py ABRDF POVRAY INCLUDE_DIR WORK_DIR
"""
import json
import os
import subprocess
import sys
import unittest

from pov_parse import parse_run

ABRDF, POVRAY, INC, WORK = sys.argv[1:5]
del sys.argv[1:5]

# (goal, surface, n, r, anisotropy, max_rel_pct, max_abs); None = not given / no limit.
CASES = [
    ("performance", "general", 300, None, 0, 2, 0.05),
    ("performance", "general", 300, None, 0, 0.5, None),
    ("performance", "general", None, 0.3, 0, 2, 0.05),
    ("photoreal", "general", None, 0.02, 0, None, None),
    ("photoreal", "general", None, 0.03, 0, None, None),
    ("photoreal", "general", None, 0.031, 0, None, None),
    ("photoreal", "general", 300, None, 0, None, None),
    ("photoreal", "general", 200, 0.01, 0, None, None),
    ("photoreal", "general", None, 0.2, 0, None, None),
    ("photoreal", "general", None, 0.2, 0.5, None, None),
    ("photoreal", "cloth_rough", None, 0.5, 0, None, None),
    ("photoreal", "cloth_shiny", None, 0.5, 0, None, None),
    ("photoreal", "hair", None, 0.5, 0, None, None),
    ("photoreal", "layered_plastic", None, 0.1, 0, None, None),
    ("photoreal", "layered_plate", None, 0.1, 0, None, None),
    ("photoreal", "layered_metal", None, 0.1, 0, None, None),
]
ERRORS = [("fs", 20), ("fkub", 100)]


def sdl_num(v):
    return "-1" if v is None else repr(float(v))


def run_pov():
    lines = ['#version 3.7;', 'global_settings { assumed_gamma 1 }',
             '#include "abrdf.inc"', '#include "abrdf_select.inc"']
    for i, (goal, surf, n, r, an, rel, ab) in enumerate(CASES):
        args = '"%s", "%s", %s, %s, %s' % (goal, surf, sdl_num(n), sdl_num(r), repr(float(an)))
        lines.append('#declare S = Abrdf_Select(%s, %s, %s);' % (args, sdl_num(rel), sdl_num(ab)))
        lines.append('#declare Nu = Abrdf_Select_N("%s", "%s", %s, %s);' % (goal, surf, sdl_num(n), sdl_num(r)))
        lines.append('#debug concat("CASE %d ", S[0], "|", S[1], "|", str(Nu, 0, 12), "\\n")' % i)
    for i, (m, n) in enumerate(ERRORS):
        lines.append('#declare E = Abrdf_Approx_Error("%s", %s);' % (m, repr(float(n))))
        lines.append('#debug concat("ERR %d ", str(E[0], 0, 15), " ", str(E[1], 0, 15), "\\n")' % i)
    out = parse_run(POVRAY, INC, WORK, "select_check.pov", lines)
    got = {}
    for line in out.splitlines():
        # POV-Ray wraps long console lines; the markers start a line
        if line.startswith("CASE ") or line.startswith("ERR "):
            kind, idx, rest = line.split(" ", 2)
            got[(kind, int(idx))] = rest
    return got, out


class PovSelect(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.got, cls.log = run_pov()

    def test_select_matches_advise(self):
        for i, (goal, surf, n, r, an, rel, ab) in enumerate(CASES):
            with self.subTest(case=CASES[i]):
                cmd = [ABRDF, "advise", "--goal", goal, "--type", surf, "--anisotropy", str(an), "--json"]
                if n is not None:
                    cmd += ["--n", repr(n)]
                if r is not None:
                    cmd += ["--r", repr(r)]
                if goal == "performance":
                    cmd += ["--max-rel-error", "none" if rel is None else repr(rel),
                            "--max-abs-error", "none" if ab is None else repr(ab)]
                ref = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
                self.assertIn(("CASE", i), self.got, self.log[-3000:])
                diffuse, specular, nu = self.got[("CASE", i)].split("|")
                self.assertEqual(diffuse, ref["diffuse"] or "")
                self.assertEqual(specular, ref["specular"])
                self.assertAlmostEqual(float(nu) / ref["params"]["n"], 1.0, places=9)

    def test_approx_error_matches_tables(self):
        for i, (m, n) in enumerate(ERRORS):
            with self.subTest(model=m, n=n):
                out = subprocess.run([ABRDF, "advise", "--n", repr(n), "--goal", "performance",
                                      "--max-rel-error", "none", "--max-abs-error", "none", "--json"],
                                     check=True, capture_output=True, text=True).stdout
                ref = None
                for step in json.loads(out)["trace"]:
                    if step.get("model") == m and step.get("step") == "candidate":
                        ref = (step["value"], step["value2"])
                self.assertIsNotNone(ref, out[:2000])
                self.assertIn(("ERR", i), self.got, self.log[-3000:])
                rel, ab = (float(v) for v in self.got[("ERR", i)].split())
                self.assertAlmostEqual(rel / ref[0], 1.0, places=7)
                self.assertAlmostEqual(ab / ref[1], 1.0, places=7)


if __name__ == "__main__":
    unittest.main(verbosity=2)
