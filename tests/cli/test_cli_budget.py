"""CLI tests of the selection's budget mode and the fit (run by CTest with the path of the abrdf
binary and the scenes directory): `abrdf fit`, `abrdf advise --budget/--pareto/--plot`, scene
files with `adaptive budget=`, `abrdf render --adaptive --budget`, and the errors (one line on
stderr, exit status 2 for bad arguments, 1 for a bad scene)."""
import json
import os
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET

ABRDF = None
SCENES = None


def run(*args, code=0, timeout=300):
    p = subprocess.run([ABRDF, *args], capture_output=True, text=True, timeout=timeout)
    if p.returncode != code:
        raise AssertionError(f"abrdf {' '.join(args)}: exit {p.returncode} (expected {code})\n"
                             f"stdout: {p.stdout}\nstderr: {p.stderr}")
    return p


def one_line_error(test, p, *words):
    lines = p.stderr.strip().splitlines()
    test.assertEqual(len(lines), 1, p.stderr)
    for w in words:
        test.assertIn(w, lines[0])


# The surface class `abrdf fit --ref M` reports for M (every other model: general).
SURFACE_OF = {"neubelt_pettineo": "cloth_rough", "kajiya_kay": "cloth_shiny", "huang": "hair",
              "marschner": "hair", "weidlich_wilkie": "layered_plastic",
              "belcour": "layered_plate", "disney_clearcoat": "layered_plate"}

MATERIAL_HEADER = ("name,type,n,r,kd_r,kd_g,kd_b,ks_r,ks_g,ks_b,f0_r,f0_g,f0_b,eta,anisotropy,"
                   "melanin,redness,coat_eta,coat_r,coat_depth,coat_sa_r,coat_sa_g,coat_sa_b,"
                   "base_eta,base_kappa,source\n")


def fit_json(*args):
    return json.loads(run("fit", *args, "--json").stdout)


class Fit(unittest.TestCase):
    def test_fit_json_reports_the_errors_and_stays_in_range(self):
        d = json.loads(run("fit", "--ref", "disney_specular", "--set", "r=0.5",
                           "--candidate", "blinn_phong", "--json").stdout)
        self.assertEqual((d["reference"], d["candidate"]), ("disney_specular", "blinn_phong"))
        for key in ("rel_l2", "max_rel_pct", "max_abs", "nmse_pred"):
            self.assertGreaterEqual(d[key], 0, key)
        self.assertTrue(1 <= d["params"]["n"] <= 1e6)
        self.assertTrue(all(0 <= v <= 1 for v in d["params"]["ks"]))
        self.assertGreater(d["directions"], 500)

    def test_fit_json_is_json_when_the_prediction_is_infinite(self):
        # f2 cannot follow glass's reference at all: its predicted NMSE is infinite
        d = json.loads(run("fit", "--material", "glass", "--candidate", "f2", "--json").stdout,
                       parse_constant=lambda c: self.fail("%s is not JSON" % c))
        self.assertIsNone(d["nmse_pred"])
        self.assertEqual(d["class"], "significant")

    def test_a_lobe_switched_off_has_weight_zero_not_minus_zero(self):
        # cotton's sheen: the Cook-Torrance lobe beside Oren-Nayar fits best switched off;
        # its ks is written 0 (it printed "-0, -0, -0")
        out = run("fit", "--material", "cotton", "--candidate", "oren_nayar+cook_torrance").stdout
        ks = next(line for line in out.splitlines() if line.split()[:1] == ["ks"])
        self.assertNotIn("-0", ks, out)
        raw = run("fit", "--material", "cotton", "--candidate", "oren_nayar+cook_torrance",
                  "--json").stdout
        seg = raw[raw.index('"ks"'):]
        self.assertNotIn("-0", seg[:seg.index("]")], raw)

    def test_fit_material_reference(self):
        out = run("fit", "--material", "gold", "--candidate", "f_ge").stdout
        self.assertIn("reference   disney_diffuse+disney_specular", out)
        self.assertRegex(out, r"image NMSE  \d")

    def test_every_model_fits_itself_exactly(self):
        # abrdf_fit keeps a lobe the reference has (keep_shared), so every model abrdf models
        # lists fits itself with error 0 and is refused for none. The coarsest direction set;
        # huang's image prediction is most of the time (about 6 s of CPU in all).
        # (the measured model fits a table: tests/cli/test_cli_measured.py)
        names = [m["name"] for m in json.loads(run("models", "--json").stdout)["models"]
                 if "table" not in m["needs"]]
        self.assertGreaterEqual(len(names), 31)
        before = os.times()
        for m in names:
            with self.subTest(model=m):
                d = fit_json("--ref", m, "--candidate", m, "--resolution", "1")
                self.assertEqual((d["reference"], d["candidate"]), (m, m))
                for key in ("rel_l2", "max_rel_pct", "max_abs", "nmse_pred"):
                    self.assertLess(d[key], 1e-12, key)
                self.assertEqual(d["surface"], SURFACE_OF.get(m, "general"))
        after = os.times()
        cpu = sum(after[2:4]) - sum(before[2:4])
        print(f"\n{len(names)} self-fits: {cpu:.1f} s of CPU", file=sys.stderr)

    def test_special_reference_offers_what_its_material_offers(self):
        # (--ref, a material whose photoreal choice is of the same class, a candidate both offer)
        for ref, material, cand in (("belcour", "transparent_plate", "weidlich_wilkie"),
                                    ("weidlich_wilkie", "car_paint", "lambert+f_ge"),
                                    ("kajiya_kay", "silk", "lambert+blinn_phong"),
                                    ("neubelt_pettineo", "wool", "oren_nayar+disney_specular"),
                                    ("marschner", "hair_blond", "kajiya_kay")):
            with self.subTest(ref=ref):
                a = fit_json("--ref", ref, "--candidate", cand, "--resolution", "1")
                b = fit_json("--material", material, "--candidate", cand, "--resolution", "1")
                self.assertEqual(a["surface"], b["surface"])
                self.assertTrue(a["budget_candidate"] and b["budget_candidate"])
                self.assertIn(cand, a["budget_candidates"])
                if ref != "belcour":  # belcour has no kd: its class without a diffuse base
                    self.assertEqual(a["budget_candidates"], b["budget_candidates"])

    def test_fits_what_the_library_fits_and_says_what_the_budget_offers(self):
        d = fit_json("--ref", "marschner", "--candidate", "phong", "--resolution", "1")
        self.assertEqual((d["surface"], d["budget_candidate"]), ("hair", False))
        self.assertEqual(d["budget_candidates"], ["huang", "marschner", "kajiya_kay"])
        self.assertGreater(d["rel_l2"], 0.1)
        out = run("fit", "--ref", "marschner", "--candidate", "phong", "--resolution", "1").stdout
        self.assertIn("surface     hair: phong is not one of the budget mode's candidates "
                      "(huang, marschner, kajiya_kay)\n", out)

    def test_materials_file_is_loaded_for_either_reference(self):
        for ref in (("--ref", "blinn_phong"), ("--material", "gold")):
            with self.subTest(ref=ref[0]):
                p = run("fit", *ref, "--candidate", "f2", "--materials", "MISSING", code=2)
                one_line_error(self, p, "abrdf fit: MISSING: cannot open")
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "m.csv")
            jade = "jade,general,,{r},0.3,0.6,0.4,1,1,1,,,,1.66,,,,,,,,,,,,my jade\n"
            with open(path, "w") as f:
                f.write(MATERIAL_HEADER + jade.format(r=0.2))
            d = fit_json("--material", "jade", "--materials", path, "--candidate", "f2",
                         "--resolution", "1")
            self.assertEqual(d["reference"], "disney_diffuse+disney_specular")
            with open(path, "w") as f:
                f.write(MATERIAL_HEADER + jade.format(r=2))
            p = run("fit", "--ref", "f2", "--materials", path, "--candidate", "f2", code=2)
            one_line_error(self, p, f"{path}:2: column 'r'")

    def test_bad_arguments(self):
        one_line_error(self, run("fit", "--ref", "gold", "--candidate", "f2", code=2), "gold")
        one_line_error(self, run("fit", "--ref", "disney_specular", "--candidate", "f2",
                                 "--metric", "l1", code=2), "--metric")
        one_line_error(self, run("fit", "--candidate", "f2", code=2), "--ref")
        one_line_error(self, run("fit", "--ref", "disney_specular", "--set", "r=2",
                                 "--candidate", "f2", code=2), "r")


class Advise(unittest.TestCase):
    def test_budget_choice_is_within_and_cheapest(self):
        d = json.loads(run("advise", "plastic_red", "--budget", "slight", "--json").stdout)
        self.assertEqual(d["budget"], {"max_nmse": 0.00025, "class": "slight"})
        self.assertLess(d["error"]["nmse_pred"], 0.00025)
        within = [c for c in d["candidates"] if c["within"]]
        self.assertTrue(within)
        self.assertEqual(min(c["cost"] for c in within), d["cost"]["total"])
        self.assertEqual(d["candidates"][0]["specular"], d["reference"]["specular"])
        self.assertEqual(d["candidates"][0]["nmse_pred"], 0)
        steps = [s["step"] for s in d["trace"]]
        self.assertEqual(steps[-1], "budget")
        self.assertEqual(steps.count("fit"), len(d["candidates"]))

    def test_numeric_budget_and_human_output(self):
        out = run("advise", "gold", "--budget", "3e-4").stdout
        self.assertIn("budget     predicted image NMSE < 0.0003\n", out)
        self.assertIn("choice     disney_specular\n", out)
        self.assertIn("the cheapest within NMSE < 0.0003", out)

    def test_pareto_front_and_plot(self):
        with tempfile.TemporaryDirectory() as tmp:
            svg = os.path.join(tmp, "front.svg")
            d = json.loads(run("advise", "gold", "--pareto", "--plot", svg, "--json").stdout)
            front = sorted((c for c in d["candidates"] if c["pareto"]), key=lambda c: c["cost"])
            self.assertGreaterEqual(len(front), 1)
            errs = [c["nmse_pred"] for c in front]
            self.assertEqual(errs, sorted(errs, reverse=True))  # cheaper ones err more
            # every candidate is dominated by one on the front (cheaper or equal, and no worse)
            for c in d["candidates"]:
                if c["cost"] is None:
                    continue
                self.assertTrue(any(f["cost"] <= c["cost"] and f["nmse_pred"] <= c["nmse_pred"]
                                    for f in front), c)
            root = ET.parse(svg).getroot()
            self.assertTrue(root.tag.endswith("svg"))
            self.assertGreaterEqual(len([e for e in root.iter() if e.tag.endswith("circle")]),
                                    len(d["candidates"]) - 1)

    def test_hair_against_its_table(self):
        """--hair-table: the hair's reference is its table (the trace says so), which wins at
        error 0 and the cost the trace gives it, below every coarser quadrature's; a material
        that is not hair ignores it; without --budget or --pareto it is refused."""
        table = ["--hair-table-sizes", "6,3,8,1"]
        d = json.loads(run("advise", "hair_brown", "--budget", "slight", "--json", *table).stdout)
        self.assertEqual((d["specular"], d["error"]["nmse_pred"]), ("huang", 0))
        self.assertIs(d["reference"]["prepared"], True)
        texts = [s["text"] for s in d["trace"]]
        self.assertTrue(any("(the photoreal choice, as the caller prepared it)" in t
                            for t in texts), texts)
        huang = [c for c in d["candidates"] if c["specular"] == "huang"]
        self.assertEqual(len(huang), 5)  # the table, entry grids 5 to 2
        self.assertEqual(d["cost"]["total"], huang[0]["cost"])
        self.assertLess(huang[0]["cost"], min(c["cost"] for c in huang[1:]))
        self.assertTrue(all(c["nmse_pred"] > 0 for c in huang[1:]))
        plain = json.loads(run("advise", "gold", "--budget", "slight", "--json").stdout)
        self.assertIs(plain["reference"]["prepared"], False)
        p = run("advise", "gold", "--budget", "slight", "--json", *table)
        other = json.loads(p.stdout)
        self.assertEqual((other["diffuse"], other["specular"], other["params"]),
                         (plain["diffuse"], plain["specular"], plain["params"]))
        self.assertIn("note: --hair-table: gold's photoreal choice is not huang", p.stderr)
        human = run("advise", "hair_brown", "--budget", "slight", *table).stdout
        self.assertIn("(the flowchart's photoreal choice, from its huang table)", human)
        one_line_error(self, run("advise", "hair_brown", *table, code=2), "--hair-table goes with")

    def test_bad_budgets(self):
        one_line_error(self, run("advise", "gold", "--budget", "slite", code=2),
                       "unknown budget class 'slite'")
        one_line_error(self, run("advise", "gold", "--budget", "-1e-4", code=2), "(0, 1]")
        one_line_error(self, run("advise", "gold", "--budget", "nan", code=2), "nan")
        one_line_error(self, run("advise", "gold", "--budget", "slight", "--goal", "performance",
                                 code=2), "--goal")
        one_line_error(self, run("advise", "gold", "--plot", "x.svg", code=2), "--pareto")


class Scenes(unittest.TestCase):
    def test_render_adaptive_budget_and_scene_budget(self):
        with tempfile.TemporaryDirectory() as tmp:
            scene = os.path.join(tmp, "b.scene")
            with open(scene, "w") as f:
                f.write("camera position=0,0,4 look_at=0,0,0 resolution=32,32\n"
                        "light directional direction=-1,1,1 intensity=3\n"
                        "material m adaptive budget=noticeable table=gold\n"
                        "sphere material=m radius=1\n")
            out = run("render", scene, "-o", os.path.join(tmp, "a.exr"), "--no-preview",
                      "--explain").stdout
            self.assertIn("budget NMSE < 0.001, table entry gold: disney_specular", out)
            out = run("render", os.path.join(SCENES, "sphere.scene"), "-o",
                      os.path.join(tmp, "s.exr"), "--no-preview", "--width", "32", "--height", "32",
                      "--adaptive", "--budget", "slight", "--explain").stdout
            self.assertIn("budget NMSE < 0.00025", out)
            self.assertTrue(os.path.getsize(os.path.join(tmp, "s.exr")) > 0)

    def test_bad_scene_budget_and_flags(self):
        with tempfile.TemporaryDirectory() as tmp:
            scene = os.path.join(tmp, "b.scene")
            with open(scene, "w") as f:
                f.write("camera position=0,0,4 look_at=0,0,0 resolution=8,8\n"
                        "material m adaptive budget=huge table=gold\n"
                        "sphere material=m radius=1\n")
            p = run("render", scene, "-o", os.path.join(tmp, "a.exr"), code=1)
            one_line_error(self, p, "b.scene:2:", "unknown budget class 'huge'")
            with open(scene, "w") as f:
                f.write("camera position=0,0,4 look_at=0,0,0 resolution=8,8\n"
                        "material m adaptive budget=slight goal=photoreal table=gold\n"
                        "sphere material=m radius=1\n")
            one_line_error(self, run("render", scene, "-o", os.path.join(tmp, "a.exr"), code=1),
                           "b.scene:2:", "goal= or budget=")
        sphere = os.path.join(SCENES, "sphere.scene")
        one_line_error(self, run("render", sphere, "-o", "x.exr", "--budget", "slight", code=2),
                       "--budget needs --adaptive")
        one_line_error(self, run("render", sphere, "-o", "x.exr", "--adaptive", "--budget", "-3",
                                 code=2), "(0, 1]")


if __name__ == "__main__":
    ABRDF = sys.argv.pop(1)
    SCENES = sys.argv.pop(1)
    unittest.main(verbosity=2)
