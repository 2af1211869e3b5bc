"""Measured BRDFs through the command (docs/MEASURED.md, "Files"): `abrdf tabulate` writes a
model on the measured grid as a MERL BRDF file of the exact size, with the values, noise and
holes its help states, deterministically per seed; `abrdf inspect` reads it back; bad arguments
and bad files are refused in one line, with nothing written.

Run by CTest with ABRDF (the command) in the environment."""
import json
import math
import os
import struct
import subprocess
import unittest

from clitest import TempDirCase, checked_stderr

ABRDF = os.environ["ABRDF"]
SCALES = (1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0)


def run(*args, timeout=120):
    p = subprocess.run([ABRDF, *args], capture_output=True, timeout=timeout)
    return p.returncode, p.stdout.decode(), checked_stderr(p)


def read_merl(path):
    """(grid, [red, green, blue] lists of f_r or None for cells not measured)."""
    with open(path, "rb") as f:
        data = f.read()
    grid = struct.unpack_from("<iii", data)
    n = grid[0] * grid[1] * grid[2]
    assert len(data) == 12 + 24 * n
    values = struct.unpack_from("<%dd" % (3 * n), data, 12)
    return grid, [[v * SCALES[c] if v >= 0 else None for v in values[c * n:(c + 1) * n]]
                  for c in range(3)]


class Base(TempDirCase):
    def fails(self, rc_expected, args, *needles):
        rc, out, err = run(*args)
        self.assertEqual(rc, rc_expected, (args, err))
        self.assertEqual(err.count("\n"), 1, err)
        for n in needles:
            self.assertIn(n, err)
        return err

    def tabulate(self, name, *args):
        path = self.path(name)
        rc, out, err = run("tabulate", *args, "-o", path)
        self.assertEqual(rc, 0, err)
        return path

    def inspect(self, path):
        rc, out, err = run("inspect", path, "--json")
        self.assertEqual(rc, 0, err)
        return json.loads(out)


class Tabulate(Base):
    def test_default_grid_is_merls(self):
        path = self.tabulate("l.binary", "lambert", "--set", "kd=0.5")
        self.assertEqual(os.path.getsize(path), 12 + 24 * 90 * 90 * 180)
        rc, out, err = run("inspect", path)
        self.assertEqual(rc, 0, err)
        self.assertIn("grid: 90 x 90 x 180", out)
        # the cells with the light or the view below the horizon (theta_h + theta_d > 90)
        self.assertIn("not measured: 346568 cells", out)
        info = self.inspect(path)
        self.assertEqual(info["grid"], [90, 90, 180])
        self.assertEqual(info["cells"], 90 * 90 * 180)
        self.assertEqual(info["unmeasured"], 346568)
        for c in range(3):
            self.assertAlmostEqual(info["max_f_r"][c], 0.5 / math.pi, places=6)
            self.assertAlmostEqual(info["albedo_normal"][c], 0.5, places=3)

    def test_values_are_the_models(self):
        """Lambert: kd/pi in every cell seen from above the horizon; the others not measured."""
        path = self.tabulate("s.binary", "lambert", "--set", "kd=0.2,0.4,0.8", "--grid",
                             "8,8,16")
        grid, ch = read_merl(path)
        self.assertEqual(grid, (8, 8, 16))
        below = 0
        for c, kd in enumerate((0.2, 0.4, 0.8)):
            for v in ch[c]:
                if v is None:
                    below += 1
                else:
                    self.assertAlmostEqual(v, kd / math.pi, delta=1e-7)
        self.assertGreater(below, 0)  # grazing cells: a direction below the horizon
        self.assertLess(below, 3 * 8 * 8 * 16 // 2)

    def test_holes_and_noise_are_deterministic(self):
        args = ("cook_torrance", "--set", "r=0.4", "--grid", "8,8,16")
        plain = self.tabulate("p.binary", *args)
        a = self.tabulate("a.binary", *args, "--noise", "0.2", "--holes", "0.25", "--seed", "7")
        b = self.tabulate("b.binary", *args, "--noise", "0.2", "--holes", "0.25", "--seed", "7")
        c = self.tabulate("c.binary", *args, "--noise", "0.2", "--holes", "0.25", "--seed", "8")
        with open(a, "rb") as fa, open(b, "rb") as fb, open(c, "rb") as fc:
            da, db, dc = fa.read(), fb.read(), fc.read()
        self.assertEqual(da, db)
        self.assertNotEqual(da, dc)
        _, p = read_merl(plain)
        _, n = read_merl(a)
        missing = sum(1 for i in range(len(n[0])) if n[0][i] is None)
        self.assertEqual(self.inspect(a)["unmeasured"], missing)
        below = sum(1 for i in range(len(p[0])) if p[0][i] is None)  # the horizon's cells
        self.assertLess(abs((missing - below) / (len(n[0]) - below) - 0.25), 0.05)
        for c in range(3):  # a hole is one in every channel
            self.assertEqual([v is None for v in n[c]], [v is None for v in n[0]])
        logs = [math.log(n[c][i] / p[c][i]) for c in range(3) for i in range(len(p[0]))
                if n[c][i] is not None and p[c][i] is not None and p[c][i] > 0]
        mean = sum(logs) / len(logs)
        sd = math.sqrt(sum((x - mean) ** 2 for x in logs) / len(logs))
        self.assertLess(abs(mean + 0.5 * 0.2 ** 2), 0.02)  # log f' = log f + sigma z - sigma^2/2
        self.assertLess(abs(sd - 0.2), 0.02)

    def test_all_holes(self):
        path = self.tabulate("h.binary", "lambert", "--grid", "2,2,2", "--holes", "1")
        info = self.inspect(path)
        self.assertEqual(info["unmeasured"], 8)
        self.assertIsNone(info["albedo_normal"])
        self.assertEqual(info["max_f_r"], [None, None, None])

    def test_bad_arguments(self):
        out = self.path("x.binary")
        for args, needle in (
                (["tabulate", "-o", out], "model"),
                (["tabulate", "lambert"], "missing -o FILE"),
                (["tabulate", "lambert", "-o", self.path("x.png")], "'.png' is not"),
                (["tabulate", "lambert", "--noise", "0.1", "-o", self.path("x.bsdf")],
                 "apply to .binary files"),
                (["tabulate", "lambert", "-o", self.path("x")], "no extension"),
                (["tabulate", "lambrt", "-o", out], "did you mean lambert"),
                (["tabulate", "lambert", "--grid", "1,90,180", "-o", out], "[2, 1024]"),
                (["tabulate", "lambert", "--grid", "90,90", "-o", out], "three whole numbers"),
                (["tabulate", "lambert", "--grid", "1024,1024,1024", "-o", out], "cells"),
                (["tabulate", "lambert", "--noise", "-0.1", "-o", out], "--noise"),
                (["tabulate", "lambert", "--noise", "nan", "-o", out], "--noise"),
                (["tabulate", "lambert", "--holes", "1.5", "-o", out], "--holes"),
                (["tabulate", "lambert", "--seed", "-1", "-o", out], "--seed"),
                (["tabulate", "lambert", "--set", "kd=2", "-o", out], "kd"),
                (["tabulate", "lambert", "--set", "nope=1", "-o", out], "nope"),
                (["tabulate", "lambert", "--frobnicate", "-o", out], "unknown option"),
                (["tabulate", "lambert", "phong", "-o", out], "one model only"),
                (["tabulate", "lambert", "-o", out, "-o", out], "given twice")):
            self.fails(2, args, needle)
        self.fails(1, ["tabulate", "lambert", "-o", self.path("no/dir/x.binary")], "x.binary")
        self.assertEqual(os.listdir(self.dir), [])


class Inspect(Base):
    def put_merl(self, name, grid, values, extra=b""):
        return self.put(name, struct.pack("<iii", *grid) +
                        struct.pack("<%dd" % len(values), *values) + extra)

    def test_reads_a_file(self):
        values = [1500.0] * 8 + [-1.0] + [1500.0] * 15
        info = self.inspect(self.put_merl("ok.binary", (2, 2, 2), values))
        self.assertEqual(info["grid"], [2, 2, 2])
        self.assertEqual(info["unmeasured"], 1)
        self.assertAlmostEqual(info["max_f_r"][1], 1.15, places=6)
        self.assertAlmostEqual(info["max_f_r"][2], 1.66, places=6)

    def test_bad_files(self):
        os.mkdir(self.path("d.binary"))
        ok = [1.0] * 24
        for name, data, needle in (
                ("short.binary", b"\x02\x00", "shorter than the 12-byte header"),
                ("absurd.binary", struct.pack("<iii", 90, 0, 180), "absurd sizes"),
                ("cut.binary", struct.pack("<iii", 2, 2, 2) + struct.pack("<23d", *ok[:23]),
                 "truncated"),
                ("tail.binary", struct.pack("<iii", 2, 2, 2) + struct.pack("<24d", *ok) + b"x",
                 "1 trailing bytes"),
                ("nan.binary", struct.pack("<iii", 2, 2, 2) +
                 struct.pack("<24d", *(ok[:9] + [math.nan] + ok[10:])), "green channel, cell 1")):
            path = self.put(name, data)
            self.fails(1, ["inspect", path], path + ": ", needle)
        self.fails(1, ["inspect", self.path("d.binary")], "is a directory")
        self.fails(1, ["inspect", self.path("none.binary")], "cannot open")
        self.fails(1, ["inspect", self.put("x.bsdf", b"")], "too short for a tensor file")
        self.fails(2, ["inspect", self.put("x.png", b"")], "'.png' is not")

    def test_rgl_file_round_trip(self):
        # a model written as an RGL file reads back onto MERL's grid: Lambert's kd / pi
        path = self.path("l.bsdf")
        rc, out, err = run("tabulate", "lambert", "--set", "kd=0.5", "-o", path)
        self.assertEqual(rc, 0, err)
        self.assertTrue(os.path.getsize(path) > 1000)
        rc, out, err = run("inspect", path, "--json")
        self.assertEqual(rc, 0, err)
        info = json.loads(out)
        self.assertEqual(info["grid"], [90, 90, 180])
        # (the largest f_r is the writer's coarse tabulation near the horizon, docs/MEASURED.md)
        for c in range(3):
            self.assertAlmostEqual(info["albedo_normal"][c], 0.5, delta=0.005)
        self.fails(2, ["inspect"], "missing FILE")


SCENE = """camera position=0,0,4 look_at=0,0,0 up=0,1,0 fov=30 resolution=64,64
light directional direction=-1,1,1 color=1,1,1 intensity=3
light point position=2,1,3 color=1,0.9,0.8 intensity=4
ambient 0
{material}
sphere material=m radius=1
"""


class Render(Base):
    """`material NAME measured=FILE [kd=...]` in a scene (docs/MEASURED.md, "In a scene")."""

    def render(self, name, material, *extra):
        scene = self.path(name + ".scene")
        with open(scene, "w") as f:
            f.write(SCENE.format(material=material))
        out = self.path(name + ".exr")
        rc, stdout, err = run("render", scene, "-o", out, *extra)
        self.assertEqual(rc, 0, err)
        return out, stdout + err

    def nmse(self, a, b):
        rc, out, err = run("compare", a, b, "--json")
        self.assertEqual(rc, 0, err)
        return json.loads(out)["nmse"]

    def test_table_renders_as_its_model(self):
        # a table written from disney_specular under a Lambert term given as kd= renders as the
        # analytic pair: the grid's interpolation error only (bound stated in MEASURED.md)
        self.tabulate("s.binary", "disney_specular", "--set", "r=0.35", "--set", "f0=0.04")
        data, err = self.render("data", "material m measured=s.binary kd=0.18,0.30,0.60",
                                "--explain")
        self.assertIn("lambert + measured", err)
        self.assertIn("measured table: ", err)
        self.assertIn("90 x 90 x 180 cells", err)
        model, _ = self.render("model", "material m diffuse=lambert specular=disney_specular "
                                        "kd=0.18,0.30,0.60 r=0.35 f0=0.04")
        self.assertLess(self.nmse(model, data), 1e-6)
        # the same under the double reference path
        dd, _ = self.render("dd", "material m measured=s.binary kd=0.18,0.30,0.60",
                            "--precision", "double")
        self.assertLess(self.nmse(data, dd), 1e-8)

    def test_exports_write_the_fitted_stand_in(self):
        # the hosts cannot read a table: both exports carry the stand-in and say so
        # (POV-Ray renders it: tests/ports/test_pov_measured.py)
        self.tabulate("s.binary", "cook_torrance", "--set", "r=0.4", "--grid", "45,45,90")
        scene = self.path("e.scene")
        with open(scene, "w") as f:
            f.write(SCENE.format(material="material m measured=s.binary"))
        for flag, ext, comment in (("--pov", ".pov", "//"), ("--cycles", ".py", "#")):
            out = self.path("e" + ext)
            rc, _, err = run("export", flag, scene, "-o", out)
            self.assertEqual(rc, 0, err)
            with open(out) as f:
                text = f.read()
            self.assertRegex(text, comment + r" material m: the host cannot read the measured "
                             r"table .*s\.binary.*fitted stand-in \w+ \+ \w+, fit rel\. L2")
            self.assertNotIn("measured", text.split("fitted stand-in")[1].split("\n")[0])

    def test_model_override_drops_the_table(self):
        # --model replaces every material's lobes: the table is no longer read or named
        self.tabulate("s.binary", "lambert", "--grid", "8,8,16")
        _, text = self.render("o", "material m measured=s.binary", "--model", "lambert",
                              "--explain")
        self.assertIn("m (line 5): lambert", text)
        self.assertNotIn("measured table", text)
        scene = self.path("o.scene")
        self.fails(2, ["render", scene, "-o", self.path("x.exr"), "--model", "measured"],
                   "reads a table")
        self.fails(1, ["render", scene, "-o", self.path("x.exr"), "--adaptive", "--goal",
                       "photoreal"], "is measured", "advise --measured")

    def test_bad_materials(self):
        self.tabulate("s.binary", "lambert", "--grid", "8,8,16")
        for material, needle in (
                ("material m measured=none.binary", "cannot open"),
                ("material m measured=s.png", "'.png' is not"),
                ("material m measured=s.binary specular=disney_specular", "drop model=/specular="),
                ("material m measured=s.binary diffuse=disney_specular", "not a diffuse model"),
                ("material m measured=s.binary r=0.3", "not used by the material"),
                ("material m table=gold measured=s.binary", "drop model=/diffuse=/specular=/measured="),
                ("material m model=measured", "names its table: measured=FILE"),
                ("material m diffuse=measured measured=s.binary", "names its table"),
                ("material m adaptive budget=slight r=0.3 measured=s.binary",
                 "drop model=/diffuse=/specular=/measured=")):
            scene = self.path("bad.scene")
            with open(scene, "w") as f:
                f.write(SCENE.format(material=material))
            self.fails(1, ["render", scene, "-o", self.path("bad.exr")], "bad.scene:5:", needle)
            self.assertFalse(os.path.exists(self.path("bad.exr")))


if __name__ == "__main__":
    unittest.main()
