"""CLI tests of `abrdf export` (no bpy needed): the Cycles script is valid Python holding
the scene's numbers and a generated OSL shader with every object, material and light;
--model and --set act as in `abrdf render`; table= and adaptive materials are exported as the
selection's models with its trace as comments; hostile paths and names stay data in both
languages (the Python script is run; the POV-Ray render of a hostile export is
tests/ports/test_pov_hostile.py); usage errors exit 2, scene errors 1. Run by CTest with
ABRDF and SCENES in the environment (the rendering check is osl_cycles)."""
import ast
import base64
import json
import os
import re
import struct
import subprocess
import sys
import tempfile
import unittest

ABRDF = os.environ["ABRDF"]
SCENES = os.environ["SCENES"]


def run(*args):
    return subprocess.run([ABRDF, "export", *args], capture_output=True, text=True)


def exr_channels(path):
    """An EXR file's channels and their pixel types (0 uint, 1 half, 2 float), from its
    header's chlist attribute."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"\x76\x2f\x31\x01":
        raise ValueError("%s: not an EXR file" % path)
    at = 8
    while data[at] != 0:
        name_end = data.index(b"\0", at)
        type_end = data.index(b"\0", name_end + 1)
        (size,) = struct.unpack_from("<i", data, type_end + 1)
        value = data[type_end + 5:type_end + 5 + size]
        if data[at:name_end] == b"channels":
            out, k = {}, 0
            while value[k] != 0:
                end = value.index(b"\0", k)
                (out[value[k:end].decode()],) = struct.unpack_from("<i", value, end + 1)
                k = end + 17
            return out
        at = type_end + 5 + size
    raise ValueError("%s: no channels attribute" % path)


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
        self.assertIn("eta[m], melanin[m], redness[m], cuticle_tilt[m],\n", s["osl"])
        self.assertIn("aspect_ratio[m], entry_grid[m], internal_grid[m]);", s["osl"])
        self.assertEqual((m["entry_grid"], m["internal_grid"]), (6, 3))
        # per call: no table
        self.assertNotIn("huang_table", m)
        self.assertIn('string huang_table[1] = {\n        ""};', s["osl"])

    def test_huang_tables_are_exported(self):
        """--hair-table (--cycles, eval mode): every tabulated material's table in the script,
        the very table abrdf render reads (its cache file's values, as float32), named in the
        shader's huang_table array; --pov writes each as an image beside the .pov; glTF,
        --native and closure mode refuse it, as do bad sizes: one line, exit 2, nothing
        written."""
        hair = os.path.join(self.tmp.name, "hair.scene")
        with open(hair, "w") as f:
            f.write("camera position=0,0,6 look_at=0,0,0 resolution=24,24\n"
                    "light directional direction=-0.45,0.75,0.55 intensity=2.5\n"
                    "material brown table=hair_brown\nmaterial blond table=hair_blond\n"
                    "material grey model=lambert kd=0.5\n"
                    "capsule material=brown radius=0.6 height=1.4 tangent=v translate=-0.7,0,0\n"
                    "sphere material=blond radius=0.6 tangent=v translate=0.8,0,0\n"
                    "box material=grey size=4,4,0.1 translate=0,0,-1\n")
        cache = os.path.join(self.tmp.name, "cache")
        os.mkdir(cache)
        s = self.scene("--hair-table-sizes", "6,3,8,1", "--hair-table-cache", cache, name=hair)
        self.assertEqual([m["name"] for m in s["materials"]], ["brown", "blond", "grey"])
        self.assertNotIn("huang_table", s["materials"][2])
        cached = []
        for name in sorted(os.listdir(cache)):
            with open(os.path.join(cache, name), "rb") as f:
                v = struct.unpack("<%dd" % (8 + 3 * 6 * 3 * 6 * 8), f.read())
            cached.append(struct.pack("<%df" % (len(v) - 8), *v[8:]))
        self.assertEqual(len(cached), 2)
        exported = []
        for m in s["materials"][:2]:
            t = m["huang_table"]
            self.assertEqual((t["width"], t["height"]), (6 * 8, 6 * 3))
            self.assertEqual(t["sizes"], [6, 3, 8, 1])
            exported.append(base64.b64decode(t["data"]))
        self.assertEqual(sorted(exported), sorted(cached))
        self.assertNotEqual(exported[0], exported[1])
        self.assertIn('string huang_table[3] = {\n        "@ABRDF_TABLES@/abrdf_huang_0.pfm",\n'
                      '        "@ABRDF_TABLES@/abrdf_huang_1.pfm",\n        ""};', s["osl"])
        self.assertIn("int table_nt = 6, table_nv = 3, table_np = 8;", s["osl"])
        # the generic mode's shader reads them too (abrdf_cycles.eval_inputs)
        g = self.scene("--mode", "generic", "--hair-table-sizes", "6,3,8,1",
                       "--hair-table-cache", cache, name=hair)
        self.assertEqual(g["mode"], "generic")
        self.assertEqual(g["materials"][0]["huang_table"]["data"],
                         s["materials"][0]["huang_table"]["data"])
        # --pov: one image per tabulated material, named OUT.huang<i>.exr, beside OUT, named
        # in the file by its name alone (test_pov_hair_table.py renders them)
        pov = os.path.join(self.tmp.name, "x.pov")
        r = run("--pov", hair, "-o", pov, "--hair-table-sizes", "6,3,8,1", "--hair-table-cache",
                cache)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(pov) as f:
            text = f.read()
        for i, melanin in enumerate(("0.72999999999999998", "0.26000000000000001")):
            self.assertIn("#declare Abrdf_Mat_%d_Built = array[8] {1.55, %s, 0, 2, "
                          "0.84999999999999998, 0.29999999999999999, 6, 3}\n"
                          "#declare Abrdf_Mat_%d = Abrdf_Huang_Table(Abrdf_Mat_%d, "
                          "\"x.huang%d.exr\", 6, 3, 8, " % (i, melanin, i, i, i), text)
            self.assertTrue(os.path.isfile(os.path.join(self.tmp.name, "x.huang%d.exr" % i)))
            # stored as half floats, which every value is (test_pov_hair_table.py: exact)
            self.assertEqual(exr_channels(os.path.join(self.tmp.name, "x.huang%d.exr" % i)),
                             {"R": 1, "G": 1, "B": 1})
        self.assertNotIn("Abrdf_Mat_2 = Abrdf_Huang_Table", text)
        self.assertFalse(os.path.exists(os.path.join(self.tmp.name, "x.huang2.exr")))
        os.remove(pov)
        # a table's name that is a directory: refused before anything is written
        os.remove(os.path.join(self.tmp.name, "x.huang1.exr"))
        os.mkdir(os.path.join(self.tmp.name, "x.huang1.exr"))
        r = run("--pov", hair, "-o", pov, "--hair-table-sizes", "6,3,8,1", "--hair-table-cache",
                cache)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("x.huang1.exr: is a directory, not a file", r.stderr)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
        self.assertFalse(os.path.exists(pov))
        os.rmdir(os.path.join(self.tmp.name, "x.huang1.exr"))
        # an output in a directory that does not exist: refused before any table is built
        fresh = os.path.join(self.tmp.name, "fresh")
        os.mkdir(fresh)
        for fmt, name in (("--pov", "x.pov"), ("--cycles", "x.py")):
            r = run(fmt, hair, "-o", os.path.join(self.tmp.name, "none", name),
                    "--hair-table-sizes", "6,3,8,1", "--hair-table-cache", fresh)
            self.assertEqual(r.returncode, 1, r.stderr)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
            self.assertIn(os.path.join("none", name), r.stderr)
            self.assertEqual(os.listdir(fresh), [])
        for args, msg in [(("--pov", hair, "-o", pov, "--native", "--hair-table"),
                           "not by --native"),
                          (("--cycles", hair, "-o", self.out, "--mode", "closure",
                            "--hair-table"), "not by --mode closure"),
                          (("--gltf", hair, "-o", os.path.join(self.tmp.name, "x.gltf"),
                            "--hair-table"), "--hair-table is an option of --cycles and --pov"),
                          (("--cycles", hair, "-o", self.out, "--hair-table-sizes", "6,3,8"),
                           "is not NT,NV,NP,SETS"),
                          (("--cycles", hair, "-o", self.out, "--hair-table-cache",
                            os.path.join(self.tmp.name, "none")), "not a directory")]:
            with open(self.out, "w") as f:
                f.write("kept")
            r = run(*args)
            self.assertEqual(r.returncode, 2, (args, r.stderr))
            self.assertIn(msg, r.stderr)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
            self.assertFalse(os.path.exists(pov) or
                             os.path.exists(os.path.join(self.tmp.name, "x.gltf")))
            with open(self.out) as f:
                self.assertEqual(f.read(), "kept")
        # sizes the scene's material refuses (one view azimuth: a round fibre's): exit 1
        r = run("--cycles", hair, "-o", self.out, "--hair-table-sizes", "6,1,8,1")
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("material 'brown' (line 3): huang table 6,1,8,1: ", r.stderr)
        with open(self.out) as f:
            self.assertEqual(f.read(), "kept")

    def test_huang_quadrature_grids_are_exported(self):
        # huang's grids (a budget choice coarsens entry_grid) reach both ports.
        s = self.scene("--model", "huang", "--set", "entry_grid=4", "--set", "internal_grid=2",
                       name="sphere.scene")
        self.assertEqual((s["materials"][0]["entry_grid"], s["materials"][0]["internal_grid"]),
                         (4, 2))
        self.assertIn("int entry_grid[1] = {\n        4};", s["osl"])
        self.assertIn("int internal_grid[1] = {\n        2};", s["osl"])
        pov = os.path.join(self.tmp.name, "scene.pov")
        r = run("--pov", os.path.join(SCENES, "sphere.scene"), "-o", pov, "--model", "huang",
                "--set", "entry_grid=4", "--set", "internal_grid=2")
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(pov) as f:
            text = f.read()
        self.assertIn("[ABRDF_SLOT_ENTRY_GRID + 0] = 4;", text)
        self.assertIn("[ABRDF_SLOT_INTERNAL_GRID + 0] = 2;", text)

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

    def test_area_lights_closure_mode_only(self):
        # Sphere, rect and environment lights reach Cycles' closure mode with their numbers;
        # the eval mode and POV-Ray refuse them with the light's line, and nothing is written.
        path = os.path.join(SCENES, "area.scene")
        s = self.scene("--mode", "closure", name="area.scene")
        kinds = [(l["kind"], l["position"], l["radius"], l["u"], l["v"], l["intensity"])
                 for l in s["lights"]]
        self.assertEqual(kinds, [("sphere", (-2, 3, 1.5), 0.12, (0, 0, 0), (0, 0, 0), 900),
                                 ("rect", (2, 2.6, 0), 0, (1.2, 0, 0), (0, 0, 0.8), 9)])
        os.remove(self.out)
        for args, text in ((("--cycles", path, "-o", self.out), "line 8: a sphere light needs "
                            "--mode closure"),
                           (("--pov", path, "-o", self.out), "light at line 8: sphere, rect and "
                            "environment lights are not exported to POV-Ray")):
            r = run(*args)
            self.assertEqual(r.returncode, 1, r.stderr)
            self.assertIn(text, r.stderr)
            # the problem is the scene's: the message names it, not the output
            self.assertIn("abrdf export: %s: " % path, r.stderr)
            self.assertNotIn(self.out, r.stderr)
            self.assertFalse(os.path.exists(self.out))
        env = os.path.join(self.tmp.name, "env.exr")
        r = subprocess.run([ABRDF, "render", os.path.join(SCENES, "sphere.scene"), "-o", env,
                            "--width", "8", "--height", "4", "--spp", "1", "--no-preview"],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        scene = os.path.join(self.tmp.name, "env.scene")
        with open(scene, "w") as f:
            f.write("camera position=0,0,4 look_at=0,0,0\nlight environment file=env.exr\n"
                    "material m model=lambert\nsphere material=m radius=1\n")
        for args, text in ((("--cycles", scene, "-o", self.out),
                            "line 2: an environment light needs --mode closure"),
                           (("--pov", scene, "-o", self.out), "light at line 2: sphere, rect")):
            r = run(*args)
            self.assertEqual(r.returncode, 1, r.stderr)
            self.assertIn(text, r.stderr)
            self.assertFalse(os.path.exists(self.out))
        # closure mode: the map by its absolute path (the script may run anywhere)
        cwd = os.getcwd()
        try:
            os.chdir(self.tmp.name)
            s = self.scene("--mode", "closure", name=os.path.abspath("env.scene"))
        finally:
            os.chdir(cwd)
        (light,) = s["lights"]
        self.assertEqual((light["kind"], light["file"]),
                         ("environment", os.path.realpath(env)))


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

    def test_mesh_file_names_stay_data(self):
        """A mesh file named with quotes and a backslash (a scene word is printable ASCII
        without '#'): the POV-Ray export keeps the name in a comment, and the Cycles script
        holds the exact name as a string constant."""
        name = b'm"fopen(F)\\q\'x.obj'
        with open(self.base + b"/" + name, "w") as f:
            f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        scene = self.base + b"/mesh.scene"
        with open(scene, "wb") as f:
            f.write(scene_text(["m0"]).encode() + b"mesh file=" + name + b" material=m0\n")
        out = self.base + b"/m.pov"
        self.export(b"--pov", scene, b"-o", out)
        with open(out, "rb") as f:
            lines = f.read().split(b"\n")
        named = [line for line in lines if b"fopen" in line]
        self.assertTrue(named)  # the name is written, escaped, in a comment
        for line in lines:
            self.assertTrue(all(0x20 <= c <= 0x7e for c in line), line)
        for line in named:
            self.assertTrue(line.startswith(b"//"), line)
        py = self.base + b"/m.py"
        self.export(b"--cycles", scene, b"-o", py)
        with open(py, "rb") as f:
            text = f.read()
        names = [n.value for n in ast.walk(ast.parse(text))
                 if isinstance(n, ast.Constant) and isinstance(n.value, str) and n.value.endswith("x.obj")]
        self.assertTrue(names)
        for n in names:
            self.assertTrue(os.fsencode(n).endswith(name), n)


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


def obj_counts(path):
    """Statements of an OBJ file by keyword, and its vertex positions as written."""
    counts, verts = {}, []
    with open(path) as f:
        for line in f:
            w = line.split()
            if w:
                counts[w[0]] = counts.get(w[0], 0) + 1
                if w[0] == "v":
                    verts.append(tuple(float(x) for x in w[1:4]))
    return counts, verts


class ExportMeshes(unittest.TestCase):
    """`mesh` objects: POV-Ray mesh2 with the corner normals, Cycles mesh arrays."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.counts, self.verts = obj_counts(os.path.join(SCENES, "teapot.obj"))

    def tearDown(self):
        self.tmp.cleanup()

    def pov(self, *args):
        out = os.path.join(self.tmp.name, "t.pov")
        r = run("--pov", os.path.join(SCENES, "teapot.scene"), "-o", out, *args)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out) as f:
            return f.read()

    def test_pov_mesh2_with_the_normals(self):
        text = self.pov()
        nt, nn = self.counts["f"], self.counts["vn"]
        self.assertEqual(text.count("mesh2 {"), 1)
        self.assertIn("vertex_vectors { %d," % self.counts["v"], text)
        self.assertIn("normal_vectors { %d," % nn, text)
        self.assertIn("face_indices { %d," % nt, text)
        self.assertIn("normal_indices { %d," % nt, text)
        # the function pigments' triangle code and data
        self.assertIn("uv_vectors { %d," % (3 * nt), text)
        self.assertIn("<0, %d.5>, <1, %d.5>, <0, %d.5>" % (2 * (nt - 1), 2 * (nt - 1), 2 * nt - 1), text)
        self.assertEqual(len(re.findall(r"#declare Abrdf_Mesh_0_(P0|P1|P2|N0|N1|N2|T) = function", text)), 7)
        self.assertIn("Abrdf_Mesh_Texture(Abrdf_Mat_0, Abrdf_Mesh_0_Data, true,", text)
        # the first vertex as the file has it (9 digits keep the float)
        first = re.search(r"vertex_vectors \{ \d+,\s*<([^>]*)>", text).group(1)
        self.assertEqual(tuple(float(x) for x in first.split(",")), self.verts[0])

    def test_pov_native_is_plain_mesh2(self):
        text = self.pov("--native", "--model", "lambert")
        self.assertIn("normal_vectors {", text)
        self.assertNotIn("uv_vectors", text)
        self.assertNotIn("Abrdf_Mesh_0_P0", text)
        self.assertIn("object { Abrdf_Mesh_0_Smooth\n  Abrdf_Native_Texture(", text)

    def test_cycles_mesh_arrays(self):
        out = os.path.join(self.tmp.name, "t.py")
        r = run("--cycles", os.path.join(SCENES, "teapot.scene"), "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out) as f:
            tree = ast.parse(f.read())
        s = ast.literal_eval(next(n.value for n in tree.body if isinstance(n, ast.Assign)
                                  and n.targets[0].id == "SCENE"))
        m = s["meshes"][0]
        self.assertEqual((m["vertices"], m["triangles"]), (self.counts["v"], self.counts["f"]))
        pos = struct.unpack("<%df" % (3 * m["vertices"]), base64.b64decode(m["positions"]))
        self.assertEqual(pos[:3], struct.unpack("<3f", struct.pack("<3f", *self.verts[0])))
        tri = struct.unpack("<%di" % (3 * m["triangles"]), base64.b64decode(m["tri"]))
        self.assertTrue(0 <= min(tri) and max(tri) < m["vertices"])
        nrm = struct.unpack("<%df" % (3 * self.counts["vn"]), base64.b64decode(m["normals"]))
        self.assertAlmostEqual(sum(x * x for x in nrm[:3]), 1.0, places=6)
        mesh_objects = [o for o in s["objects"] if o["shape"] == "mesh"]
        self.assertEqual(len(mesh_objects), 1)
        self.assertEqual((mesh_objects[0]["mesh"], mesh_objects[0]["smooth"]), (0, True))
        self.assertIn("ABRDF_SHAPE_MESH", s["osl"])
        self.assertIn("int has_mesh = 1;", s["osl"])

    def test_uv_tangent_is_refused_by_cycles(self):
        scene = os.path.join(self.tmp.name, "uv.scene")
        with open(scene, "w") as f:
            f.write("camera position=0,2,8 look_at=0,1,0\n"
                    "material m model=disney_specular_aniso anisotropic=0.5\n"
                    "mesh file=%s material=m tangent=uv\n" % os.path.join(SCENES, "teapot.obj"))
        r = run("--cycles", scene, "-o", os.path.join(self.tmp.name, "uv.py"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("tangent=uv is not ported to Cycles", r.stderr)
        r = run("--pov", scene, "-o", os.path.join(self.tmp.name, "uv.pov"))
        self.assertEqual(r.returncode, 0, r.stderr)


class PovLights(unittest.TestCase):
    """How the POV-Ray export carries the lights: one light through POV-Ray's light_source
    (shadows); several lights as passes, light k alone with its light_source and shadows when
    povray is given Declare=Abrdf_Pass=k, the ambient term in pass 0 only (the render check is
    tests/ports/test_pov_lights.py); --no-shadows every light in the pigment."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.tmp.cleanup()

    def pov(self, name, *args):
        out = os.path.join(self.tmp.name, "x.pov")
        r = run("--pov", os.path.join(SCENES, name), "-o", out, *args)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out) as f:
            return f.read()

    def objects(self, text):
        return len(re.findall(r"^object \{", text, re.M))

    def test_one_light_is_povrays(self):
        text = self.pov("robot.scene")
        self.assertNotIn("Abrdf_Pass", text)
        self.assertEqual(len(re.findall(r"^light_source \{", text, re.M)), 1)
        self.assertEqual(text.count("Abrdf_Eye, Abrdf_Lights,"), self.objects(text))
        self.assertEqual(len(re.findall(r">, true\)$", text, re.M)), self.objects(text))

    def test_several_lights_are_passes(self):
        for name, n in (("robot_lights.scene", 3), ("robot16.scene", 16)):
            text = self.pov(name)
            self.assertIn("#declare Abrdf_Pass_Count = %d;" % n, text)
            cases = re.findall(r"#case \((\d+)\)\n    #declare Abrdf_Pass_Lights = array\[1\]\[7\] "
                               r"\{(\{[^}]*\})\}\n    light_source \{", text)
            self.assertEqual([int(c[0]) for c in cases], list(range(n)), name)
            # pass k's row is row k of every light's table
            table = re.search(r"#declare Abrdf_Lights = array\[%d\]\[7\] \{\n(.*?)\n\}" % n,
                              text, re.S).group(1)
            rows = [r.strip().rstrip(",") for r in table.split("\n")]
            self.assertEqual([c[1] for c in cases], rows, name)
            self.assertIn("#declare Abrdf_Ambient_On = (Abrdf_Pass = 0);", text)
            self.assertEqual(text.count("Abrdf_Eye, Abrdf_Pass_Lights,"), self.objects(text))
            self.assertEqual(text.count(" * Abrdf_Ambient_On, Abrdf_Lit)"), self.objects(text))
            self.assertIn("Declare=Abrdf_Pass=k", text.split("#version")[0])  # the header says how

    def test_no_shadows_is_emissive(self):
        text = self.pov("robot_lights.scene", "--no-shadows")
        self.assertNotIn("Abrdf_Pass", text)
        self.assertNotIn("light_source", text)
        self.assertEqual(len(re.findall(r">, false\)$", text, re.M)), self.objects(text))


if __name__ == "__main__":
    unittest.main()
