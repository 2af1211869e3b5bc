#!/usr/bin/env python3
"""test_cli.py - the `abrdf` command: model listing, values against independent hand
computations, the slice CSV, and the one-line error contract (exit status 2, never a crash).

    python3 test_cli.py PATH/TO/abrdf        (CTest passes the built binary)

Python 3 standard library only. The hand computations below are written from the formulas
in the paper and the original publications, term by term, not from the library's code."""
import csv
import io
import json
import math
import random
import subprocess
import sys
import unittest

ABRDF = None  # set from argv in main
PI = math.pi

# Every model issue 2 names, with the formula reference `abrdf models` must report.
EXPECTED_MODELS = {
    "lambert": "Eq. 1", "lambert_fresnel": "Eq. 2", "disney_diffuse": "Eq. 3",
    "oren_nayar": None, "phong": None, "blinn_phong": "Eq. 4",
    "f2": "Table 1", "f4": "Table 1", "f8": "Table 1", "f16": "Table 1", "fs": "Table 1",
    "fkv": "Table 1", "fkub": "Table 1",
    "f_phe": "Table 5", "f_be": "Table 5", "f_2e": "Table 5", "f_16e": "Table 5",
    "f_ge": "Table 5", "f_ctphe": "Table 5", "f_ct2e": "Table 5", "f_ct16e": "Table 5",
    "cook_torrance": "Eq. 5", "disney_specular": "Eqs. 5, 6, 8, 9",
    "disney_specular_aniso": "Eqs. 5, 7, 8, 9", "disney_clearcoat": None,
}


def run(*args):
    p = subprocess.run([ABRDF] + [str(a) for a in args], stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, universal_newlines=True, timeout=60)
    return p.returncode, p.stdout, p.stderr


# ---- small vector helpers ---------------------------------------------------------------
def norm(v):
    l = math.sqrt(sum(x * x for x in v))
    return [x / l for x in v]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def vec(v):
    return ",".join(repr(x) for x in v)


def schlick(f0, cos_d):
    return f0 + (1.0 - f0) * (1.0 - cos_d) ** 5  # Eq. 8


class Geometry:
    """wi, wo in a frame (N, T, B); every cosine the hand formulas need."""

    def __init__(self, wi, wo, n=(0.0, 0.0, 1.0), t=None):
        self.n = norm(n)
        self.wi, self.wo = norm(wi), norm(wo)
        if t is not None:
            t = norm(t)
            d = dot(t, self.n)
            self.t = norm([t[k] - d * self.n[k] for k in range(3)])
            self.b = cross(self.n, self.t)
        self.h = norm([self.wi[k] + self.wo[k] for k in range(3)])
        self.ci, self.co = dot(self.n, self.wi), dot(self.n, self.wo)
        self.ch, self.cd = dot(self.n, self.h), dot(self.wi, self.h)
        r = [2.0 * self.ci * self.n[k] - self.wi[k] for k in range(3)]  # mirror of wi
        self.rv = dot(r, self.wo)

    def args(self):
        a = ["--wi", vec(self.wi), "--wo", vec(self.wo), "--normal", vec(self.n)]
        if hasattr(self, "t"):
            a += ["--tangent", vec(self.t)]
        return a


# Near-mirror pair, off the plane of the normal, so every lobe is well above zero.
G = Geometry([-0.3, 0.1, 1.0], [0.25, -0.05, 1.0])


def ggx_d(ch, ag):
    a2 = ag * ag
    return a2 / (PI * (1.0 + (a2 - 1.0) * ch * ch) ** 2)  # Eq. 6


def smith_g1_ggx(c, ag):
    return 2.0 / (1.0 + math.sqrt(1.0 + ag * ag * (1.0 - c * c) / (c * c)))  # Eq. 9


# ---- hand computations, one per model -------------------------------------------------------
def hand_disney_specular(g, r, f0):
    ag = r * r
    return [schlick(f, g.cd) * ggx_d(g.ch, ag) * smith_g1_ggx(g.ci, ag) * smith_g1_ggx(g.co, ag)
            / (4.0 * g.ci * g.co) for f in f0]  # Eq. 5


def hand_lambert(g, kd):
    return [k / PI for k in kd]  # Eq. 1


def hand_lambert_fresnel(g, kd, f0):
    return [k / PI * (1.0 - schlick(f, g.cd)) for k, f in zip(kd, f0)]  # Eq. 2


def hand_disney_diffuse(g, kd, r):
    fd90 = 0.5 + 2.0 * r * g.cd ** 2
    s = (1.0 + (fd90 - 1.0) * (1.0 - g.ci) ** 5) * (1.0 + (fd90 - 1.0) * (1.0 - g.co) ** 5)  # Eq. 3
    return [k / PI * s for k in kd]


def hand_oren_nayar(g, kd, sigma):
    # Oren & Nayar 1994 qualitative model with angles (the library uses a trig-free form).
    ti, to = math.acos(g.ci), math.acos(g.co)
    pi_ = norm([g.wi[k] - g.ci * g.n[k] for k in range(3)])
    po = norm([g.wo[k] - g.co * g.n[k] for k in range(3)])
    cos_phi = dot(pi_, po)
    s2 = sigma * sigma
    a = 1.0 - 0.5 * s2 / (s2 + 0.33)
    b = 0.45 * s2 / (s2 + 0.09)
    alpha, beta = max(ti, to), min(ti, to)
    return [k / PI * (a + b * max(0.0, cos_phi) * math.sin(alpha) * math.tan(beta)) for k in kd]


def hand_lobe(ks, value):
    return [k * value for k in ks]


def power_form(n, c, m):
    return max(0.0, (n / m) * (c - 1.0) + 1.0) ** m  # Table 1, base clamped at 0


def hand_cook_torrance(g, r, f0):
    ag = r * r
    tan2 = (1.0 - g.ch ** 2) / g.ch ** 2
    d = math.exp(-tan2 / (ag * ag)) / (PI * ag * ag * g.ch ** 4)  # Beckmann
    gct = min(1.0, 2.0 * g.ch * g.co / g.cd, 2.0 * g.ch * g.ci / g.cd)
    return [schlick(f, g.cd) * d * gct / (4.0 * g.ci * g.co) for f in f0]  # Eq. 5


def hand_disney_aniso(g, r, aniso, f0):
    aspect = math.sqrt(1.0 - 0.9 * aniso)
    ax, ay = r * r / aspect, r * r * aspect
    hx, hy, hz = dot(g.h, g.t), dot(g.h, g.b), g.ch
    d = 1.0 / (PI * ax * ay * ((hx / ax) ** 2 + (hy / ay) ** 2 + hz ** 2) ** 2)  # Eq. 7

    def g1(w):
        c = dot(w, g.n)
        lam = math.sqrt((dot(w, g.t) * ax) ** 2 + (dot(w, g.b) * ay) ** 2 + c * c)
        return 2.0 * c / (c + lam)
    return [schlick(f, g.cd) * d * g1(g.wi) * g1(g.wo) / (4.0 * g.ci * g.co) for f in f0]


def hand_clearcoat(g, ks, gloss):
    a = 0.1 + (0.001 - 0.1) * gloss
    a2 = a * a
    d = (a2 - 1.0) / (PI * math.log(a2) * (1.0 + (a2 - 1.0) * g.ch ** 2))  # GTR1
    v = 0.25 * schlick(0.04, g.cd) * d * smith_g1_ggx(g.ci, 0.25) * smith_g1_ggx(g.co, 0.25) \
        / (4.0 * g.ci * g.co)
    return [k * v for k in ks]


def hand_values():
    """(model, --set list, geometry, expected RGB) for every case checked against the CLI."""
    n = 20.0
    ks = [0.9, 0.6, 0.3]
    f0 = [0.9, 0.5, 0.2]
    kd = [0.8, 0.5, 0.25]
    c_bp = [("ks", "0.9,0.6,0.3"), ("n", "20")]
    c_f0 = c_bp + [("f0", "0.9,0.5,0.2")]
    norm_phe = (n + 2.0) / (2.0 * PI)
    norm_be = (n + 2.0) * (n + 4.0) / (8.0 * PI * (2.0 ** (-n / 2.0) + n))
    norm_2e = 0.111 / n + 0.238 * (0.481 + n)
    norm_16e = (1.063 * n + 1.0) / (2.0 * PI)
    norm_ge = (n + 2.0) / (4.0 * PI * (2.0 - 2.0 ** (-n / 2.0)))
    ch, rv = G.ch, G.rv
    ct = 4.0 * G.ci * G.co
    tilted = Geometry([0.1, -0.2, 1.0], [0.3, 0.35, 0.8], n=[0.2, 0.1, 1.0])
    grazing = Geometry([-0.9, 0.2, 0.35], [-0.3, 0.6, 0.4], n=[0.1, 0.0, 1.0])
    aniso = Geometry([-0.3, 0.1, 1.0], [0.25, -0.05, 1.0], t=[1.0, 1.0, 0.3])
    return [
        ("disney_specular", [("r", "0.4"), ("f0", "0.9,0.5,0.2")], G, hand_disney_specular(G, 0.4, f0)),
        ("disney_specular", [("r", "0.7"), ("f0", "0.04")], tilted, hand_disney_specular(tilted, 0.7, [0.04] * 3)),
        ("lambert", [("kd", "0.8,0.5,0.25")], G, hand_lambert(G, kd)),
        ("lambert_fresnel", [("kd", "0.8,0.5,0.25"), ("f0", "0.9,0.5,0.2")], G, hand_lambert_fresnel(G, kd, f0)),
        ("disney_diffuse", [("kd", "0.8,0.5,0.25"), ("r", "0.2")], grazing, hand_disney_diffuse(grazing, kd, 0.2)),
        ("oren_nayar", [("kd", "0.8,0.5,0.25"), ("sigma", "0.5")], grazing, hand_oren_nayar(grazing, kd, 0.5)),
        ("phong", c_bp, G, hand_lobe(ks, rv ** n)),
        ("blinn_phong", c_bp, G, hand_lobe(ks, ch ** n)),  # Eq. 4
        ("f2", c_bp, G, hand_lobe(ks, power_form(n, ch, 2))),
        ("f4", c_bp, G, hand_lobe(ks, power_form(n, ch, 4))),
        ("f8", c_bp, G, hand_lobe(ks, power_form(n, ch, 8))),
        ("f16", c_bp, G, hand_lobe(ks, power_form(n, ch, 16))),
        ("fs", c_bp, G, hand_lobe(ks, ch / (n - n * ch + ch))),
        ("fkv", c_bp, G, hand_lobe(ks, max(0.0, 0.786 * n * ch * ch + (1.0 - 0.786 * n) * ch))),
        ("f_phe", c_bp, G, hand_lobe(ks, norm_phe * rv ** n)),
        ("f_be", c_bp, G, hand_lobe(ks, norm_be * ch ** n)),
        ("f_2e", c_bp, G, hand_lobe(ks, norm_2e * power_form(n, rv, 2))),
        ("f_16e", c_bp, G, hand_lobe(ks, norm_16e * power_form(n, rv, 16))),
        ("f_ge", c_f0, G, [k * schlick(f, G.cd) * norm_ge * ch ** n / max(G.ci, G.co) for k, f in zip(ks, f0)]),
        ("f_ctphe", c_f0, G, [k * schlick(f, G.cd) * norm_phe * ch ** n / ct for k, f in zip(ks, f0)]),
        ("f_ct2e", c_f0, G, [k * schlick(f, G.cd) * norm_2e * power_form(n, ch, 2) / ct for k, f in zip(ks, f0)]),
        ("f_ct16e", c_f0, G, [k * schlick(f, G.cd) * norm_16e * power_form(n, ch, 16) / ct for k, f in zip(ks, f0)]),
        ("cook_torrance", [("r", "0.5"), ("f0", "0.9,0.5,0.2")], G, hand_cook_torrance(G, 0.5, f0)),
        ("disney_specular_aniso", [("r", "0.5"), ("anisotropic", "0.8"), ("f0", "0.9,0.5,0.2")], aniso,
         hand_disney_aniso(aniso, 0.5, 0.8, f0)),
        ("disney_clearcoat", [("ks", "0.9,0.6,0.3"), ("clearcoat_gloss", "0.3")], G, hand_clearcoat(G, ks, 0.3)),
    ]


def eval_json(model, sets, g):
    args = ["eval", model] + g.args() + ["--json"]
    for k, v in sets:
        args += ["--set", "%s=%s" % (k, v)]
    rc, out, err = run(*args)
    if rc != 0:
        raise AssertionError("abrdf %s -> %d: %s" % (" ".join(args), rc, err))
    return json.loads(out)["f_r"]


def rel_err(a, b):
    return abs(a - b) / max(abs(a), abs(b), 1e-300)


class Models(unittest.TestCase):
    def setUp(self):
        rc, out, err = run("models", "--json")
        self.assertEqual(rc, 0, err)
        self.doc = json.loads(out)
        self.models = {m["name"]: m for m in self.doc["models"]}

    def test_every_model_listed_with_formula(self):
        for name, eq in EXPECTED_MODELS.items():
            self.assertIn(name, self.models, "model %s missing from abrdf models --json" % name)
            m = self.models[name]
            self.assertTrue(m["equation"], name)
            self.assertTrue(m["citation"], name)
            if eq is not None:
                self.assertEqual(m["equation"], eq, name)

    def test_params_have_range_and_default(self):
        for name, m in self.models.items():
            # every model reads parameters but the measured one, which reads a table
            self.assertEqual(not m["params"], "table" in m["needs"], name)
            for p in m["params"]:
                for key in ("name", "kind", "min", "max", "default", "help"):
                    self.assertIn(key, p, "%s.%s lacks %s" % (name, p.get("name"), key))
                self.assertLessEqual(p["min"], p["default"], "%s.%s" % (name, p["name"]))
                self.assertLessEqual(p["default"], p["max"], "%s.%s" % (name, p["name"]))

    def test_needs(self):
        needs = {n: set(m["needs"]) for n, m in self.models.items()}
        self.assertEqual(needs["lambert"], set())
        self.assertIn("fresnel", needs["disney_specular"])
        self.assertIn("fresnel", needs["lambert_fresnel"])
        self.assertIn("tangent", needs["disney_specular_aniso"])
        self.assertNotIn("tangent", needs["disney_specular"])
        for m in self.models.values():
            self.assertTrue(set(m["needs"]) <= {"tangent", "fresnel", "layers", "integration", "table"}, m["name"])
        self.assertEqual(needs["measured"], {"table"})

    def test_param_names_per_model(self):
        def names(m):
            return {p["name"] for p in self.models[m]["params"]}
        self.assertEqual(names("disney_specular"), {"ks", "r", "f0"})
        self.assertEqual(names("lambert"), {"kd"})
        self.assertEqual(names("blinn_phong"), {"ks", "n"})
        self.assertIn("anisotropic", names("disney_specular_aniso"))
        n2e = [p for p in self.models["f_2e"]["params"] if p["name"] == "n"][0]
        self.assertEqual(n2e["min"], 1.0)  # 0.111/n: the fit holds for n >= 1

    def test_table_lists_the_same_models(self):
        rc, out, err = run("models")
        self.assertEqual(rc, 0, err)
        listed = {line.split()[0] for line in out.splitlines()[1:] if line.strip()}
        self.assertEqual(listed, set(self.models))


class Eval(unittest.TestCase):
    def test_disney_specular_matches_hand_computation(self):
        # The acceptance check: GGX D, Schlick F, separable Smith G to 1e-9 relative.
        got = eval_json("disney_specular", [("r", "0.4"), ("f0", "0.9,0.5,0.2")], G)
        want = hand_disney_specular(G, 0.4, [0.9, 0.5, 0.2])
        for c in range(3):
            self.assertLess(rel_err(got[c], want[c]), 1e-9, "channel %d: %r vs %r" % (c, got[c], want[c]))

    def test_models_match_hand_computations(self):
        for model, sets, g, want in hand_values():
            got = eval_json(model, sets, g)
            for c in range(3):
                self.assertGreater(want[c], 0.0, "%s: pick a geometry with a non-zero lobe" % model)
                self.assertLess(rel_err(got[c], want[c]), 1e-9,
                                "%s channel %d: abrdf %.17g, hand %.17g" % (model, c, got[c], want[c]))

    def test_hand_cases_cover_every_closed_form_but_fkub(self):
        # fkub's coefficients come from the fitted table, checked by its own tests.
        covered = {case[0] for case in hand_values()}
        self.assertEqual(set(EXPECTED_MODELS) - covered, {"fkub"})

    def test_back_facing_is_zero(self):
        rc, out, err = run("eval", "disney_specular", "--wi", "0.3,0,-1", "--wo", "0,0,1", "--json")
        self.assertEqual(rc, 0, err)
        self.assertEqual(json.loads(out)["f_r"], [0.0, 0.0, 0.0])

    def test_text_output(self):
        rc, out, err = run("eval", "lambert", "--wi", "0,0,1", "--wo", "0,0,1", "--set", "kd=0.5")
        self.assertEqual(rc, 0, err)
        self.assertTrue(out.startswith("lambert f_r = "), out)
        self.assertAlmostEqual(float(out.split()[3]), 0.5 / PI, places=9)


class Slice(unittest.TestCase):
    def read(self, *args):
        rc, out, err = run("slice", *args)
        self.assertEqual(rc, 0, err)
        header = [l for l in out.splitlines() if l.startswith("#")]
        body = [l for l in out.splitlines() if not l.startswith("#")]
        return header, list(csv.DictReader(io.StringIO("\n".join(body))))

    def test_csv_is_self_describing(self):
        header, rows = self.read("f_2e", "--csv", "--theta-i", "30", "--steps", "36", "--set", "n=50")
        text = "\n".join(header)
        for word in ("f_2e", "Table 5", "theta_i = 30", "n=50", "ks=1,1,1", "1/sr", "cos theta_o", "rows: 37"):
            self.assertIn(word, text)
        self.assertEqual(list(rows[0].keys()),
                         ["theta_o_deg", "f_r", "f_g", "f_b", "fcos_r", "fcos_g", "fcos_b"])
        self.assertEqual(len(rows), 37)

    def test_rows_angles_and_cosine(self):
        steps = 7  # angles that do not print exactly in few digits
        header, rows = self.read("disney_specular", "--csv", "--theta-i", "40", "--steps", steps,
                                 "--set", "r=0.5")
        self.assertEqual(len(rows), steps + 1)
        for s, row in enumerate(rows):
            th = float(row["theta_o_deg"])
            self.assertAlmostEqual(th, -90.0 + 180.0 * s / steps, places=12)
            c = max(0.0, math.cos(math.radians(th)))
            for ch in "rgb":
                f, fc = float(row["f_" + ch]), float(row["fcos_" + ch])
                self.assertTrue(math.isfinite(f) and f >= 0.0)
                self.assertLessEqual(abs(fc - f * c), 1e-12 * max(f, 1e-300) + 1e-300, row)

    def test_slice_matches_eval(self):
        header, rows = self.read("disney_specular", "--csv", "--theta-i", "40", "--steps", "4",
                                 "--set", "r=0.5")
        ti = math.radians(40.0)
        for row in rows[1:-1]:
            to = math.radians(float(row["theta_o_deg"]))
            g = Geometry([-math.sin(ti), 0.0, math.cos(ti)], [math.sin(to), 0.0, math.cos(to)])
            want = hand_disney_specular(g, 0.5, [0.04] * 3)[0]
            self.assertLess(rel_err(float(row["f_r"]), want), 1e-9)

    def test_mirror_direction_is_the_peak(self):
        header, rows = self.read("blinn_phong", "--csv", "--theta-i", "30", "--steps", "180")
        best = max(rows, key=lambda r: float(r["f_r"]))
        self.assertEqual(float(best["theta_o_deg"]), 30.0)

    def test_table_output(self):
        rc, out, err = run("slice", "lambert", "--steps", "2")
        self.assertEqual(rc, 0, err)
        self.assertEqual(len(out.strip().splitlines()), 2 + 3)


class Errors(unittest.TestCase):
    def fails(self, args, *must_contain):
        rc, out, err = run(*args)
        cmd = "abrdf " + " ".join(str(a) for a in args)
        self.assertEqual(rc, 2, "%s: exit %d (stderr %r)" % (cmd, rc, err))
        self.assertEqual(out, "", cmd)
        self.assertTrue(err.endswith("\n") and err.count("\n") == 1, "%s: not one line: %r" % (cmd, err))
        self.assertTrue(err.startswith("abrdf"), err)
        for s in must_contain:
            self.assertIn(s, err, cmd)
        return err

    W = ["--wi", "0,0,1", "--wo", "0,0,1"]

    def test_unknown_model_suggests_and_lists(self):
        err = self.fails(["eval", "disney_speculr"] + self.W, "'disney_speculr'", "did you mean disney_specular",
                         "lambert", "f_2e", "disney_clearcoat")
        self.fails(["eval", "xyzzy"] + self.W, "'xyzzy'", "models: lambert")
        self.fails(["slice", "blin_phong"], "did you mean blinn_phong")
        self.fails(["eval"] + self.W, "missing model name", "disney_specular")
        self.assertNotIn("\n", err[:-1])

    def test_unknown_parameter(self):
        self.fails(["eval", "lambert", "--set", "r=0.3"] + self.W, "'r'", "lambert", "parameters: kd")
        self.fails(["eval", "disney_specular", "--set", "rough=0.3"] + self.W, "'rough'", "ks, r, f0")
        self.fails(["slice", "f2", "--set", "n"], "NAME=VALUE", "ks, n")

    def test_out_of_range(self):
        self.fails(["eval", "disney_specular", "--set", "r=1.5"] + self.W, "'r'", "1.5", "[0, 1]")
        self.fails(["eval", "f_2e", "--set", "n=0.5"] + self.W, "'n'", "0.5", "[1, 1e+06]")
        self.fails(["eval", "lambert", "--set", "kd=0.5,2,0.5"] + self.W, "'kd'", "[0, 1]")
        self.fails(["eval", "blinn_phong", "--set", "n=-1"] + self.W, "'n'", "[0, 1e+06]")

    def test_nan_and_text_values(self):
        for bad in ("nan", "NaN", "inf", "-inf", "abc", "", "1e400", "0.5x"):
            self.fails(["eval", "disney_specular", "--set", "r=" + bad] + self.W, "'r'", "[0, 1]")
        self.fails(["eval", "lambert", "--set", "kd=0.1,nan,0.2"] + self.W, "'kd'")
        self.fails(["slice", "lambert", "--theta-i", "nan"], "--theta-i", "[0, 90]")
        self.fails(["slice", "lambert", "--steps", "ten"], "--steps")

    def test_malformed_vectors(self):
        for bad in ("0,0", "0,0,1,2", "0,,1", "a,b,c", "0,0,nan", "1e999,0,1", "", "0;0;1"):
            self.fails(["eval", "lambert", "--wi", bad, "--wo", "0,0,1"], "--wi", "X,Y,Z")
        self.fails(["eval", "lambert", "--wi", "0,0,1", "--wo", "0,0,1", "--normal", "0,0,0"], "--normal")
        self.fails(["eval", "lambert", "--wi", "0,0,0", "--wo", "0,0,1"], "--wi", "zero length")

    def test_missing_directions(self):
        self.fails(["eval", "lambert", "--wo", "0,0,1"], "missing --wi", "--wo")
        self.fails(["eval", "lambert", "--wi", "0,0,1"], "missing --wo")
        self.fails(["eval", "lambert", "--wi"], "--wi", "X,Y,Z")

    def test_unknown_options_and_commands(self):
        self.fails(["eval", "lambert", "--wj", "0,0,1"] + self.W, "'--wj'", "--wi")
        self.fails(["models", "--xml"], "'--xml'", "--json")
        self.fails(["slice", "lambert", "--theta", "3"], "'--theta'", "--theta-i")
        self.fails(["modles"], "'modles'", "did you mean models", "eval", "slice")

    def test_no_arguments_is_usage_error(self):
        rc, out, err = run()
        self.assertEqual(rc, 2)
        self.assertIn("usage", err)

    def test_garbage_never_crashes(self):
        rng = random.Random(20240521)
        pieces = ["eval", "slice", "models", "disney_specular", "f2", "--wi", "--wo", "--set",
                  "--normal", "--tangent", "--steps", "--theta-i", "--csv", "--json", "r=", "n=1e6",
                  "0,0,1", "1,1", "nan", "-0", "1e308,1e308,1e308", "=", ",,", "kd=1,1,1",
                  "-", "--", "\t", "x" * 300, "0," * 200, "n=1e-320"]
        for _ in range(150):
            args = [rng.choice(pieces) for _ in range(rng.randint(1, 7))]
            rc, out, err = run(*args)
            self.assertIn(rc, (0, 2), "abrdf %r -> %d: %s" % (args, rc, err[-300:]))
            if rc == 2:
                self.assertEqual(err.count("\n"), 1, "abrdf %r: %r" % (args, err))


class Help(unittest.TestCase):
    def commands(self):
        rc, out, err = run("--help")
        self.assertEqual(rc, 0, err)
        lines = out.splitlines()
        i = lines.index("commands:")
        return [l.split()[0] for l in lines[i + 1:] if l.strip()]

    def test_every_subcommand_has_help(self):
        cmds = self.commands()
        for expected in ("models", "eval", "slice"):
            self.assertIn(expected, cmds)
        for c in cmds:
            for flag in ("--help", "-h"):
                rc, out, err = run(c, flag)
                self.assertEqual(rc, 0, "abrdf %s %s: %s" % (c, flag, err))
                self.assertIn("usage: abrdf " + c, out)

    def test_version(self):
        rc, out, err = run("--version")
        self.assertEqual(rc, 0)
        self.assertRegex(out, r"^abrdf \d+\.\d+\.\d+\n$")


def main():
    global ABRDF
    if len(sys.argv) < 2:
        sys.stderr.write("usage: test_cli.py PATH/TO/abrdf [unittest args]\n")
        return 2
    ABRDF = sys.argv.pop(1)
    prog = unittest.main(exit=False, verbosity=2)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
