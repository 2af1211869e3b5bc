"""huang from a table in POV-Ray: `abrdf export --pov --hair-table` writes each huang
material's table as an EXR image beside the .pov, and abrdf_huang.inc's Abrdf_Huang_Table
reads it texel by texel, interpolated as the library reads its tables (docs/POVRAY.md, "huang
from a table").

Two hair materials (two tables) on a capsule and a sphere under a front and a back light,
one pass per light (POV-Ray's shadows), the passes summed by oiiotool; 12 theta nodes, so that
the read along the lobes' ridges, the read along the theta axes near their ends and the blend
between them all appear; fibres of aspect 0.85 (3 view azimuths, read across their mirrors).
POV-Ray writes EXR as half floats, so the image is compared with `abrdf render --hair-table`
rounded to half floats: equal to the last bit where the port computes what the library does
(measured: NMSE 0). The quadrature per call is far from both (the table is read, not
bypassed). A material edited in the .pov since its table was built, and a table of other
sizes, stop the parse with one line.

usage: test_pov_hair_table.py ABRDF POVRAY OIIOTOOL INCLUDE_DIR WORK_DIR"""
import json
import os
import re
import shutil
import subprocess
import sys
import unittest

ABRDF, POVRAY, OIIOTOOL, INCLUDE, WORK = (None,) * 5
SIZES = "12,3,8,1"
SCENE = ("camera position=0,0,6 look_at=0,0,0 up=0,1,0 fov=30 resolution=48,48\n"
         "light directional direction=-0.45,0.75,0.55 intensity=2.5\n"
         "light directional direction=0.3,-0.2,-0.9 intensity=2\n"
         "material brown table=hair_brown\nmaterial blond table=hair_blond\n"
         "capsule material=brown radius=0.6 height=1.4 tangent=v translate=-0.7,0,0\n"
         "sphere material=blond radius=0.6 tangent=v translate=0.8,0,0\n")


def path(name):
    return os.path.join(WORK, name)


def run(*cmd, cwd=None):
    return subprocess.run(list(cmd), capture_output=True, text=True, cwd=cwd or WORK)


def povray(pov, out, k, cwd=None, *extra):
    """One pass (light k) of pov at the scene's size, no antialiasing."""
    return run(POVRAY, "-D", "+WT2", "+I" + pov, "+O" + out, "+FE", "+W48", "+H48", "-A",
               "+L" + INCLUDE, "Declare=Abrdf_Pass=%d" % k, *extra, cwd=cwd)


def nmse(a, b):
    r = run(ABRDF, "compare", a, b, "--json")
    return json.loads(r.stdout)["nmse"]


class PovHairTable(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        shutil.rmtree(WORK, ignore_errors=True)
        os.makedirs(path("cache"))
        with open(path("hair.scene"), "w") as f:
            f.write(SCENE)
        table = ("--hair-table-sizes", SIZES, "--hair-table-cache", path("cache"))
        for args in [("export", "--pov", path("hair.scene"), "-o", path("hair.pov")) + table,
                     ("render", path("hair.scene"), "-o", path("ref.exr"), "--spp", "1",
                      "--precision", "double", "--no-preview") + table,
                     ("render", path("hair.scene"), "-o", path("per_call.exr"), "--spp", "1",
                      "--precision", "double", "--no-preview")]:
            r = run(ABRDF, *args)
            assert r.returncode == 0, (args, r.stderr)
        for k in range(2):
            r = povray(path("hair.pov"), path("pass_%d.exr" % k), k)
            assert r.returncode == 0, r.stderr
        for cmd in [(path("pass_0.exr"), path("pass_1.exr"), "--add", "-o", path("pov.exr")),
                    (path("ref.exr"), "-d", "half", "-o", path("ref_half.exr"))]:
            r = run(OIIOTOOL, *cmd)
            assert r.returncode == 0, r.stderr
        with open(path("hair.pov")) as f:
            cls.pov = f.read()

    def test_the_tables_are_written_beside_the_file(self):
        calls = re.findall(r'^#declare Abrdf_Mat_(\d) = Abrdf_Huang_Table\(Abrdf_Mat_\1, '
                           r'"([^"]+)", 12, 3, 8, ([0-9.e+]+), Abrdf_Mat_\1_Built\)$',
                           self.pov, re.M)
        self.assertEqual([c[:2] for c in calls],
                         [("0", "hair.huang0.exr"), ("1", "hair.huang1.exr")])
        for _, name, scale in calls:
            self.assertTrue(os.path.isfile(path(name)))
            s = float(scale)
            self.assertEqual(s, 2.0 ** round(__import__("math").log2(s)))  # a power of two
        # rendered from another directory with +L naming this one: the same pass
        elsewhere = path("elsewhere")
        os.makedirs(elsewhere, exist_ok=True)
        r = povray(path("hair.pov"), os.path.join(elsewhere, "pass_0.exr"), 0, elsewhere,
                   "+L" + WORK)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(nmse(path("pass_0.exr"), os.path.join(elsewhere, "pass_0.exr")), 0)

    def test_the_table_is_read_as_the_library_reads_it(self):
        exact = nmse(path("ref_half.exr"), path("pov.exr"))
        to_float = nmse(path("ref.exr"), path("pov.exr"))
        far = nmse(path("per_call.exr"), path("pov.exr"))
        sys.stderr.write("\nhuang from a table, POV-Ray against abrdf render: NMSE %.1e against "
                         "its half floats, %.1e against its floats (per call: %.1e)\n"
                         % (exact, to_float, far))
        self.assertLess(exact, 1e-10)
        self.assertGreater(far, 1e-5)

    def edited(self, old, new, name):
        self.assertEqual(self.pov.count(old), 1, old)
        with open(path(name), "w") as f:
            f.write(self.pov.replace(old, new))
        out = path(name + ".exr")
        r = povray(path(name), out, 0)
        self.assertNotEqual(r.returncode, 0)
        self.assertFalse(os.path.exists(out))
        return " ".join((r.stdout + r.stderr).split())  # POV-Ray wraps its messages

    def test_an_edited_material_is_refused(self):
        line = re.search(r"^#declare Abrdf_Mat_1\[ABRDF_SLOT_MELANIN \+ 0\] = .*$", self.pov,
                         re.M).group(0)
        log = self.edited(line, "#declare Abrdf_Mat_1[ABRDF_SLOT_MELANIN + 0] = 0.5;",
                          "edited.pov")
        self.assertIn("Abrdf_Huang_Table: hair.huang1.exr was built for melanin = 0.260000, "
                      "the material has 0.500000: export the scene again", log)

    def test_a_table_of_other_sizes_is_refused(self):
        log = self.edited('"hair.huang0.exr", 12, 3, 8,', '"hair.huang0.exr", 12, 1, 8,',
                          "resized.pov")
        self.assertIn("Abrdf_Huang_Table: hair.huang0.exr is 96 x 108 texels, not 96 x 36", log)


if __name__ == "__main__":
    ABRDF, POVRAY, OIIOTOOL, INCLUDE, WORK = sys.argv[1:6]
    del sys.argv[1:6]
    unittest.main(verbosity=2)
