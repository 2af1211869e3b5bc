"""CLI tests of `abrdf advise` (run by CTest with the path of the abrdf binary): the flowchart's
branches through the command line, --json, --list, user material and cost files, and the
errors (unknown material with suggestions, invalid numbers -> exit status 2)."""
import json
import os
import sys
import tempfile
import unittest

import subprocess

ABRDF = None
HEADER = ("name,type,n,r,kd_r,kd_g,kd_b,ks_r,ks_g,ks_b,f0_r,f0_g,f0_b,eta,anisotropy,melanin,"
          "redness,coat_eta,coat_r,coat_depth,coat_sa_r,coat_sa_g,coat_sa_b,base_eta,base_kappa,"
          "source\n")


def run(*args, code=0):
    p = subprocess.run([ABRDF, "advise", *args], capture_output=True, text=True, timeout=60)
    if p.returncode != code:
        raise AssertionError(f"abrdf advise {' '.join(args)}: exit {p.returncode} (expected {code})\n"
                             f"stdout: {p.stdout}\nstderr: {p.stderr}")
    return p


def advise_json(*args):
    return json.loads(run(*args, "--json").stdout)


def texts(doc):
    return [s["text"] for s in doc["trace"]]


class Branches(unittest.TestCase):
    def test_gold_photoreal_is_disney_with_the_reason(self):
        out = run("gold", "--goal", "photoreal").stdout
        self.assertIn("specular  disney_specular", out)
        self.assertIn("diffuse   disney_diffuse", out)
        self.assertIn("alpha 0.2 > 0.03: rough", out)
        self.assertIn("Johnson & Christy 1972", out)

    def test_performance_n300_rel2_is_f8(self):
        out = run("--n", "300", "--goal", "performance", "--max-rel-error", "2").stdout
        self.assertIn("specular  f8", out)
        self.assertRegex(out, r"f8: rel 1\.\d+% <= 2%, abs 0\.0\d+ <= 0\.05, 14 cycles: cheapest that passes")
        self.assertRegex(out, r"f4: rel \d\.\d+% > 2%.*rejected")

    def test_performance_json(self):
        d = advise_json("--n", "300", "--goal", "performance", "--max-rel-error", "2",
                        "--max-abs-error", "0.05")
        self.assertEqual((d["goal"], d["diffuse"], d["specular"]), ("performance", "lambert", "f8"))
        self.assertEqual(d["tolerance"], {"max_rel_pct": 2, "max_abs": 0.05})
        self.assertLessEqual(d["error"]["rel_pct"], 2)
        self.assertEqual(d["cost"]["specular"], 14)
        cands = [s for s in d["trace"] if s["step"] == "candidate"]
        self.assertEqual([s["model"] for s in cands], ["f2", "f4", "f8", "f16", "fs", "fkv", "fkub"])
        for s in cands:
            self.assertEqual(s["passed"], s["value"] <= 2 and s["value2"] <= 0.05, s)
        self.assertEqual(d["trace"][-1]["step"], "cheapest")
        self.assertEqual(d["params"]["n"], 300)

    def test_performance_nothing_passes_is_blinn_phong(self):
        d = advise_json("--n", "300", "--goal", "performance", "--max-rel-error", "0.1",
                        "--max-abs-error", "none")
        self.assertEqual(d["specular"], "blinn_phong")
        self.assertIsNone(d["tolerance"]["max_abs"])
        self.assertTrue(any("no Table-1 approximation passes" in t for t in texts(d)))

    def test_smooth_boundary_and_override(self):
        d = advise_json("--r", "0.03")
        self.assertEqual((d["diffuse"], d["specular"]), ("lambert_fresnel", "f_2e"))
        self.assertIn("alpha 0.03 <= 0.03: smooth", texts(d))
        d = advise_json("gold", "--r", "0.01")  # an override turns polished gold smooth
        self.assertEqual(d["specular"], "f_2e")
        self.assertEqual(d["material"], "gold")

    def test_anisotropic_material(self):
        d = advise_json("brushed_aluminium")
        self.assertEqual(d["specular"], "disney_specular_aniso")

    def test_special_surfaces_by_name(self):
        expect = {"wool": "neubelt_pettineo", "denim": "neubelt_pettineo", "silk": "kajiya_kay",
                  "velvet": "kajiya_kay", "hair_red": "huang", "car_paint": "weidlich_wilkie",
                  "transparent_plate": "belcour", "coated_steel": "belcour"}
        for name, model in expect.items():
            d = advise_json(name, "--goal", "photoreal")
            self.assertEqual(d["specular"], model, name)
            self.assertIsNone(d["diffuse"], name)
        d = advise_json("coated_steel")
        self.assertTrue(any("smooth metal under a rough coat" in t for t in texts(d)))
        self.assertEqual(len(d["params"]["layers"]), 2)

    def test_type_override(self):
        d = advise_json("--r", "0.5", "--type", "hair", "--melanin", "0.8")
        self.assertEqual(d["specular"], "huang")
        self.assertEqual(d["params"]["melanin"], 0.8)


class Listing(unittest.TestCase):
    def test_list(self):
        out = run("--list").stdout
        self.assertIn("gold", out)
        self.assertRegex(out, r"\n(\d+) materials\n")
        self.assertGreaterEqual(int(out.strip().split()[-2]), 40)

    def test_list_json(self):
        d = json.loads(run("--list", "--json").stdout)
        self.assertGreaterEqual(len(d["materials"]), 40)
        self.assertTrue(all(m["source"] for m in d["materials"]))


class Rules(unittest.TestCase):
    def test_rules_json_is_the_flowchart(self):
        r = json.loads(run("--rules", "--json").stdout)
        self.assertEqual(r["smooth_r_max"], 0.03)
        self.assertEqual(r["candidates"], ["f2", "f4", "f8", "f16", "fs", "fkv", "fkub"])
        self.assertEqual(r["special"]["layered_metal"]["model"], "belcour")
        self.assertEqual(r["special"]["hair"]["model"], "huang")
        self.assertEqual(len(r["table6_f2e"]), 18)
        self.assertIn("smooth if r <= 0.03", run("--rules").stdout)


class Files(unittest.TestCase):
    def write(self, text, suffix=".csv"):
        f = tempfile.NamedTemporaryFile("w", suffix=suffix, delete=False)
        f.write(text)
        f.close()
        self.addCleanup(os.unlink, f.name)
        return f.name

    def test_user_materials_override_and_add(self):
        path = self.write("# mine\n" + HEADER +
                          "gold,general,,0.01,0,0,0,1,1,1,0.957,0.792,0.408,,,,,,,,,,,,,my gold\n"
                          "jade,general,,0.2,0.3,0.6,0.4,1,1,1,,,,1.66,,,,,,,,,,,,my jade\n")
        self.assertEqual(advise_json("gold", "--materials", path)["specular"], "f_2e")
        self.assertEqual(advise_json("jade", "--materials", path)["source"], "my jade")

    def test_bad_user_file_names_file_and_line(self):
        path = self.write(HEADER + "jade,general,,2,0.3,0.6,0.4,1,1,1,,,,1.66,,,,,,,,,,,,x\n")
        err = run("jade", "--materials", path, code=2).stderr
        self.assertIn(f"{path}:2: column 'r': 2 is outside [0, 1]", err)

    def test_calibrated_costs(self):
        path = self.write("# measured\nf8 5.0\nf16 1.0\n", suffix=".txt")
        d = advise_json("--n", "300", "--goal", "performance", "--costs", path)
        self.assertEqual(d["specular"], "f16")
        self.assertTrue(d["cost"]["unit"].startswith("ns/eval"))


class Errors(unittest.TestCase):
    def error(self, *args, needle):
        p = run(*args, code=2)
        self.assertIn(needle, p.stderr)
        self.assertEqual(p.stdout, "")

    def test_unknown_material_suggests_nearest(self):
        self.error("gld", needle="unknown material 'gld'; did you mean: gold")
        self.error("alumin", needle="aluminium")
        self.error("qqqqqqqqqqqq", needle="abrdf advise --list")

    def test_invalid_numbers(self):
        self.error("--n", "-5", needle="--n: -5 is outside [0, 1e+06]")
        self.error("--r", "1.5", needle="--r: 1.5 is outside [0, 1]")
        self.error("--r", "nan", needle="--r: 'nan' is not a finite number")
        self.error("--n", "abc", needle="--n: 'abc' is not a finite number")
        self.error("--n", "inf", needle="is not a finite number")
        self.error("gold", "--kd", "2", needle="--kd: 2 is outside [0, 1]")
        self.error("gold", "--kd", "0.1,x,0.2", needle="is not R,G,B")
        self.error("--n", "300", "--goal", "performance", "--max-rel-error", "-1",
                   needle="--max-rel-error: -1 is outside")
        self.error("--r", needle="--r needs a value")

    def test_usage_errors(self):
        self.error(needle="give a MATERIAL name or at least --n or --r")
        self.error("gold", "--goal", "fast", needle="--goal needs performance or photoreal")
        self.error("gold", "--type", "metal", needle="--type needs one of")
        self.error("gold", "--bogus", needle="unknown option '--bogus'")
        self.error("gold", "silver", needle="one material at a time")
        self.error("gold", "--materials", "/nonexistent/m.csv", needle="/nonexistent/m.csv: cannot open: No such file or directory")

    def test_help(self):
        self.assertIn("usage: abrdf advise", run("--help").stdout)


if __name__ == "__main__":
    ABRDF = sys.argv.pop(1)
    unittest.main(verbosity=1)
