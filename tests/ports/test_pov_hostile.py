"""The POV-Ray export of a hostile scene, rendered by the real povray, creates no file and still
matches `abrdf render`; and scenes with table= and adaptive materials export to POV-Ray as
what abrdf render renders.

The hostile scene lives in a directory whose name holds a line break followed by POV-Ray file
directives (#fopen/#write: if the path reached the SDL unescaped, POV-Ray would create a
file), and its materials are named to end the check string early and add geometry
(a")box{-9,9}//), to break POV-Ray's parse (x\\q) and to close a triple quote. The renders
compare as in pov_scene_check.c: abrdf at --spp 4, POV-Ray at twice the resolution without
antialiasing, 2 x 2 blocks averaged, NMSE < 1e-4 (the paper's "no visible difference").

usage: test_pov_hostile.py ABRDF POVRAY INCLUDE_DIR WORK_DIR  (system python3: OpenImageIO)"""
import os
import shutil
import subprocess
import sys
import unittest

import numpy as np
import OpenImageIO as oiio

ABRDF, POVRAY, INCLUDE, WORK = (None,) * 4
SIZE, K, BAR = 24, 2, 1e-4

# Were a comment cut at the line breaks, this would parse: the directives would run, write
# the file "pwned" and the render would still succeed, so the test would see the file.
HOSTILE_DIR = (b'h\n#fopen F "pwned" write #write(F,"x") #fclose F\n// "\'\\ '
               b'\xc3\xa9\xff#')
HOSTILE_NAMES = ['a")box{-9,9}//', "x\\q", 'q"""']


def read(path):
    buf = oiio.ImageBuf(os.fsdecode(path))
    px = buf.get_pixels(oiio.FLOAT)
    assert px is not None and px.size, buf.geterror()
    return px.astype(np.float64)[:, :, :3]


def every_file(top):
    out = set()
    for root, _, files in os.walk(top):
        out |= {os.path.join(root, f) for f in files}
    return out


class PovHostile(unittest.TestCase):
    def compare(self, scene, name, *export_args):
        """abrdf render vs povray on the export; returns the files povray created."""
        ref, pov, big = (os.path.join(WORK, name + s) for s in ("_ref.exr", ".pov", "_pov.exr"))
        r = subprocess.run([ABRDF, "render", scene, "-o", ref, "--width", str(SIZE), "--height",
                            str(SIZE), "--spp", str(K * K), "--no-preview", *export_args],
                           capture_output=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        r = subprocess.run([ABRDF, "export", "--pov", scene, "-o", pov, "--width", str(SIZE),
                            "--height", str(SIZE), *export_args], capture_output=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        before = every_file(WORK)
        r = subprocess.run([POVRAY, "-D", "+WT1", "+I" + pov, "+O" + big, "+FE",
                            "+W%d" % (K * SIZE), "+H%d" % (K * SIZE), "-A", "+L" + INCLUDE],
                           capture_output=True, cwd=WORK)
        self.assertEqual(r.returncode, 0, r.stderr.decode(errors="replace")[-2000:])
        created = every_file(WORK) - before
        a = read(ref)
        b = read(big).reshape(SIZE, K, SIZE, K, 3).mean(axis=(1, 3))
        nmse = ((b - a) ** 2).sum() / (a ** 2).sum()
        print("%s: NMSE %.2e" % (name, nmse))
        self.assertLess(nmse, BAR, name)
        return created - {big}

    def test_hostile_export_creates_nothing_and_matches(self):
        d = os.fsencode(WORK) + b"/" + HOSTILE_DIR
        os.makedirs(d, exist_ok=True)
        scene = d + b"/s#1.scene"
        lines = ["camera position=0,0,4 look_at=0,0,0 resolution=24,24",
                 "light directional direction=-1,1,1 intensity=3", "ambient 0.05"]
        for i, n in enumerate(HOSTILE_NAMES):
            lines.append("material %s diffuse=lambert specular=blinn_phong kd=0.%d n=%d" %
                         (n, 3 + 2 * i, 10 + 20 * i))
        for i, n in enumerate(HOSTILE_NAMES):
            lines.append("sphere material=%s radius=0.55 translate=%g,0,0" % (n, -1.2 + 1.2 * i))
        with open(scene, "w") as f:
            f.write("\n".join(lines) + "\n")
        created = self.compare(scene, "hostile")
        self.assertEqual(created, set(), "POV-Ray created files")
        self.assertFalse(any(os.path.basename(os.fsencode(p)) == b"pwned"
                             for p in every_file(WORK)))

    def test_table_and_adaptive_materials_export_as_rendered(self):
        scene = os.path.join(WORK, "select.scene")
        with open(scene, "w") as f:
            f.write("camera position=0,0,4 look_at=0,0,0 resolution=24,24\n"
                    "light directional direction=-1,1,1 intensity=3\n"
                    "material gold table=gold\n"
                    "material auto adaptive goal=performance r=0.3 kd=0.5\n"
                    "sphere material=gold radius=0.6 translate=-0.7,0,0\n"
                    "sphere material=auto radius=0.6 translate=0.7,0,0\n")
        self.assertEqual(self.compare(scene, "select"), set())
        robot = os.path.join(os.path.dirname(INCLUDE), "scenes", "robot.scene")
        self.assertEqual(self.compare(robot, "robot_adaptive", "--adaptive", "--goal",
                                      "performance"), set())


if __name__ == "__main__":
    ABRDF, POVRAY, INCLUDE, WORK = sys.argv[1:5]
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    unittest.main(argv=sys.argv[:1])
