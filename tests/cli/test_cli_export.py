"""CLI tests of `abrdf export` (no bpy needed): the Cycles script is valid Python holding
the scene's numbers and a generated OSL shader with every object, material and light;
--model and --set act as in `abrdf render`; usage errors exit 2, scene errors 1. Run by
CTest with ABRDF and SCENES in the environment (the rendering check is osl_cycles)."""
import ast
import base64
import os
import re
import struct
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


if __name__ == "__main__":
    unittest.main()
