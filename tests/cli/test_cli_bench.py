#!/usr/bin/env python3
"""test_cli_bench.py - `abrdf bench` (docs/BENCHMARKS.md): the quick run's JSON lists every
model of `abrdf models --json` with finite, positive cost ratios on both paths; the
accuracy columns are where the references say; the Pareto plot is well-formed SVG; the
renderer comparison reports its four variants. No timing thresholds: only structure,
finiteness and values that do not depend on the machine's speed.

    python3 test_cli_bench.py PATH/TO/abrdf        (CTest passes the built binary)
"""
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET

ABRDF = None
COST_OF = None  # build/bin/cost_of: one model's cost at given parameters

APPROX = ["f2", "f4", "f8", "f16", "fs", "fkv", "fkub"]
TABLE5 = ["f_phe", "f_be", "f_2e", "f_16e", "f_ge", "f_ctphe", "f_ct2e", "f_ct16e"]


def run(*args, timeout=300):
    p = subprocess.run([ABRDF] + [str(a) for a in args], stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, universal_newlines=True, timeout=timeout)
    return p.returncode, p.stdout, p.stderr


class QuickBench(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.svg = os.path.join(cls.tmp.name, "pareto.svg")
        rc, out, err = run("bench", "--quick", "--json", "--plot", cls.svg)
        if rc != 0:
            raise AssertionError("abrdf bench --quick --json failed: " + err)
        cls.data = json.loads(out)
        rc, out, _ = run("models", "--json")
        cls.models = [m["name"] for m in json.loads(out)["models"]]

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def row(self, name):
        return next(r for r in self.data["models"] if r["name"] == name)

    def test_every_model_once(self):
        names = [r["name"] for r in self.data["models"]]
        self.assertEqual(sorted(names), sorted(self.models))
        self.assertEqual(len(names), len(set(names)))

    def test_ratios_finite_and_positive(self):
        self.assertTrue(math.isfinite(self.data["unit_ns"]) and self.data["unit_ns"] > 0)
        for r in self.data["models"]:
            for k in ("float_ratio", "double_ratio", "prepared_ratio", "prepared_unit_ratio",
                      "prepared_float_ratio", "float_speedup"):
                v = r[k]
                self.assertTrue(isinstance(v, (int, float)) and math.isfinite(v) and v > 0,
                                "%s %s = %r" % (r["name"], k, v))
            self.assertAlmostEqual(r["float_ratio"] * r["float_speedup"], 1.0, places=4)
            # disney_specular inlined (abrdf_inline.h); no other model has an inline form
            if r["name"] == "disney_specular":
                self.assertTrue(math.isfinite(r["inline_ratio"]) and r["inline_ratio"] > 0)
            else:
                self.assertIsNone(r["inline_ratio"], r["name"])
            if r["sweep"] is not None:
                s = r["sweep"]
                self.assertIn(s["param"], ("n", "r"))
                self.assertEqual(len(s["values"]), len(s["float_ratio"]))
                self.assertEqual(len(s["values"]), len(s["double_ratio"]))
                for v in s["float_ratio"] + s["double_ratio"]:
                    self.assertTrue(math.isfinite(v) and v > 0, r["name"])

    def test_hair_per_evaluation_and_per_light(self):
        # huang's lights of one view share its paths through the fibre: a light costs less
        # when four share a view than alone (no timing threshold: only that both are measured)
        h = self.data["huang_shared_view"]
        self.assertEqual(h["lights"], 4)
        for k in ("ns_per_eval", "ns_per_light"):
            self.assertTrue(math.isfinite(h[k]) and h[k] > 0, "%s = %r" % (k, h[k]))

    def test_sweeps_where_cost_may_depend_on_a_parameter(self):
        self.assertEqual(self.row("blinn_phong")["sweep"]["param"], "n")
        self.assertEqual(self.row("disney_specular")["sweep"]["param"], "r")
        self.assertIsNone(self.row("lambert")["sweep"])

    def test_accuracy_columns(self):
        for name in APPROX:
            r = self.row(name)
            self.assertEqual(r["reference"], "blinn_phong")
            self.assertTrue(math.isfinite(r["robot_nmse"]) and r["robot_nmse"] > 0, name)
            self.assertTrue(r["table2_max_rel_pct"] > 0 and r["table3_max_abs"] > 0, name)
        for name in TABLE5 + ["cook_torrance"]:
            r = self.row(name)
            self.assertEqual(r["reference"], "disney_specular")
            self.assertTrue(math.isfinite(r["robot_nmse"]) and r["robot_nmse"] > 0, name)
            self.assertIsNone(r["table2_max_rel_pct"])
        for name in ("blinn_phong", "disney_specular", "disney_diffuse"):
            self.assertEqual(self.row(name)["robot_nmse"], 0)
        self.assertIsNone(self.row("huang")["robot_nmse"])
        # The Table-2/3 errors are the library's (abrdf tables 2 computes the same).
        self.assertLess(self.row("f16")["table3_max_abs"], self.row("f2")["table3_max_abs"])

    def test_plot_is_svg_with_a_point_per_model_with_an_error(self):
        root = ET.parse(self.svg).getroot()
        self.assertTrue(root.tag.endswith("svg"))
        texts = [t.text for t in root.iter() if t.tag.endswith("text")]
        with_error = [r["name"] for r in self.data["models"]
                      if r["robot_nmse"] is not None and r["robot_nmse"] > 0]
        for name in with_error:
            self.assertIn(name, texts)
        circles = [c for c in root.iter() if c.tag.endswith("circle")]
        self.assertEqual(len(circles), len(with_error) + 3)  # + the legend's three


class RenderBench(unittest.TestCase):
    def test_four_variants(self):
        rc, out, err = run("bench", "--render", "--quick", "--json")
        self.assertEqual(rc, 0, err)
        d = json.loads(out)
        names = [v["name"] for v in d["variants"]]
        self.assertEqual(names, ["full_disney", "adaptive_photoreal", "adaptive_performance",
                                 "performance_exact_bp"])
        ref = d["variants"][0]
        self.assertEqual(ref["time_ratio"], 1)
        self.assertEqual(ref["image_nmse"], 0)
        for v in d["variants"]:
            self.assertTrue(math.isfinite(v["time_ratio"]) and v["time_ratio"] > 0)
            self.assertTrue(math.isfinite(v["image_nmse"]) and v["image_nmse"] >= 0)
            self.assertEqual([m["material"] for m in v["materials"]], ["shell", "joint", "eye"])
        for m in ref["materials"]:
            self.assertEqual(m["models"], "disney_diffuse + disney_specular")
            self.assertEqual(m["nmse"], 0)
        # the exact variant has Blinn-Phong where the performance variant has an approximation
        for perf, exact in zip(d["variants"][2]["materials"], d["variants"][3]["materials"]):
            self.assertNotIn("blinn_phong", perf["models"])
            self.assertIn("blinn_phong", exact["models"])
        split = d["performance_vs_exact_bp"]
        self.assertTrue(math.isfinite(split["image_nmse"]) and split["image_nmse"] > 0)
        self.assertEqual(len(split["materials"]), 3)
        # each lobe's render cost beside its per-eval cost, relative to disney_specular
        lc = d["lobe_costs"]
        self.assertEqual(lc["scene"], "robot16")
        self.assertGreater(lc["lit_pairs"], 0)
        self.assertEqual(lc["lobes"][0]["lobe"], "disney_specular")
        self.assertEqual(lc["lobes"][0]["render_ratio"], 1)
        self.assertEqual(lc["lobes"][0]["eval_ratio"], 1)
        names = [x["lobe"] for x in lc["lobes"]]
        for n in ("f8", "fkub", "blinn_phong", "f_2e"):
            self.assertIn(n, names)
        for x in lc["lobes"]:
            self.assertTrue(math.isfinite(x["eval_ratio"]) and x["eval_ratio"] > 0)
            self.assertTrue(math.isfinite(x["render_ratio"]))
        self.assertTrue(0 <= lc["within_1_5x"] <= len(lc["lobes"]))
        # light sampling: the three estimators per scene and model, each a noisy estimate
        # (NMSE > 0 against the reference); MIS and light sampling of the same image (NMSE
        # well below 1; BRDF sampling alone may miss a small light or the sun: any size)
        ls = d["light_sampling"]
        self.assertGreater(ls["reference_light_samples"], ls["light_samples"])
        self.assertEqual(sorted({r["scene"] for r in ls["rows"]}), ["area", "environment"])
        self.assertEqual(len(ls["rows"]), 8)
        for r in ls["rows"]:
            self.assertEqual([e["name"] for e in r["estimators"]], ["mis", "light", "brdf"])
            self.assertEqual(r["estimators"][0]["nmse_ratio"], 1)
            for e in r["estimators"]:
                self.assertTrue(0 < e["nmse"] < (0.5 if e["name"] != "brdf" else math.inf),
                                (r["scene"], r["model"], e))
                self.assertTrue(math.isfinite(e["seconds"]) and e["seconds"] > 0)
                self.assertTrue(math.isfinite(e["nmse_time_ratio"]))


class BudgetBench(unittest.TestCase):
    def test_against_the_hair_table(self):
        """bench --budget --hair-table-sizes: photoreal renders its hair from the table and
        is every NMSE's reference; each budget predicts the hair against the same table, which
        wins (NMSE exactly 0: the same table rendered); photoreal with huang per call is a
        fifth variant, off the table by the quadrature's error; one table built (the lock)."""
        rc, out, err = run("bench", "--budget", "--quick", "--json", "--hair-table-sizes",
                           "6,3,8,1")
        self.assertEqual(rc, 0, err)
        d = json.loads(out)
        self.assertEqual(d["reference"], "photoreal, huang from its table")
        names = [v["name"] for v in d["variants"]]
        self.assertEqual(names, ["photoreal", "budget none", "budget slight",
                                 "budget noticeable", "photoreal per call"])
        self.assertEqual(d["hair_tables"]["sizes"], [6, 3, 8, 1])
        self.assertEqual((d["hair_tables"]["built"], d["hair_tables"]["read"]), (1, 0))
        for v in d["variants"]:
            self.assertTrue(math.isfinite(v["time_ratio"]) and v["time_ratio"] > 0)
            hair = [m for m in v["materials"] if m["material"] == "hair"]
            self.assertEqual(len(hair), 1)
            self.assertEqual(hair[0]["models"], "huang")
            if v["name"] == "photoreal per call":
                self.assertGreater(hair[0]["nmse"], 0)
                self.assertTrue(all(m["nmse"] == 0 for m in v["materials"] if m is not hair[0]))
            else:
                self.assertEqual(hair[0]["nmse"], 0, v["name"])
        self.assertGreater(d["speedup_slight_per_call"], 0)
        self.assertIn(d["goal"]["met"], (True, False))


class Errors(unittest.TestCase):
    def test_unknown_option(self):
        rc, _, err = run("bench", "--nope")
        self.assertEqual(rc, 2)
        self.assertIn("unknown argument", err)

    def test_hair_table_needs_budget(self):
        rc, _, err = run("bench", "--hair-table")
        self.assertEqual(rc, 2)
        self.assertIn("--hair-table goes with --budget", err)
        self.assertEqual(len(err.strip().splitlines()), 1, err)
        rc, _, err = run("bench", "--budget", "--hair-table-sizes", "6,3,8")
        self.assertEqual(rc, 2)
        self.assertIn("is not NT,NV,NP,SETS", err)

    def test_bad_size(self):
        rc, _, _ = run("bench", "--size", "3")
        self.assertEqual(rc, 2)


class CostOf(unittest.TestCase):
    """cost_of MODEL --set ...: one line with finite, positive costs; bad arguments get one
    line naming what is wrong and exit 2."""

    def cost_of(self, *args):
        p = subprocess.run([COST_OF] + list(args), stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, universal_newlines=True, timeout=120)
        return p.returncode, p.stdout, p.stderr

    def test_a_conductor_stack(self):
        rc, out, err = self.cost_of("weidlich_wilkie", "--reps", "1", "--set", "layer_count=1",
                                    "--set", "layer0_kappa=3")
        self.assertEqual(rc, 0, err)
        m = re.match(r"weidlich_wilkie: float batch (\S+) ns/eval \((\S+) units\), per call "
                     r"\(abrdf_eval_prepared_unit\) (\S+) ns \((\S+) units\), per float call "
                     r"\(abrdf_eval_prepared_float\) (\S+) ns \((\S+) units\); unit .* (\S+) ns, "
                     r"median of 1\n$", out)
        self.assertIsNotNone(m, out)
        for v in m.groups():
            self.assertTrue(math.isfinite(float(v)) and float(v) > 0.0, out)

    def test_bad_arguments(self):
        for args, needle in ((["nope"], "unknown model 'nope'"),
                             (["lambert", "--set", "r=7"], "'r'"),
                             (["weidlich_wilkie", "--set", "layer0_r=7"], "'layer0_r' = 7"),
                             (["lambert", "--reps", "0"], "--reps"),
                             (["lambert", "--fast"], "unknown argument '--fast'"),
                             ([], "usage")):
            rc, out, err = self.cost_of(*args)
            self.assertEqual(rc, 2, args)
            self.assertEqual(out, "", args)
            self.assertEqual(err.count("\n"), 1, err)
            self.assertIn(needle, err)


def load_tests(loader, tests, pattern):
    """Every test case of this file but the classes ABRDF_BENCH_EXCLUDE names (space
    separated; the sanitizer build leaves out BudgetBench, tests/cli/CMakeLists.txt)."""
    exclude = set(os.environ.get("ABRDF_BENCH_EXCLUDE", "").split())
    unknown = exclude - {c.__name__ for c in CASES}
    if unknown:
        raise ValueError("ABRDF_BENCH_EXCLUDE names no test case: %s" % " ".join(sorted(unknown)))
    suite = unittest.TestSuite()
    for case in CASES:
        if case.__name__ not in exclude:
            suite.addTests(loader.loadTestsFromTestCase(case))
    return suite


CASES = [c for c in list(globals().values())
         if isinstance(c, type) and issubclass(c, unittest.TestCase)]

if __name__ == "__main__":
    ABRDF = sys.argv.pop(1)
    COST_OF = sys.argv.pop(1)
    unittest.main()
