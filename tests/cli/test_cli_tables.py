"""CLI tests of `abrdf tables 2|3|4|gltf` and `abrdf calibrate` (run by CTest with the path of
the abrdf binary). No timing thresholds: only that the commands run, their CSV parses, the
Markdown has its tables, and a calibration file names every model with a positive cost."""
import csv
import io
import json
import os
import subprocess
import sys
import tempfile
import unittest

ABRDF = None
NS = ["2", "5", "10", "20", "50", "100", "200", "500", "700", "1000"]
TABLE1 = ["f2", "f4", "f8", "f16", "fs", "fkv", "fkub"]


def run(*args, code=0):
    p = subprocess.run([ABRDF, *args], capture_output=True, text=True, timeout=300)
    if p.returncode != code:
        raise AssertionError(f"abrdf {' '.join(args)}: exit {p.returncode} (expected {code})\n"
                             f"stdout: {p.stdout}\nstderr: {p.stderr}")
    return p


def registered_models():
    return [m["name"] for m in json.loads(run("models", "--json").stdout)["models"]]


class ErrorTables(unittest.TestCase):
    def check_csv(self, table):
        rows = list(csv.DictReader(io.StringIO(run("tables", table, "--csv").stdout)))
        self.assertEqual(len(rows), 3 * len(TABLE1))
        self.assertEqual(list(rows[0].keys()), ["model", "kind", *NS, "mad"])
        by = {(r["model"], r["kind"]): r for r in rows}
        for m in TABLE1:
            comp, pub, diff = by[(m, "computed")], by[(m, "published")], by[(m, "difference")]
            for n in NS:
                c, p, d = float(comp[n]), float(pub[n]), float(diff[n])
                self.assertGreaterEqual(c, 0.0)
                self.assertAlmostEqual(c - p, d, delta=2e-4 if table == "2" else 2e-6)
            mad = sum(abs(float(diff[n])) for n in NS) / len(NS)
            self.assertAlmostEqual(float(diff["mad"]), mad, delta=0.01)
            self.assertEqual(comp["mad"], "")
        return by

    def test_table2_csv(self):
        by = self.check_csv("2")
        self.assertEqual(float(by[("f2", "computed")]["2"]), 0.0)  # f2 is exact at n = 2
        self.assertEqual(by[("f16", "published")]["20"], "0.25")

    def test_table3_csv(self):
        by = self.check_csv("3")
        self.assertEqual(float(by[("fs", "published")]["1000"]), 0.2)

    def test_markdown_is_default(self):
        for table in ("2", "3"):
            out = run("tables", table).stdout
            self.assertEqual(out, run("tables", table, "--markdown").stdout)
            self.assertIn(f"## Table {table}", out)
            for heading in ("### computed", "### published", "### difference"):
                self.assertIn(heading, out)
            self.assertIn("| model | 2 | 5 | 10 |", out)
            self.assertIn("| f16 |", out)
            self.assertIn(": met", out)  # the reproduction criterion line


class CostTable(unittest.TestCase):
    def test_table4_measured_now(self):
        rows = list(csv.DictReader(io.StringIO(run("tables", "4", "--csv", "--reps", "1").stdout)))
        by = {r["model"]: r for r in rows}
        for m, cycles in {"f2": 8, "f4": 11, "f8": 14, "f16": 17, "fkub": 17, "fkv": 14, "fs": 15}.items():
            self.assertEqual(float(by[m]["paper_cycles"]), cycles)
            self.assertEqual(float(by[m]["ops_cycles"]), cycles)
            self.assertGreater(float(by[m]["ns_per_eval"]), 0.0)
            self.assertGreater(float(by[m]["vs_powf_blinn_phong"]), 0.0)
        self.assertEqual(float(by["powf_blinn_phong"]["vs_powf_blinn_phong"]), 1.0)
        self.assertEqual(by["blinn_phong"]["paper_cycles"], "")

    @staticmethod
    def table4_of(directory, text):
        """`abrdf tables 4 --costs costs.txt` on a cost file holding `text`."""
        path = os.path.join(directory, "costs.txt")
        with open(path, "w") as f:
            f.write(text)
        return run("tables", "4", "--costs", path).stdout

    def test_table4_markdown_from_cost_file(self):
        with tempfile.TemporaryDirectory() as d:
            out = self.table4_of(d, "# hand-written cost file\npowf_blinn_phong 10\nf2 5 # half\nfs 20\n")
            self.assertIn("## Table 4", out)
            self.assertIn("cost file costs.txt", out)
            self.assertIn("| f2 | 2 | 2 | 0 | 8 | 8 | 1.00 | 5.000 | 1.00 | 0.50 |", out)
            self.assertIn("| fs | 2 | 1 | 1 | 15 | 15 | 1.88 | 20.000 | 4.00 | 2.00 |", out)
            self.assertIn("| f4 | 2 | 3 | 0 | 11 | 11 | 1.38 | — | — | — |", out)
            self.assertIn("equals the published cycles", out)
            self.assertIn("cycles (here): none, the cost file gives no clock", out)
            self.assertNotIn("| cycles (here) |", out)
            # a clock line: the cycles column is ns x GHz
            out = self.table4_of(d, "# clock: 2.00 GHz, by hand\npowf_blinn_phong 10\nf2 5\nfs 20\n")
            self.assertIn("cycles (here) = ns x the clock the cost file gives, 2.00 GHz.", out)
            self.assertIn("| f2 | 2 | 2 | 0 | 8 | 8 | 1.00 | 5.000 | 10.0 | 1.00 | 0.50 |", out)
            self.assertIn("| fs | 2 | 1 | 1 | 15 | 15 | 1.88 | 20.000 | 40.0 | 4.00 | 2.00 |", out)


class GltfTable(unittest.TestCase):
    """`abrdf tables gltf`: the glTF mapping's measured error (docs/GLTF.md, "The mapping")."""

    def test_csv_rows_and_classes(self):
        rows = list(csv.DictReader(io.StringIO(run("tables", "gltf", "--csv").stdout)))
        names = [r["mapping"] for r in rows]
        for name in ("dielectric, rough", "metal", "metallic 0.5", "anisotropy 0.5",
                     "clearcoat 1", "sheen", "transmission 0.5"):
            self.assertIn(name, names)
        bounds = [(1e-4, "none"), (2.5e-4, "slight"), (1e-3, "noticeable"), (float("inf"), "significant")]
        for r in rows:
            errs = [float(r[f"albedo_err_{a}"]) for a in (0, 45, 75)]
            self.assertAlmostEqual(float(r["albedo_max_abs"]), max(abs(e) for e in errs), delta=1e-6)
            nmse = float(r["nmse"])
            self.assertGreaterEqual(nmse, 0.0)
            self.assertEqual(r["class"], next(c for b, c in bounds if nmse < b))
        by = {r["mapping"]: r for r in rows}
        # left out layers are errors the table must show; an exact row must show none
        self.assertEqual(by["sheen"]["class"], "significant")
        self.assertEqual(by["clearcoat 1"]["class"], "significant")
        self.assertLess(float(by["dielectric, smooth"]["nmse"]), 1e-9)

    def test_markdown_is_default(self):
        out = run("tables", "gltf").stdout
        self.assertEqual(out, run("tables", "gltf", "--markdown").stdout)
        self.assertIn("| mapping | glTF material | exact | approximated |", out)
        self.assertEqual(out.count("\n| "), 12)  # the header and 11 rows


class Calibrate(unittest.TestCase):
    def test_writes_a_parseable_file_with_every_model(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "costs.txt")
            run("calibrate", "-o", path, "--quick", "--reps", "1", "--pairs", "256")
            with open(path) as f:
                text = f.read()
            header = [l for l in text.splitlines() if l.startswith("#")]
            for key in ("# machine:", "# date:", "# command: abrdf calibrate -o", "# clock:"):
                self.assertTrue(any(l.startswith(key) for l in header), key)
            costs = {}
            for line in text.splitlines():
                line = line.split("#", 1)[0].split()
                if line:
                    self.assertEqual(len(line), 2)
                    costs[line[0]] = float(line[1])
            self.assertEqual(set(costs), set(registered_models()) | {"powf_blinn_phong"})
            self.assertTrue(all(v > 0 for v in costs.values()))
            # the tool reads back what it wrote
            out = run("tables", "4", "--csv", "--costs", path).stdout
            by = {r["model"]: r for r in csv.DictReader(io.StringIO(out))}
            self.assertAlmostEqual(float(by["f8"]["ns_per_eval"]), costs["f8"], delta=1e-3)

    def test_stdout_without_output_file(self):
        out = run("calibrate", "--quick", "--reps", "1", "--pairs", "64").stdout
        self.assertIn("\npowf_blinn_phong ", out)


class Errors(unittest.TestCase):
    def test_usage_errors_exit_2(self):
        self.assertIn("available: 2, 3, 4", run("tables", code=2).stderr)
        self.assertIn("no table '9'", run("tables", "9", code=2).stderr)
        run("tables", "2", "--bogus", code=2)
        run("tables", "4", "--reps", "0", code=2)
        run("calibrate", "--reps", "x", code=2)
        run("calibrate", "extra", code=2)

    def test_bad_files_exit_1_with_the_line(self):
        with tempfile.TemporaryDirectory() as d:
            bad = os.path.join(d, "bad.txt")
            for content, msg in (("f2 -3\n", "bad.txt:1:"), ("f2 1\nnot_a_model 2\n", "unknown model 'not_a_model'"),
                                 ("f2 1\nf2 2\n", "appears twice"), ("# nothing\n", "no model costs")):
                with open(bad, "w") as f:
                    f.write(content)
                self.assertIn(msg, run("tables", "4", "--costs", bad, code=1).stderr)
            run("tables", "4", "--costs", os.path.join(d, "missing.txt"), code=1)
            paper = os.path.join(d, "paper.csv")
            with open(paper, "w") as f:
                f.write("table,row,column,value\n2,f2\n")
            self.assertIn("paper.csv:2:", run("tables", "2", "--paper", paper, code=1).stderr)


if __name__ == "__main__":
    ABRDF = sys.argv.pop(1)
    unittest.main(verbosity=1)
