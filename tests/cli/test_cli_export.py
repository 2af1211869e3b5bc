"""CLI tests of `abrdf export` (no bpy needed): the Cycles script is valid Python holding
the scene's numbers and a generated OSL shader with every object, material and light;
--model and --set act as in `abrdf render`; usage errors exit 2, scene errors 1. Run by
CTest with ABRDF and SCENES in the environment (the rendering check is osl_cycles)."""
import ast
import os
import re
import subprocess
import tempfile
import unittest

ABRDF = os.environ["ABRDF"]
SCENES = os.environ["SCENES"]


def run(*args):
    return subprocess.run([ABRDF, "export", *args], capture_output=True, text=True)


class Export(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.out = os.path.join(self.tmp.name, "scene.py")

    def tearDown(self):
        self.tmp.cleanup()

    def scene(self, *args, name="robot.scene"):
        r = run("--cycles", os.path.join(SCENES, name), "-o", self.out, *args)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(self.out) as f:
            text = f.read()
        tree = ast.parse(text)  # valid Python
        scene = next(n.value for n in tree.body if isinstance(n, ast.Assign)
                     and n.targets[0].id == "SCENE")
        return ast.literal_eval(scene)

    def test_robot_counts_and_camera(self):
        s = self.scene("--width", "40", "--height", "30", "--spp", "9", "--osl-dir", "/x/osl")
        self.assertEqual((s["width"], s["height"], s["samples"]), (40, 30, 9))
        self.assertEqual(s["osl_dir"], "/x/osl")
        self.assertEqual(len(s["objects"]), 35)
        self.assertEqual(len(s["materials"]), 3)
        self.assertEqual(s["camera"]["position"], (3.2, 1.8, 10))
        self.assertEqual(s["camera"]["fov_deg"], 34)
        osl = s["osl"]
        self.assertIn("int nobj = 35, nlight = 1;", osl)
        self.assertIn("int image_w = 40, image_h = 30;", osl)
        self.assertEqual(len(re.findall(r"ABRDF_SHAPE_CAPSULE", osl)), 8)
        self.assertEqual(s["lights"][0]["kind"], "directional")

    def test_model_and_set_replace_every_material(self):
        s = self.scene("--model", "blinn_phong", "--set", "n=37")
        for m in s["materials"]:
            self.assertEqual(m["lobes"], ["blinn_phong"])
            self.assertEqual(m["n"], 37)
        self.assertNotIn('"disney_specular"', s["osl"])

    def test_hair_models_are_exported(self):
        # The hair models have OSL twins (osl/abrdf_hair.h): their parameters reach the shader.
        s = self.scene("--model", "huang", "--set", "melanin=0.3", name="sphere.scene")
        m = s["materials"][0]
        self.assertEqual(m["lobes"], ["huang"])
        self.assertEqual((m["melanin"], m["eta"]), (0.3, 1.55))
        self.assertIn("float melanin[1] = {\n        0.29999999999999999};", s["osl"])
        self.assertIn("redness[m], cuticle_tilt[m], aspect_ratio[m]);", s["osl"])

    def test_ambient_is_ka_times_ia(self):
        s = self.scene()  # robot: ambient 0.02, ka defaults to kd
        self.assertAlmostEqual(s["materials"][0]["ambient"][0], 0.02 * 0.50)

    def test_closure_mode_default(self):
        self.assertEqual(self.scene("--mode", "closure")["mode"], "closure")

    def test_usage_errors(self):
        sphere = os.path.join(SCENES, "sphere.scene")
        for args, msg in [((sphere, "-o", self.out), "choose one format"),
                          (("--cycles", "-o", self.out), "missing SCENE"),
                          (("--cycles", sphere), "missing -o"),
                          (("--cycles", sphere, "-o", self.out, "--mode", "x"), "--mode"),
                          (("--cycles", sphere, "-o", self.out, "--set", "n=3"), "--set needs --model"),
                          (("--cycles", sphere, "-o", self.out, "--model", "blin_phong"), "blinn_phong"),
                          (("--cycles", sphere, "-o", self.out, "--spp", "0"), "--spp")]:
            r = run(*args)
            self.assertEqual(r.returncode, 2, (args, r.stderr))
            self.assertIn(msg, r.stderr)

    def test_scene_errors_exit_1(self):
        bad = os.path.join(self.tmp.name, "bad.scene")
        with open(bad, "w") as f:
            f.write("camera position=0,0,4 look_at=0,0,0\nsphere material=none radius=1\n")
        r = run("--cycles", bad, "-o", self.out)
        self.assertEqual(r.returncode, 1)
        self.assertIn("bad.scene:2", r.stderr)
        r = run("--cycles", os.path.join(SCENES, "sphere.scene"), "-o",
                os.path.join(self.tmp.name, "no", "such", "dir.py"))
        self.assertEqual(r.returncode, 1)


if __name__ == "__main__":
    unittest.main()
