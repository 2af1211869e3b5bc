#!/usr/bin/env python3
"""test_cli_sample.py - `abrdf sample` and the samplers `abrdf models --json` names:
the JSON-lines and text outputs, weights against `abrdf eval` (weight = f_r max(0, N.wi) /
pdf), closed forms (Lambert's weight is kd, its pdf N.wi/pi), frames, seeds, and the
one-line error contract (exit status 2, nothing on stdout).

    python3 test_cli_sample.py PATH/TO/abrdf        (CTest passes the built binary)

Python 3 standard library only."""
import json
import math
import subprocess
import sys
import unittest

ABRDF = None  # set from argv in main


def run(*args):
    p = subprocess.run([ABRDF] + [str(a) for a in args], stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, universal_newlines=True, timeout=120)
    return p.returncode, p.stdout, p.stderr


def samples(*args):
    rc, out, err = run("sample", *args, "--json")
    if rc != 0:
        raise AssertionError("abrdf sample %r -> %d: %s" % (args, rc, err))
    return [json.loads(line) for line in out.splitlines()]


def vec(v):
    return ",".join(repr(x) for x in v)


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def norm(v):
    l = math.sqrt(dot(v, v))
    return [x / l for x in v]


class Sample(unittest.TestCase):
    def test_json_lines(self):
        s = samples("disney_specular", "--wo", "0.3,0.1,1", "-n", "300", "--set", "r=0.4")
        self.assertEqual(len(s), 300)
        for x in s:
            self.assertEqual(set(x), {"wi", "pdf", "weight"})
            self.assertAlmostEqual(math.sqrt(dot(x["wi"], x["wi"])), 1.0, places=12)
            self.assertGreater(x["pdf"], 0.0)
            for w in x["weight"]:
                self.assertTrue(math.isfinite(w) and w >= 0.0)
                if x["wi"][2] <= 0.0:
                    self.assertEqual(w, 0.0)  # below the surface: weight 0, still printed

    def test_weight_is_eval_cos_over_pdf(self):
        # One model per sampler (the first that names it; the library's suites test every
        # model), a frame with a tilted normal and a tangent: `abrdf eval` of each sampled
        # direction gives f_r; weight = f_r max(0, N.wi) / pdf.
        n, t, wo = [0.2, -0.3, 1.0], [1.0, 0.4, 0.0], [0.5, 0.2, 0.9]
        nn = norm(n)
        rc, out, err = run("models", "--json")
        names, seen = [], set()
        for m in json.loads(out)["models"]:  # (the measured model: test_cli_measured.py)
            if m["sampler"]["name"] not in seen and "table" not in m["needs"]:
                seen.add(m["sampler"]["name"])
                names.append(m["name"])
        for name in names:
            count = "2"
            for x in samples(name, "--wo", vec(wo), "-n", count, "--normal", vec(n),
                             "--tangent", vec(t), "--seed", "7"):
                rc, out, err = run("eval", name, "--wi", vec(x["wi"]), "--wo", vec(wo),
                                   "--normal", vec(n), "--tangent", vec(t), "--json")
                self.assertEqual(rc, 0, err)
                f = json.loads(out)["f_r"]
                cos_i = max(0.0, dot(nn, x["wi"]))
                for c in range(3):
                    want = f[c] * cos_i / x["pdf"]
                    self.assertLessEqual(abs(x["weight"][c] - want), 1e-9 * max(want, 1e-300),
                                         "%s: weight %r, f cos / pdf %r" % (name, x["weight"], want))

    def test_lambert_closed_form(self):
        # cosine-weighted: pdf = N.wi / pi and weight = kd exactly, in any frame
        n = norm([0.0, 1.0, 0.3])
        for x in samples("lambert", "--wo", "0.2,1,0.5", "--normal", vec(n), "-n", "200",
                         "--set", "kd=0.2,0.4,0.8"):
            self.assertAlmostEqual(x["pdf"], dot(n, x["wi"]) / math.pi, places=12)
            for w, kd in zip(x["weight"], (0.2, 0.4, 0.8)):
                self.assertAlmostEqual(w, kd, places=12)

    def test_seed_repeats_and_varies(self):
        a = run("sample", "phong", "--wo", "0,0.3,1", "-n", "20", "--seed", "5")
        b = run("sample", "phong", "--wo", "0,0.3,1", "-n", "20", "--seed", "5")
        c = run("sample", "phong", "--wo", "0,0.3,1", "-n", "20", "--seed", "6")
        self.assertEqual(a, b)
        self.assertNotEqual(a[1], c[1])

    def test_text_output(self):
        rc, out, err = run("sample", "kajiya_kay", "--wo", "0.1,0.2,1", "-n", "5")
        self.assertEqual(rc, 0, err)
        lines = out.splitlines()
        self.assertTrue(lines[0].startswith("# abrdf sample kajiya_kay: wi_x"))
        self.assertEqual(len(lines), 6)
        for l in lines[1:]:
            self.assertEqual(len([float(v) for v in l.split()]), 7)

    def test_every_model_names_its_sampler(self):
        rc, out, err = run("models", "--json")
        self.assertEqual(rc, 0, err)
        for m in json.loads(out)["models"]:
            s = m["sampler"]
            self.assertRegex(s["name"], r"^[a-z0-9_]+$", m["name"])
            self.assertTrue(s["method"] and s["citation"], m["name"])
            self.assertIsInstance(s["mixture"], bool)
            self.assertIsInstance(s["below_surface"], bool)
        models = {m["name"]: m["sampler"] for m in json.loads(out)["models"]}
        self.assertEqual(models["lambert"]["name"], "cosine")
        self.assertEqual(models["disney_specular"]["name"], "ggx_vndf")
        self.assertTrue(models["neubelt_pettineo"]["mixture"])
        self.assertFalse(models["lambert"]["below_surface"])


class Errors(unittest.TestCase):
    def fails(self, args, *needles):
        rc, out, err = run(*args)
        self.assertEqual(rc, 2, "abrdf %r -> %d" % (args, rc))
        self.assertEqual(out, "", "abrdf %r printed to stdout" % (args,))
        self.assertEqual(err.count("\n"), 1, "abrdf %r: %r" % (args, err))
        for n in needles:
            self.assertIn(n, err)

    def test_bad_input_is_one_line_exit_2(self):
        W = ["--wo", "0,0,1"]
        self.fails(["sample", "lambert"], "missing --wo")
        self.fails(["sample"] + W, "missing model name")
        self.fails(["sample", "lambrt"] + W, "did you mean lambert")
        self.fails(["sample", "lambert", "--wo", "0.2,0,-1"], "below the surface")
        self.fails(["sample", "lambert", "--wo", "0,0,1", "--normal", "0,0,-1"], "below the surface")
        self.fails(["sample", "lambert", "--wo", "0,0,0"], "--wo", "no direction")
        self.fails(["sample", "lambert", "--wo", "0,nan,1"], "--wo", "X,Y,Z")
        self.fails(["sample", "lambert", "--wo", "0,1"], "--wo", "X,Y,Z")
        self.fails(["sample", "lambert"] + W + ["--normal", "0,0,0"], "--normal")
        for bad in ("0", "-1", "ten", "1e3", "10000001"):
            self.fails(["sample", "lambert"] + W + ["-n", bad], "-n", "[1, 10000000]")
        self.fails(["sample", "lambert"] + W + ["-n"], "-n")
        self.fails(["sample", "lambert"] + W + ["--seed", "-1"], "--seed")
        self.fails(["sample", "lambert"] + W + ["--seed", "x"], "--seed")
        self.fails(["sample", "lambert"] + W + ["--set", "r=0.3"], "'r'", "parameters: kd")
        self.fails(["sample", "disney_specular"] + W + ["--set", "r=2"], "'r'", "[0, 1]")
        self.fails(["sample", "lambert"] + W + ["--wi", "0,0,1"], "'--wi'", "--wo")
        self.fails(["sample", "lambert", "phong"] + W, "'phong'")

    def test_help(self):
        rc, out, err = run("sample", "--help")
        self.assertEqual(rc, 0)
        self.assertIn("usage: abrdf sample MODEL --wo X,Y,Z", out)
        rc, out, err = run("--help")
        self.assertIn("sample", out)


def main():
    global ABRDF
    if len(sys.argv) < 2:
        sys.stderr.write("usage: test_cli_sample.py PATH/TO/abrdf [unittest args]\n")
        return 2
    ABRDF = sys.argv.pop(1)
    prog = unittest.main(exit=False, verbosity=2)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
