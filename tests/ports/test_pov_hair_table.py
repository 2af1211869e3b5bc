"""huang from a table in POV-Ray: `abrdf export --pov --hair-table` writes each huang
material's table as an EXR image beside the .pov, and abrdf_huang.inc's Abrdf_Huang_Table
reads it texel by texel, interpolated as the library reads its tables (docs/POVRAY.md, "huang
from a table").

Three scenes, each light one POV-Ray pass (its shadows) against `abrdf render --hair-table`
of the scene with that light alone:
- hair: two hair materials (two tables) on a capsule and a sphere under a front and a back
  light; 12 theta nodes, so that the read along the lobes' ridges, the read along the theta
  axes near their ends and the blend between them all appear; fibres of aspect 0.85 (3 view
  azimuths, read across their mirrors);
- round: round fibres (one view azimuth: the read without the view's stencil), cuticle
  tilts of +-10 degrees, a light near the fibres' axis; huang as the second lobe of a
  material (lambert + huang); and a third material of the first's parameters, which reads
  the first's image;
- graze: fibres seen at grazing angles with tilts of +-10 degrees, where the tilt hides the
  mesonormal from the view.
POV-Ray writes EXR as half floats, so each pass is compared with the render rounded to half
floats: equal to the last bit where the port computes what the library does (measured: NMSE
0 in every pass). The quadrature per call is far from the table's image (the table is read,
not bypassed). A material edited in the .pov since its table was built, and a table of other
sizes, stop the parse with one line.

usage: test_pov_hair_table.py ABRDF POVRAY OIIOTOOL INCLUDE_DIR WORK_DIR"""
import json
import math
import os
import re
import shutil
import subprocess
import sys
import unittest

ABRDF, POVRAY, OIIOTOOL, INCLUDE, WORK = (None,) * 5
CAMERA = "camera position=0,0,6 look_at=0,0,0 up=0,1,0 fov=30 resolution=48,48\n"
SCENES = {
    "hair": ("12,3,8,1", CAMERA +
             "light directional direction=-0.45,0.75,0.55 intensity=2.5\n"
             "light directional direction=0.3,-0.2,-0.9 intensity=2\n"
             "material brown table=hair_brown\nmaterial blond table=hair_blond\n"
             "capsule material=brown radius=0.6 height=1.4 tangent=v translate=-0.7,0,0\n"
             "sphere material=blond radius=0.6 tangent=v translate=0.8,0,0\n"),
    "round": ("12,1,8,1", CAMERA +
              "light directional direction=0.05,1,0.1 intensity=2.5\n"
              "light directional direction=0.3,-0.2,-0.9 intensity=2\n"
              "material r1 model=huang eta=1.55 melanin=0.4 redness=0.2 cuticle_tilt=10 "
              "aspect_ratio=1 r=0.25 entry_grid=4 internal_grid=2\n"
              "material r2 diffuse=lambert specular=huang kd=0.1,0.05,0.02 eta=1.6 melanin=0.1 "
              "cuticle_tilt=-10 aspect_ratio=1 r=0.4 entry_grid=4 internal_grid=2\n"
              "material r3 model=huang eta=1.55 melanin=0.4 redness=0.2 cuticle_tilt=10 "
              "aspect_ratio=1 r=0.25 entry_grid=4 internal_grid=2\n"
              "capsule material=r1 radius=0.6 height=1.4 tangent=v translate=-0.7,0,0\n"
              "sphere material=r2 radius=0.6 tangent=v translate=0.8,0,0\n"
              "sphere material=r3 radius=0.3 tangent=u translate=0,1.3,0\n"),
    "graze": ("12,3,8,1",
              "camera position=-6,0.8,0.3 look_at=0,0,0 up=0,1,0 fov=40 resolution=48,48\n"
              "light directional direction=0.5,0.8,0.3 intensity=3\n"
              "material a model=huang eta=1.55 melanin=0.3 cuticle_tilt=10 aspect_ratio=0.7 "
              "r=0.2 entry_grid=4 internal_grid=2\n"
              "material b model=huang eta=1.55 melanin=0.3 cuticle_tilt=-10 aspect_ratio=0.7 "
              "r=0.2 entry_grid=4 internal_grid=2\n"
              "box material=a size=4,0.02,2 tangent=v translate=0,0,-1.05\n"
              "box material=b size=4,0.02,2 tangent=v translate=0,0,1.05\n"),
}


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


def checked(r, what):
    assert r.returncode == 0, (what, r.stderr)


class PovHairTable(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        shutil.rmtree(WORK, ignore_errors=True)
        os.makedirs(path("cache"))
        cls.pov, cls.passes = {}, {}
        for name, (sizes, text) in SCENES.items():
            table = ("--hair-table-sizes", sizes, "--hair-table-cache", path("cache"))
            with open(path(name + ".scene"), "w") as f:
                f.write(text)
            checked(run(ABRDF, "export", "--pov", path(name + ".scene"), "-o",
                        path(name + ".pov"), *table), name)
            with open(path(name + ".pov")) as f:
                cls.pov[name] = f.read()
            lights = [ln for ln in text.splitlines(True) if ln.startswith("light ")]
            for k, light in enumerate(lights):
                # the scene with light k alone, rendered by the library and rounded to half
                one = "%s_%d" % (name, k)
                with open(path(one + ".scene"), "w") as f:
                    f.write("".join(ln for ln in text.splitlines(True)
                                    if not ln.startswith("light ") or ln == light))
                checked(run(ABRDF, "render", path(one + ".scene"), "-o", path(one + "_ref.exr"),
                            "--spp", "1", "--precision", "double", "--no-preview", *table), one)
                checked(run(OIIOTOOL, path(one + "_ref.exr"), "-d", "half", "-o",
                            path(one + "_half.exr")), one)
                checked(povray(path(name + ".pov"), path(one + "_pov.exr"), k), one)
                cls.passes[one] = nmse(path(one + "_half.exr"), path(one + "_pov.exr"))
        # the hair scene per call, against its passes summed
        checked(run(ABRDF, "render", path("hair.scene"), "-o", path("per_call.exr"), "--spp", "1",
                    "--precision", "double", "--no-preview"), "per call")
        checked(run(OIIOTOOL, path("hair_0_pov.exr"), path("hair_1_pov.exr"), "--add", "-o",
                    path("hair_pov.exr")), "sum")
        sys.stderr.write("\nhuang from a table, each POV-Ray pass against abrdf render rounded "
                         "to half floats: %s\n" % ", ".join(
                             "%s %.1e" % kv for kv in sorted(cls.passes.items())))

    def test_the_table_is_read_as_the_library_reads_it(self):
        self.assertEqual(len(self.passes), 5)
        for one, e in self.passes.items():
            with self.subTest(one):
                self.assertLess(e, 1e-10)
        far = nmse(path("per_call.exr"), path("hair_pov.exr"))
        sys.stderr.write("\nhair, per call against POV-Ray from the table: NMSE %.1e\n" % far)
        self.assertGreater(far, 1e-5)

    def test_the_tables_are_written_beside_the_file(self):
        calls = re.findall(r'^#declare Abrdf_Mat_(\d) = Abrdf_Huang_Table\(Abrdf_Mat_\1, '
                           r'"([^"]+)", (\d+), (\d+), 8, ([0-9.e+]+), Abrdf_Mat_\1_Built\)$',
                           "".join(self.pov[n] for n in ("hair", "round")), re.M)
        self.assertEqual([c[:4] for c in calls],
                         [("0", "hair.huang0.exr", "12", "3"), ("1", "hair.huang1.exr", "12", "3"),
                          ("0", "round.huang0.exr", "12", "1"),
                          ("1", "round.huang1.exr", "12", "1"),
                          ("2", "round.huang0.exr", "12", "1")])  # r3 is r1: its image
        for _, name, _, _, scale in calls:
            self.assertTrue(os.path.isfile(path(name)))
            s = float(scale)
            self.assertEqual(s, 2.0 ** round(math.log2(s)))  # a power of two
        self.assertFalse(os.path.exists(path("round.huang2.exr")))
        # rendered from another directory with +L naming this one: the same pass
        elsewhere = path("elsewhere")
        os.makedirs(elsewhere, exist_ok=True)
        r = povray(path("hair.pov"), os.path.join(elsewhere, "pass_0.exr"), 0, elsewhere,
                   "+L" + WORK)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(nmse(path("hair_0_pov.exr"), os.path.join(elsewhere, "pass_0.exr")), 0)

    def edited(self, old, new, name):
        self.assertEqual(self.pov["hair"].count(old), 1, old)
        with open(path(name), "w") as f:
            f.write(self.pov["hair"].replace(old, new))
        out = path(name + ".exr")
        r = povray(path(name), out, 0)
        self.assertNotEqual(r.returncode, 0)
        self.assertFalse(os.path.exists(out))
        return " ".join((r.stdout + r.stderr).split())  # POV-Ray wraps its messages

    def test_an_edited_material_is_refused(self):
        line = re.search(r"^#declare Abrdf_Mat_1\[ABRDF_SLOT_MELANIN \+ 0\] = .*$",
                         self.pov["hair"], re.M).group(0)
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
