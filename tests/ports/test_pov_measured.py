#!/usr/bin/env python3
"""A measured material in POV-Ray (docs/MEASURED.md, "In other renderers"): POV-Ray cannot read
the table, so `abrdf export --pov` writes the stand-in fitted to it, with its fit's errors as a
comment; the real povray binary renders that within the Table-8 class "no visible difference"
of `abrdf render` of the table itself, and the stand-in recovers the table's model.

    test_pov_measured.py ABRDF POVRAY INCLUDE_DIR WORK_DIR
"""
import json
import os
import re
import subprocess
import sys
import unittest

ABRDF, POVRAY, INC, WORK = sys.argv[1:5]
del sys.argv[1:5]

SCENE = """camera position=0,0,4 look_at=0,0,0 up=0,1,0 fov=30 resolution=32,32
light directional direction=-1,1,1 color=1,1,1 intensity=3
ambient 0
material m measured=spec.binary {extra}
sphere material=m radius=1
"""


def run(*args):
    p = subprocess.run(list(args), capture_output=True, text=True, timeout=600)
    if p.returncode:
        raise AssertionError("%s -> %d: %s" % (" ".join(args), p.returncode, p.stderr))
    return p.stdout


class PovMeasured(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        os.makedirs(WORK, exist_ok=True)
        run(ABRDF, "tabulate", "disney_specular", "--set", "r=0.35", "--set", "f0=0.04", "-o",
            os.path.join(WORK, "spec.binary"))

    def check(self, name, extra, nmse_max):
        scene = os.path.join(WORK, name + ".scene")
        with open(scene, "w") as f:
            f.write(SCENE.format(extra=extra))
        ref, pov, img = (os.path.join(WORK, name + s) for s in ("_ref.exr", ".pov", "_pov.exr"))
        # pixel centres in both: one sample per pixel, POV-Ray without antialiasing
        run(ABRDF, "render", scene, "-o", ref, "--spp", "1", "--precision", "double",
            "--no-preview")
        run(ABRDF, "export", "--pov", scene, "-o", pov)
        with open(pov) as f:
            text = f.read()
        note = re.search(r"^// material m: the host cannot read the measured table .*$", text, re.M)
        self.assertIsNotNone(note, text[:2000])
        r = float(re.search(r"\br ([0-9.]+)", note.group(0)).group(1))
        self.assertAlmostEqual(r, 0.35, delta=0.01)  # the stand-in is the table's model
        run(POVRAY, "-D", "+WT1", "+I" + pov, "+O" + img, "+FE", "+W32", "+H32", "-A",
            "+L" + INC)
        out = json.loads(run(ABRDF, "compare", ref, img, "--json"))
        print("%s: NMSE of POV-Ray's stand-in against the measured table %.3g" % (name, out["nmse"]))
        self.assertLess(out["nmse"], nmse_max)
        return note.group(0)

    def test_table_under_a_lambert_term(self):
        note = self.check("kd", "kd=0.18,0.30,0.60", 1e-5)
        self.assertIn("lambert (the material's) + ", note)

    def test_table_alone(self):
        # the fit chooses the diffuse term too (here the table has none: kd near 0)
        self.check("alone", "", 1e-4)


if __name__ == "__main__":
    unittest.main(verbosity=2)
