"""Fitting measured data through the command (docs/MEASURED.md, "Fitting measured data"):
`abrdf fit --to FILE MODEL` recovers the parameters of the model a file was tabulated from,
`--all` fits every general candidate with finite errors, sorted by predicted NMSE, and
`abrdf advise --measured FILE --budget slight` picks the cheapest candidate within the budget;
bad files and arguments are refused in one line, with nothing on stdout.

Files are written by `abrdf tabulate` on a reduced grid (45 x 45 x 90) to keep the run short,
and on MERL's grid for one case. Run by CTest with ABRDF (the command) in the environment."""
import json
import math
import os
import subprocess
import tempfile
import unittest

from clitest import checked_stderr

ABRDF = os.environ["ABRDF"]
SLIGHT = 2.5e-4
COST_TIE = 0.15  # abrdf_select_budget's: costs within 15 % of the cheapest count as equal
GENERAL_SPECULAR = {"disney_specular", "cook_torrance", "blinn_phong", "phong", "f2", "f4", "f8",
                    "f16", "fs", "fkv", "fkub", "f_phe", "f_be", "f_2e", "f_16e", "f_ge",
                    "f_ctphe", "f_ct2e", "f_ct16e"}


def run(*args, timeout=300):
    p = subprocess.run([ABRDF, *args], capture_output=True, timeout=timeout)
    return p.returncode, p.stdout.decode(), checked_stderr(p)


def finite(*values):
    return all(v is not None and math.isfinite(v) for v in values)


class MeasuredFit(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        d = cls.tmp.name
        cls.ds = os.path.join(d, "ds.binary")  # MERL's grid
        cls.ds45 = os.path.join(d, "ds45.binary")
        cls.ct45 = os.path.join(d, "ct45.binary")
        for path, model, grid in ((cls.ds, "disney_specular", None),
                                  (cls.ds45, "disney_specular", "45,45,90"),
                                  (cls.ct45, "cook_torrance", "45,45,90")):
            args = ["tabulate", model, "--set", "r=0.3", "-o", path]
            if grid:
                args += ["--grid", grid]
            rc, _, err = run(*args)
            assert rc == 0, err

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def fit(self, *args):
        rc, out, err = run("fit", *args, "--json")
        self.assertEqual(rc, 0, err)
        return json.loads(out)

    def fails(self, rc_expected, args, *needles):
        rc, out, err = run(*args)
        self.assertEqual(rc, rc_expected, (args, err))
        self.assertEqual(out, "")
        self.assertEqual(err.count("\n"), 1, err)
        for n in needles:
            self.assertIn(n, err)

    def test_fit_recovers_r_on_merl_grid(self):
        j = self.fit("--to", self.ds, "disney_specular")
        self.assertEqual((j["diffuse"], j["specular"]), ("lambert", "disney_specular"))
        p = j["params"]
        self.assertLess(abs(p["r"] - 0.3), 0.01, p)
        self.assertLess(abs(p["ks"][0] - 1.0), 0.02, p)
        self.assertLess(abs(p["f0"][0] - 0.04), 0.005, p)
        self.assertLess(p["kd"][0], 0.01, p)
        self.assertTrue(finite(j["rel_l2"], j["rel_log"], j["rel_cbrt"], j["nmse_pred"]))
        self.assertLess(j["nmse_pred"], SLIGHT)
        self.assertGreater(j["cost"], 0.0)
        self.assertEqual(j["reference"]["grid"], [90, 90, 180])

    def test_fit_recovers_r_reduced_grid(self):
        j = self.fit("--to", self.ct45, "cook_torrance", "--diffuse", "none")
        self.assertIsNone(j["diffuse"])
        self.assertLess(abs(j["params"]["r"] - 0.3), 0.02, j["params"])
        text = run("fit", "--to", self.ct45, "cook_torrance")[1]
        for line in ("candidate   lambert + cook_torrance", "rel L2", "rel log", "rel cbrt",
                     "image NMSE", "cost", "fit time"):
            self.assertIn(line, text)

    def test_all_lists_every_candidate(self):
        j = self.fit("--to", self.ds45, "--all")
        c = j["candidates"]
        self.assertEqual({x["specular"] for x in c}, GENERAL_SPECULAR)
        self.assertEqual(len(c), len(GENERAL_SPECULAR))
        for x in c:
            self.assertIn(x["diffuse"], ("lambert", "disney_diffuse", "oren_nayar"))
            self.assertTrue(finite(x["rel_l2"], x["rel_log"], x["rel_cbrt"], x["nmse_pred"],
                                   x["cost"]), x)
            self.assertEqual(set(x["diffuse_tried"]), {"lambert", "disney_diffuse", "oren_nayar"})
        nmse = [x["nmse_pred"] for x in c]
        self.assertEqual(nmse, sorted(nmse))
        self.assertEqual(c[0]["specular"], "disney_specular")
        rc, out, err = run("fit", "--to", self.ds45, "--all", "--resolution", "1")
        self.assertEqual(rc, 0, err)
        for name in GENERAL_SPECULAR:
            self.assertIn(" + %s " % name, out)

    def test_advise_measured_within_slight(self):
        rc, out, err = run("advise", "--measured", self.ds45, "--budget", "slight", "--json")
        self.assertEqual(rc, 0, err)
        j = json.loads(out)
        self.assertEqual(j["reference"]["model"], "measured")
        self.assertEqual(j["budget"]["class"], "slight")
        self.assertLess(j["error"]["nmse_pred"], SLIGHT)
        within = [x for x in j["candidates"] if x["within"]]
        self.assertTrue(within)
        cheapest = min(x["cost"] for x in within)
        self.assertLessEqual(j["cost"]["total"], cheapest * (1 + COST_TIE))
        self.assertIn(j["specular"], GENERAL_SPECULAR | {"lambert", "disney_diffuse",
                                                         "oren_nayar"})
        # proved on the image: the renderer's sphere with the table and with the choice, within
        # the budget and within a factor 3 of the prediction (or both below 1e-5)
        self.assertGreater(j["reference"]["cost"], 0)
        r = j["rendered"]["nmse"]
        self.assertLess(r, SLIGHT)
        p = j["error"]["nmse_pred"]
        self.assertTrue(max(r, p) < 1e-5 or p / 3 <= r <= 3 * p, (r, p))

    def test_bad_files_and_arguments(self):
        d = self.tmp.name
        cut = os.path.join(d, "cut.binary")
        with open(self.ds45, "rb") as f, open(cut, "wb") as g:
            g.write(f.read(100))
        self.fails(1, ["fit", "--to", os.path.join(d, "nope.binary"), "f2"], "nope.binary")
        self.fails(1, ["fit", "--to", cut, "--all"], "truncated")
        self.fails(2, ["fit", "--to", os.path.join(d, "x.txt"), "f2"], ".binary")
        self.fails(2, ["fit", "--to", self.ds45, "nosuch"], "unknown model")
        self.fails(2, ["fit", "--to", self.ds45, "measured"])
        self.fails(2, ["fit", "--to", self.ds45, "--all", "f2"], "--all")
        self.fails(2, ["fit", "--to", self.ds45], "MODEL")
        self.fails(2, ["fit", "--to", self.ds45, "f2", "--diffuse", "f4"], "--diffuse")
        self.fails(2, ["fit", "--to", self.ds45, "f2", "--metric", "l3"], "--metric")
        self.fails(2, ["advise", "--measured", self.ds45], "--budget")
        self.fails(2, ["advise", "--measured", self.ds45, "--budget", "2"], "budget")
        self.fails(2, ["advise", "gold", "--measured", self.ds45, "--budget", "slight"])
        self.fails(1, ["advise", "--measured", cut, "--budget", "slight"], "truncated")


if __name__ == "__main__":
    unittest.main()
