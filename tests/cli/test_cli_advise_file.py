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


if __name__ == "__main__":
    unittest.main()
