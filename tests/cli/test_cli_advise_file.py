"""`abrdf advise FILE` (docs/GLTF.md, "Advising a file"): every glTF-style (pbr) material of
a file gets the flowchart's choice and trace, the same as `abrdf advise` gives the material's
values typed on the command line; --budget runs the budget mode per material; --json lists
them; bad files and option mixes are refused in one line, with nothing on stdout.

Run by CTest with ABRDF (the command) in the environment."""
import json
import os
import subprocess
import unittest

from clitest import TempDirCase, checked_stderr

ABRDF = os.environ["ABRDF"]

SCENE = """camera position=0,0,4 look_at=0,0,0 resolution=32,32
material gold pbr base_color=1,0.78,0.34 metallic=1 roughness=0.3
material glaze pbr base_color=0.8,0.1,0.1 metallic=0 roughness=0.02
material lacquer pbr base_color=0.2,0.3,0.8 metallic=0 roughness=0.5 clearcoat=1 clearcoat_roughness=0.05
material matte model=lambert kd=0.5
sphere material=gold radius=1
"""


def run(*args):
    p = subprocess.run([ABRDF, *args], capture_output=True, timeout=300)
    return p.returncode, p.stdout.decode(), checked_stderr(p)


class AdviseFile(TempDirCase):
    def test_every_pbr_material_with_its_trace(self):
        path = self.put("a.scene", SCENE)
        rc, out, err = run("advise", path)
        self.assertEqual(rc, 0, err)
        blocks = out.strip().split("\n\n")
        self.assertEqual(len(blocks), 3, out)  # the lambert material is not a pbr one
        self.assertIn("material  gold (general; %s:2)" % path, blocks[0])
        self.assertIn("specular  disney_specular", blocks[0])
        self.assertIn("specular  f_2e", blocks[1])  # r 0.02: the smooth branch
        self.assertIn("alpha 0.02 <= 0.03: smooth", blocks[1])
        self.assertIn("(layered_plastic;", blocks[2])  # the clear coat
        self.assertIn("specular  weidlich_wilkie", blocks[2])

    def test_same_choice_as_the_values_typed(self):
        """The file's gold is abrdf advise with its mapped values: base colour as f0, no
        diffuse, r 0.3 (abrdf_pbr_material)."""
        path = self.put("a.scene", SCENE)
        for goal in ("photoreal", "performance"):
            rc, out, err = run("advise", path, "--goal", goal, "--json")
            self.assertEqual(rc, 0, err)
            got = json.loads(out)["materials"][0]
            rc, out, err = run("advise", "--goal", goal, "--r", "0.3", "--kd", "0",
                               "--ks", "1", "--f0", "1,0.78,0.34", "--json")
            self.assertEqual(rc, 0, err)
            want = json.loads(out)
            for key in ("diffuse", "specular", "params", "error", "cost"):
                self.assertEqual(got[key], want[key], key)
            self.assertEqual(got["material"], "gold")

    def test_budget_per_material(self):
        path = self.put("b.scene", SCENE.replace("material glaze", "#").replace(
            "material lacquer", "#"))
        rc, out, err = run("advise", path, "--budget", "slight", "--json")
        self.assertEqual(rc, 0, err)
        mats = json.loads(out)["materials"]
        self.assertEqual(len(mats), 1)
        self.assertEqual(mats[0]["material"], "gold")
        self.assertLess(mats[0]["error"]["nmse_pred"], 2.5e-4, mats[0])
        self.assertEqual(mats[0]["budget"]["class"], "slight")

    def test_refusals(self):
        path = self.put("a.scene", SCENE)
        cases = [
            (("advise", path, "--r", "0.3"), "take --goal or --budget"),
            (("advise", self.path("none.gltf")), "none.gltf"),
            (("advise", self.put("bad.scene", "material x pbr roughness=7\n")), "bad.scene:1"),
            (("advise", self.put("m.scene", "camera position=0,0,4 look_at=0,0,0\n"
                                  "material m model=lambert\nsphere material=m radius=1\n")),
             "no glTF-style (pbr) material"),
        ]
        for args, what in cases:
            rc, out, err = run(*args)
            self.assertNotEqual(rc, 0, args)
            self.assertEqual(out, "", args)
            self.assertEqual(len(err.strip().splitlines()), 1, err)
            self.assertIn(what, err)


GEN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "gen",
                   "gen_material_assets.py")
QUAD = ("v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
        "f 1/1/1 2/2/1 3/3/1 4/4/1\n")


class AdviseTextured(TempDirCase):
    """A roughness map is advised over its values (docs/GLTF.md, "Selection over a
    texture"): the generated glTF's map crosses the smooth threshold (r 0.012 and 0.023
    below 0.03, the rest above), so the trace names both branches and the safe one."""

    def setUp(self):
        super().setUp()
        # the generator writes PNGs through OpenImageIO: Debian's python3 has it
        subprocess.run(["/usr/bin/python3", GEN, self.dir], check=True, capture_output=True)

    def textured(self, *args):
        rc, out, err = run("advise", self.path("scene.gltf"), *args, "--json")
        self.assertEqual(rc, 0, err)
        return next(m for m in json.loads(out)["materials"] if m["material"] == "textured")

    def test_photoreal_takes_the_reference_across_the_threshold(self):
        m = self.textured()
        self.assertEqual(m["specular"], "disney_specular")
        last = m["trace"][-1]["text"]
        for word in ("crosses", "f_2e", "disney_specular", "reference", "25% of texels"):
            self.assertIn(word, last)

    def test_performance_passes_at_every_value(self):
        m = self.textured("--goal", "performance")
        last = m["trace"][-1]["text"]
        self.assertIn("the safe branch: %s" % m["specular"], last)

    def test_render_explains_the_same_choice(self):
        r = subprocess.run([ABRDF, "render", self.path("scene.gltf"), "-o", self.path("a.exr"),
                            "--width", "24", "--height", "24", "--adaptive", "--goal",
                            "photoreal", "--explain", "--no-preview"], capture_output=True)
        err = checked_stderr(r)
        self.assertEqual(r.returncode, 0, err)
        out = r.stdout.decode()
        self.assertIn("material 'textured'", out)
        self.assertIn("over its roughness map: disney_diffuse + disney_specular", out)

    def test_budget_over_a_map(self):
        """Two roughness values on either half of a quad: the budget runs at each, and the
        render with --adaptive --budget takes the same pair (its fits per texel)."""
        subprocess.run(["/usr/bin/python3", "-c", """
import OpenImageIO as oiio, numpy as np, sys
img = np.zeros((4, 4, 3), np.float32); img[:, :2] = 0.3; img[:, 2:] = 0.6
buf = oiio.ImageBuf(oiio.ImageSpec(4, 4, 3, "uint8"))
buf.set_pixels(oiio.ROI(0, 4, 0, 4, 0, 1, 0, 3), img)
assert buf.write(sys.argv[1])
""", self.path("rough.png")], check=True)
        self.put("quad.obj", QUAD)
        scene = self.put("b.scene", "camera position=0,0,3.2 look_at=0,0,0 resolution=24,24\n"
                         "light directional direction=-0.4,0.5,1 intensity=3\n"
                         "material t pbr base_color=0.7,0.2,0.1 metallic=0 roughness=1 "
                         "roughness_map=rough.png\nmesh file=quad.obj material=t\n")
        rc, out, err = run("advise", scene, "--budget", "0.005", "--json")
        self.assertEqual(rc, 0, err)
        m = json.loads(out)["materials"][0]
        self.assertEqual(m["groups"], 2)
        self.assertLess(m["error"]["nmse_pred"], 0.005)
        pair = " + ".join(x for x in (m["diffuse"], m["specular"]) if x)
        r = subprocess.run([ABRDF, "render", scene, "-o", self.path("b.exr"), "--adaptive",
                            "--budget", "0.005", "--explain", "--no-preview"], capture_output=True)
        self.assertEqual(r.returncode, 0, checked_stderr(r))
        self.assertIn("over its roughness map: " + pair, r.stdout.decode())


if __name__ == "__main__":
    unittest.main()
