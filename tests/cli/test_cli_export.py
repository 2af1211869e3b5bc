"""CLI tests of `abrdf export` (no bpy needed): the Cycles script is valid Python holding
the scene's numbers and a generated OSL shader with every object, material and light;
--model and --set act as in `abrdf render`; table= and adaptive materials are exported as the
selection's models with its trace as comments; hostile paths and names stay data in both
languages (the Python script is run; the POV-Ray render of a hostile export is
tests/ports/test_pov_hostile.py); usage errors exit 2, scene errors 1. Run by CTest with
ABRDF and SCENES in the environment (the rendering check is osl_cycles)."""
import ast
import json
import os
import re
import subprocess
import sys
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


# A directory name and material names that would become code if written unescaped: a line
# break then POV-Ray directives, quotes of both languages, backslashes, a '#', UTF-8 and
# bytes that are not UTF-8.
HOSTILE_DIR = (b'h\n#fopen F "pwned-pov" write #write(F,"x") #end\n"""\'\\ '
               b'\nimport os; open("pwned-py", "w")\n\xc3\xa9\xff#')
HOSTILE_NAMES = ['a")box{-9,9}//', "x\\q", 'q"""', "b'\\n"]


def scene_text(names):
    lines = ["camera position=0,0,4 look_at=0,0,0 resolution=24,24",
             "light directional direction=-1,1,1 intensity=3"]
    for i, n in enumerate(names):
        lines.append("material %s diffuse=lambert specular=blinn_phong kd=0.%d n=%d" % (n, i + 3,
                                                                                     10 * i + 5))
    for i, n in enumerate(names):
        lines.append("sphere material=%s radius=0.4 translate=%g,0,0" % (n, -1.2 + 0.8 * i))
    return "\n".join(lines) + "\n"


class Hostile(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.base = os.fsencode(self.tmp.name)
        self.dir = self.base + b"/" + HOSTILE_DIR
        os.makedirs(self.dir)
        self.scene = self.dir + b"/s\n#declare X = 1;\n.scene"
        with open(self.scene, "w") as f:
            f.write(scene_text(HOSTILE_NAMES))
        self.benign = self.base + b"/benign.scene"
        with open(self.benign, "w") as f:
            f.write(scene_text(["m%d" % i for i in range(len(HOSTILE_NAMES))]))

    def tearDown(self):
        self.tmp.cleanup()

    def export(self, *args):
        r = subprocess.run([os.fsencode(ABRDF), b"export", *args], capture_output=True,
                           cwd=self.base)
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_pov_text_has_the_same_code_as_a_benign_export(self):
        """Line for line, the hostile export differs from the benign one only in comments and
        in the string of the material check: no name or path became SDL."""
        out_h, out_b = self.base + b"/h.pov", self.base + b"/b.pov"
        self.export(b"--pov", self.scene, b"-o", out_h)
        self.export(b"--pov", self.benign, b"-o", out_b)
        with open(out_h, "rb") as f:
            hostile = f.read().split(b"\n")
        with open(out_b, "rb") as f:
            benign = f.read().split(b"\n")
        self.assertEqual(len(hostile), len(benign))
        checks = 0
        for h, b in zip(hostile, benign):
            self.assertTrue(all(0x20 <= c <= 0x7e for c in h), h)  # ASCII, one line
            if h == b or (h.startswith(b"//") and b.startswith(b"//")):
                continue
            self.assertTrue(h.startswith(b"Abrdf__Check(") and b.startswith(b"Abrdf__Check("),
                            (h, b))
            self.assertEqual(h.split(b", ")[0], b.split(b", ")[0])
            checks += 1
        self.assertEqual(checks, len(HOSTILE_NAMES))

    def test_python_script_runs_as_data(self):
        """The script parses, holds the exact path, directory and names, and running it (with a
        stand-in for osl/abrdf_cycles.py in the hostile --osl-dir) executes nothing else."""
        osl = self.dir + b"/osl"
        os.makedirs(osl)
        with open(osl + b"/abrdf_cycles.py", "w") as f:
            f.write("import json, os\n"
                    "def main(scene):\n"
                    "    print(json.dumps({'source': os.fsencode(scene['source']).hex(),\n"
                    "                      'osl_dir': os.fsencode(scene['osl_dir']).hex(),\n"
                    "                      'names': [m['name'] for m in scene['materials']]}))\n")
        out = self.base + b"/scene.py"
        self.export(b"--cycles", self.scene, b"-o", out, b"--osl-dir", osl)
        with open(out, "rb") as f:
            text = f.read()
        text.decode("ascii")  # the script is ASCII: every byte of a name went through escapes
        ast.parse(text)
        r = subprocess.run([sys.executable, out], capture_output=True, cwd=self.base)
        self.assertEqual(r.returncode, 0, r.stderr)
        got = json.loads(r.stdout)
        self.assertEqual(bytes.fromhex(got["source"]), self.scene)
        self.assertEqual(bytes.fromhex(got["osl_dir"]), osl)
        self.assertEqual(got["names"], HOSTILE_NAMES)
        for root, _, files in os.walk(self.base):
            for name in files:
                self.assertNotIn(b"pwned", os.fsencode(name))


class Selection(unittest.TestCase):
    """Scenes with table= and adaptive materials export as the models the selection chose,
    the same that abrdf render uses, with the trace as comments."""

    SCENE = ("camera position=0,0,4 look_at=0,0,0 resolution=24,24\n"
             "light directional direction=-1,1,1 intensity=3\n"
             "material gold table=gold\n"
             "material auto adaptive goal=performance r=0.3 kd=0.5\n"
             "material mine table=custom_red\n"
             "sphere material=gold radius=0.5 translate=-1,0,0\n"
             "sphere material=auto radius=0.5\n"
             "sphere material=mine radius=0.5 translate=1,0,0\n")

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.scene = os.path.join(self.tmp.name, "sel.scene")
        with open(self.scene, "w") as f:
            f.write(self.SCENE)
        self.mats = os.path.join(self.tmp.name, "mine.csv")
        with open(os.path.join(os.path.dirname(SCENES), "data", "materials.csv")) as f:
            header = next(l for l in f if not l.startswith("#"))
        with open(self.mats, "w") as f:
            f.write(header + "custom_red,general,,0.6,0.7,0.1,0.1,1,1,1,,,,1.5,,,,,,,,,,,,test\n")

    def tearDown(self):
        self.tmp.cleanup()

    def test_exports_the_render_choice_with_its_trace(self):
        r = subprocess.run([ABRDF, "render", self.scene, "--materials", self.mats, "-o",
                            os.path.join(self.tmp.name, "x.exr"), "--no-preview", "--explain"],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        chosen = dict(re.findall(r"^selection: material '(\w+)'.*: ([\w +]+)$", r.stdout, re.M))
        self.assertEqual(sorted(chosen), ["auto", "gold", "mine"])
        out = os.path.join(self.tmp.name, "sel.py")
        r = run("--cycles", self.scene, "--materials", self.mats, "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out) as f:
            text = f.read()
        tree = ast.parse(text)
        scene = ast.literal_eval(next(n.value for n in tree.body if isinstance(n, ast.Assign)
                                      and n.targets[0].id == "SCENE"))
        for m in scene["materials"]:
            self.assertEqual(" + ".join(m["lobes"]), chosen[m["name"]])
        self.assertIn("# selection: material 'auto' (line 4), goal performance", text)
        pov = os.path.join(self.tmp.name, "sel.pov")
        r = run("--pov", self.scene, "--materials", self.mats, "-o", pov)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(pov) as f:
            text = f.read()
        self.assertIn("// selection: material 'gold' (line 3), goal photoreal, table entry gold",
                      text)
        self.assertIn("//    1. ", text)
        # Without the file naming custom_red, the scene does not resolve: exit 1, its line.
        r = run("--pov", self.scene, "-o", pov)
        self.assertEqual(r.returncode, 1)
        self.assertIn("sel.scene:5: material 'mine': no entry 'custom_red'", r.stderr)

    def test_adaptive_goal_for_every_material(self):
        out = os.path.join(self.tmp.name, "robot.py")
        r = run("--cycles", os.path.join(SCENES, "robot.scene"), "--adaptive", "--goal",
                "performance", "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out) as f:
            text = f.read()
        self.assertEqual(text.count("# selection: material "), 3)
        self.assertNotIn('"disney_specular"', text.split("\"osl\"")[0])
        for args, msg in (([], "--adaptive needs --goal"), (["--goal", "x"], "--adaptive needs"),
                          (["--model", "lambert"], "exclude each other")):
            r = run("--pov", os.path.join(SCENES, "robot.scene"), "--adaptive", *args, "-o", out)
            self.assertEqual(r.returncode, 2, r.stderr)
            self.assertIn(msg, r.stderr)


if __name__ == "__main__":
    unittest.main()
