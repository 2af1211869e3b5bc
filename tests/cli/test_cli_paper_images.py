"""`abrdf tables 6|7` (the paper's image experiment, tools/paper/paper_images.c): the table's shape,
the published column, and one cell recomputed independently with `abrdf render` on a scene
file written here plus `abrdf compare`. Small images keep it quick.
Usage: test_cli_paper_images.py PATH/TO/abrdf SOURCE_DIR"""
import csv
import io
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest

ABRDF = None
SOURCE = None
SIZE = ["--width", "40", "--height", "32", "--threads", "2"]
PAPER_N = [1, 5, 10, 20, 40, 60, 80, 100, 200, 300, 400, 500, 600, 700, 800, 900, 950, 1000]
ALPHA_G = ["1.0", "0.9", "0.8", "0.7", "0.6", "0.5", "0.4", "0.3", "0.2", "0.1", "0.05", "0.01",
           "0.005", "0.001", "0.0005", "0.0001", "0.00005", "0.00001"]


def run(*args, code=0):
    p = subprocess.run([ABRDF, *args], capture_output=True, text=True)
    assert "Sanitizer" not in p.stderr, p.stderr
    if p.returncode != code:
        raise AssertionError(f"abrdf {' '.join(args)}: exit {p.returncode}, want {code}\n{p.stderr}")
    return p


class ImageTablesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.rows = {}
        for t in ("6", "7"):
            out = run("tables", t, "--csv", *SIZE).stdout
            cls.rows[t] = list(csv.DictReader(io.StringIO(out)))

    def table(self, t, kind):
        return {r["alpha_g"]: r for r in self.rows[t] if r["kind"] == kind}

    def test_shape_and_search_range(self):
        for t, models in (("6", ["f_phe", "f_be", "f_2e", "f_16e"]),
                          ("7", ["f_ge", "f_ctphe", "f_ct2e", "f_ct16e"])):
            comp = self.table(t, "computed")
            self.assertEqual(list(comp), ALPHA_G)
            for a, row in comp.items():
                self.assertAlmostEqual(float(row["alpha"]), math.sqrt(float(a)), places=4)
                for m in models:
                    v = float(row[m])
                    self.assertTrue(0 <= v < 1, f"table {t} {m} at {a}: {v}")
                    self.assertIn(float(row[m + "_n"]), PAPER_N)

    def test_published_column_is_the_data_file(self):
        pub = self.table("6", "published")
        self.assertEqual(float(pub["0.00001"]["f_2e"]), 0.000002)
        self.assertEqual(float(pub["1.0"]["f_phe"]), 0.0554)
        pub7 = self.table("7", "published")
        self.assertEqual(float(pub7["0.2"]["f_ct16e"]), 0.0176)

    def test_trend_smooth_surfaces_agree_better(self):
        # The paper's finding: at alpha_g <= 0.001 (alpha <= 0.03) f_2e is far closer to the
        # GGX lobe than on rough surfaces.
        for t, m in (("6", "f_2e"), ("7", "f_ct2e")):
            comp = self.table(t, "computed")
            rough = max(float(comp[a][m]) for a in ALPHA_G[:10])
            smooth = max(float(comp[a][m]) for a in ALPHA_G[13:])
            self.assertLess(smooth, rough / 10)
            self.assertLess(smooth, 1e-4)  # Table 8: no visible difference

    def test_one_cell_recomputed_with_render_and_compare(self):
        # Reference and best candidate of one cell rendered from a scene file: the robot of
        # scenes/robot.scene with its materials replaced and no ambient light.
        comp = self.table("6", "computed")
        a, m = "0.1", "f_2e"
        n = comp[a][m + "_n"]
        with open(os.path.join(SOURCE, "scenes", "robot.scene")) as f:
            robot = [l for l in f.read().splitlines() if not l.startswith(("material", "ambient"))]
        r = repr(math.sqrt(float(a)))
        mats = {
            "ref": f"diffuse=lambert specular=disney_specular kd=0.5 ks=1 f0=0.04 r={r}",
            "cand": f"diffuse=lambert specular={m} kd=0.5 ks=0.04 n={n}",
        }
        with tempfile.TemporaryDirectory() as tmp:
            exr = {}
            for key, mat in mats.items():
                scene = os.path.join(tmp, key + ".scene")
                with open(scene, "w") as f:
                    for name in ("shell", "joint", "eye"):
                        f.write(f"material {name} {mat}\n")
                    f.write("\n".join(robot) + "\n")
                exr[key] = os.path.join(tmp, key + ".exr")
                # The double path, as `abrdf tables 6|7` renders (paper_images.c).
                run("render", scene, "-o", exr[key], "--precision", "double", "--width", "40",
                    "--height", "32", "--spp", "1", "--no-preview")
            res = json.loads(run("compare", exr["ref"], exr["cand"], "--json", "--fail", "1").stdout)
        self.assertAlmostEqual(res["nmse"], float(comp[a][m]), delta=1e-9 * res["nmse"])

    def test_markdown_and_thresholds(self):
        out = run("tables", "7", *SIZE).stdout
        self.assertIn("## Table 7", out)
        self.assertIn("| 0.00001 |", out)
        self.assertRegex(out, r"### f_ct2e: largest alpha_g")
        self.assertRegex(out, r"\| no visible difference \(NMSE < 1e-4\) \| [0-9.e-]+ \(")
        self.assertIn("Same class in", out)

    def test_option_errors(self):
        self.assertIn("not a square", run("tables", "6", "--spp", "3", code=2).stderr)
        self.assertIn("[0, 1]", run("tables", "6", "--kd", "2", code=2).stderr)
        self.assertIn("--width", run("tables", "6", "--width", "0", code=2).stderr)
        err = run("tables", "6", "--scene", "/nonexistent/robot.scene", *SIZE, code=1).stderr
        self.assertIn("robot.scene", err)


if __name__ == "__main__":
    ABRDF = sys.argv.pop(1)
    SOURCE = sys.argv.pop(1)
    unittest.main(verbosity=2)
