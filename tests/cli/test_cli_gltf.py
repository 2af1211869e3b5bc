"""CLI tests of glTF files (tools/gltf/gltf.h, docs/GLTF.md, "Reading glTF"): a glTF cube
renders as the same cube in the scene format (an OBJ mesh, the node's transform as the
object's) within NMSE 1e-6; the .glb and external-.bin forms and strips and fans render
identically; the defaults taken are stated by --explain; bad files are one line naming the
file, a non-zero exit and no output; abrdf export reads glTF. abrdf export --gltf writes
scenes (analytic shapes, pbr, chosen and explicit materials, both light kinds, ambient) that
render within NMSE 1e-6 of the scene itself, as .gltf and .glb, and maps as textures. Run by
CTest with ABRDF and SCENES in the environment."""
import json
import math
import os
import re
import struct
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import TempDirCase, checked_stderr  # noqa: E402
from gltf_build import Gltf, cube  # noqa: E402

ABRDF = os.environ["ABRDF"]
SCENES = os.environ["SCENES"]


def abrdf(*args):
    return subprocess.run([ABRDF, *args], capture_output=True)


def cube_gltf(with_camera=True, with_light=True):
    pos, nrm, idx = cube()
    g = Gltf()
    mat = g.material(pbrMetallicRoughness={"baseColorFactor": [0.8, 0.3, 0.2, 1],
                                           "metallicFactor": 0.0, "roughnessFactor": 0.5},
                     extensions={"KHR_materials_ior": {"ior": 1.4}})
    m = g.mesh(pos, idx, nrm, material=mat)
    a = math.radians(30)
    # a parent's translation, the child's rotation and scale: the scene's T * Ry * S
    child = g.node(root=False, mesh=m, rotation=[0, math.sin(a / 2), 0, math.cos(a / 2)],
                   scale=[1, 1.5, 1])
    g.node(children=[child], translation=[0.1, 0.2, -0.3])
    if with_camera:
        g.doc["cameras"] = [{"type": "perspective",
                             "perspective": {"yfov": math.radians(40), "aspectRatio": 1.5,
                                             "znear": 0.1}}]
        g.node(camera=0, translation=[0, 0.5, 4])
    if with_light:
        g.doc["extensionsUsed"] = ["KHR_lights_punctual", "KHR_materials_ior"]
        g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
            {"type": "point", "intensity": 20, "color": [1, 0.9, 0.8]}]}}
        g.node(translation=[2, 3, 3], extensions={"KHR_lights_punctual": {"light": 0}})
    return g, pos, nrm, idx


CUBE_SCENE = """camera position=0,0.5,4 look_at=0,0.5,3 fov=40 resolution=48,32
light point position=2,3,3 color=1,0.9,0.8 intensity=20
material m pbr base_color=0.8,0.3,0.2 metallic=0 roughness=0.5 ior=1.4
mesh file=cube.obj material=m translate=0.1,0.2,-0.3 rotate=0,30,0 scale=1,1.5,1
"""


def nmse(a, b):
    r = abrdf("compare", a, b)
    m = re.search(rb"NMSE\s+(\S+)", r.stdout)
    assert m, r.stdout + r.stderr
    return float(m.group(1))


class ReadGltf(TempDirCase):
    def render(self, path, *args):
        out = path + ".exr"
        r = abrdf("render", path, "-o", out, "--width", "48", "--height", "32", *args)
        checked_stderr(r)
        self.assertEqual(r.returncode, 0, r.stderr)
        return out, r.stdout.decode()

    def test_cube_matches_the_scene_format(self):
        g, pos, nrm, idx = cube_gltf()
        g.write_gltf(self.path("cube.gltf"))
        with open(self.path("cube.obj"), "w") as f:
            for i in range(0, len(pos), 3):
                f.write("v %r %r %r\n" % tuple(pos[i:i + 3]))
            for i in range(0, len(nrm), 3):
                f.write("vn %r %r %r\n" % tuple(nrm[i:i + 3]))
            for i in range(0, len(idx), 3):
                f.write("f " + " ".join("%d//%d" % (j + 1, j + 1) for j in idx[i:i + 3]) + "\n")
        self.put("cube.scene", CUBE_SCENE)
        a, _ = self.render(self.path("cube.gltf"))
        b, _ = self.render(self.path("cube.scene"))
        self.assertLess(nmse(b, a), 1e-6)

    def test_glb_and_external_bin_render_alike(self):
        g, _, _, _ = cube_gltf()
        g.write_gltf(self.path("a.gltf"))
        g.write_gltf(self.path("b.gltf"), "b.bin")
        g.write_glb(self.path("c.glb"))
        a, _ = self.render(self.path("a.gltf"))
        for other in ("b.gltf", "c.glb"):
            self.assertEqual(nmse(a, self.render(self.path(other))[0]), 0.0)
        # the .bin is one of the scene's files: never an output
        with open(self.path("b.bin"), "rb") as f:
            before = f.read()
        r = abrdf("export", "--pov", self.path("b.gltf"), "-o", self.path("b.bin"))
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn(b"buffer file", r.stderr)
        with open(self.path("b.bin"), "rb") as f:
            self.assertEqual(f.read(), before)

    def test_strips_and_fans_are_the_triangles(self):
        # a quad facing the default camera, three ways: its two triangles, a strip, a fan
        pos = [-1, -1, 0, 1, -1, 0, -1, 1, 0, 1, 1, 0]
        forms = {"tris.gltf": ([0, 1, 2, 2, 1, 3], None), "strip.gltf": ([0, 1, 2, 3], 5),
                 "fan.gltf": ([0, 1, 3, 2], 6)}
        images = []
        for name, (indices, mode) in forms.items():
            g = Gltf()
            g.node(mesh=g.mesh(pos, indices, mode=mode))
            g.write_gltf(self.path(name))
            images.append(self.render(self.path(name))[0])
        # (compare finds no NMSE against a black reference: the quad is seen)
        for other in images[1:]:
            self.assertEqual(nmse(images[0], other), 0.0)

    def test_explain_states_the_defaults(self):
        g, _, _, _ = cube_gltf(with_camera=False, with_light=False)
        g.doc["materials"][0]["emissiveFactor"] = [1, 0, 0]
        g.doc["materials"][0]["extensions"]["KHR_materials_volume"] = {"thicknessFactor": 1}
        g.write_glb(self.path("d.glb"))
        _, out = self.render(self.path("d.glb"), "--explain")
        notes = [l for l in out.splitlines() if l.startswith("scene: ")]
        for want in ("no camera", "no light", "emission left out",
                     "extension KHR_materials_volume left out"):
            self.assertTrue(any(want in n for n in notes), (want, notes))

    def test_bad_files_one_line_no_output(self):
        tri = [0, 0, 0, 1, 0, 0, 0, 1, 0]
        cases = {}
        g = Gltf()
        g.node(mesh=g.mesh(tri, [0, 1, 3]))
        cases["index.gltf"] = (g, "index 3 (at 2) but 3 vertices")
        g = Gltf()
        g.node(mesh=g.mesh(tri))
        g.doc["accessors"][0]["count"] = 4
        cases["count.gltf"] = (g, "reach past its bufferView")
        g = Gltf()
        g.node(mesh=g.mesh(tri))
        g.doc["bufferViews"][0]["byteOffset"] = 8
        cases["view.gltf"] = (g, "reach past the buffer")
        g = Gltf()
        g.node(mesh=g.mesh(tri))
        g.doc["cameras"] = [{"type": "orthographic", "orthographic":
                             {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 9}}]
        g.node(camera=0)
        cases["ortho.gltf"] = (g, "orthographic")
        g = Gltf()
        n = g.node(mesh=g.mesh(tri))
        g.doc["nodes"][n]["children"] = [n]
        cases["cycle.gltf"] = (g, "reached twice")
        g = Gltf()
        g.node(mesh=g.mesh(tri, material=0))
        g.material(pbrMetallicRoughness={"metallicFactor": 2})
        cases["metal.gltf"] = (g, "metallic")
        # an image in a bufferView reaching past its buffer: refused before a byte is read
        g = Gltf()
        g.node(mesh=g.mesh(tri, uvs=[0, 0, 1, 0, 0, 1], material=0))
        g.material(pbrMetallicRoughness={"baseColorTexture": {"index": 0}})
        g.doc["bufferViews"].append({"buffer": 0, "byteOffset": 0, "byteLength": 200000})
        g.doc["images"] = [{"bufferView": len(g.doc["bufferViews"]) - 1,
                            "mimeType": "image/png"}]
        g.doc["textures"] = [{"source": 0}]
        cases["image_view.gltf"] = (g, "reaches past its buffer")
        for name, (g, want) in cases.items():
            g.write_gltf(self.path(name))
        # extras nested 5000 deep (tinygltf recurses into them): refused before it parses
        g = Gltf()
        g.node(mesh=g.mesh(tri))
        g.write_gltf(self.path("deep.gltf"))
        with open(self.path("deep.gltf")) as f:
            text = f.read()
        self.put("deep.gltf", '{"extras": ' + "[" * 5000 + "]" * 5000 + ", " + text.lstrip()[1:])
        cases["deep.gltf"] = (None, "JSON nested more than 256 deep")
        self.put("json.gltf", "{ not json")
        cases["json.gltf"] = (None, "")
        good, _, _, _ = cube_gltf()
        self.put("cut.glb", good.glb_bytes()[:300])
        cases["cut.glb"] = (None, "")
        good.write_gltf(self.path("nobin.gltf"), "nobin.bin")
        os.remove(self.path("nobin.bin"))
        cases["nobin.gltf"] = (None, "nobin.bin")
        for name, (_, want) in cases.items():
            out = self.path(name + ".exr")
            r = abrdf("render", self.path(name), "-o", out)
            err = checked_stderr(r)
            self.assertEqual(r.returncode, 1, (name, err))
            self.assertEqual(err.count("\n"), 1, (name, err))
            self.assertTrue(err.startswith("abrdf render: " + self.path(name) + ": "),
                            (name, err))
            self.assertIn(want, err, name)
            self.assertFalse(os.path.exists(out), name)

    def test_mirrored_normals_face_out(self):
        """A mirroring node (negative determinant) turns the winding and the file's normals
        alike: the cube renders as the same cube without NORMAL (normals computed)."""
        pos, nrm, idx = cube()
        outs = []
        for with_normals in (True, False):
            g = Gltf()
            m = g.mesh(pos, idx, nrm if with_normals else None,
                       material=g.material(pbrMetallicRoughness={"metallicFactor": 0.0}))
            g.node(mesh=m, scale=[-1, 1, 1], rotation=[0, 0.2588, 0, 0.9659])
            g.doc["cameras"] = [{"type": "perspective",
                                 "perspective": {"yfov": 0.7, "aspectRatio": 1.5, "znear": 0.1}}]
            g.node(camera=0, translation=[0, 0.5, 4])
            name = "mirror%d.gltf" % with_normals
            g.write_gltf(self.path(name))
            outs.append(self.render(self.path(name))[0])
        self.assertLess(nmse(outs[1], outs[0]), 1e-6)

    def test_export_reads_gltf(self):
        g, _, _, _ = cube_gltf()
        g.write_glb(self.path("e.glb"))
        r = abrdf("export", "--pov", self.path("e.glb"), "-o", self.path("e.pov"))
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(self.path("e.pov")) as f:
            self.assertIn("mesh2", f.read())
        r = abrdf("export", "--cycles", self.path("e.glb"), "-o", self.path("e.py"))
        self.assertEqual(r.returncode, 0, r.stderr)


PBR_SCENE = """camera position=0,1,5 look_at=0,0.3,0 fov=40
ambient 0.05,0.04,0.03
light directional direction=-1,2,1.5 color=1,0.95,0.9 intensity=3
light point position=2,3,2 intensity=8
material gold pbr base_color=1,0.78,0.34 metallic=1 roughness=0.35
material coat pbr base_color=0.2,0.3,0.8 metallic=0 roughness=0.6 ior=1.45 specular=0.8 \
specular_color=1,0.9,0.9 clearcoat=0.5 clearcoat_roughness=0.1 ka=0.1,0.1,0.1
material aniso pbr base_color=0.9,0.9,0.9 metallic=1 roughness=0.4 anisotropy=0.6
material plastic diffuse=lambert specular=blinn_phong kd=0.5,0.1,0.1 ks=0.3 n=40
material chosen pbr base_color=0.8,0.2,0.2 metallic=0 roughness=0.4 goal=performance
sphere material=gold radius=0.5 translate=-1.2,0.5,0
box material=coat size=0.8,0.6,0.8 translate=0,0.3,0 rotate=0,25,0
capsule material=aniso radius=0.3 height=0.6 translate=1.2,0.6,0 rotate=0,0,20 tangent=v
cylinder material=plastic radius=2 height=0.1 translate=0,-0.05,0
mesh file=%s material=plastic scale=0.3 translate=0,0.6,1 rotate=0,40,0 smooth=off
sphere material=chosen radius=0.3 translate=0.8,0.3,1.2
""".replace("\\\n", "")


class WriteGltf(TempDirCase):
    SIZE = ("--width", "48", "--height", "36")

    def round_trip(self, scene):
        ref = self.path("ref.exr")
        r = abrdf("render", scene, "-o", ref, *self.SIZE)
        self.assertEqual(r.returncode, 0, r.stderr)
        for ext in ("gltf", "glb"):
            out = self.path("out." + ext)
            r = abrdf("export", "--gltf", scene, "-o", out, *self.SIZE)
            checked_stderr(r)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out, "rb") as f:
                head = f.read(4)
            self.assertEqual(head == b"glTF", ext == "glb")
            img = self.path("out_%s.exr" % ext)
            r = abrdf("render", out, "-o", img)  # the resolution comes from the file
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertLess(nmse(ref, img), 1e-6, (scene, ext))

    def test_teapot(self):
        self.round_trip(os.path.join(SCENES, "teapot.scene"))

    def test_sphere(self):
        self.round_trip(os.path.join(SCENES, "sphere.scene"))

    def test_pbr_shapes_and_explicit_models(self):
        scene = self.put("pbr.scene", PBR_SCENE % os.path.join(SCENES, "teapot.obj"))
        self.round_trip(scene)
        r = abrdf("export", "--gltf", scene, "-o", self.path("p.gltf"))
        with open(self.path("p.gltf")) as f:
            doc = json.load(f)
        self.assertEqual(doc["asset"]["version"], "2.0")
        for ext in ("KHR_lights_punctual", "KHR_materials_clearcoat", "KHR_materials_anisotropy"):
            self.assertIn(ext, doc["extensionsUsed"])
        plastic = [m for m in doc["materials"] if m["name"] == "plastic"][0]
        self.assertEqual(plastic["extras"]["abrdf"]["models"], ["lambert", "blinn_phong"])
        self.assertEqual(plastic["extras"]["abrdf"]["params"]["n"], 40)
        shapes = [n["extras"]["abrdf"]["shape"] for n in doc["nodes"] if "extras" in n]
        self.assertEqual(shapes, ["sphere", "box", "capsule", "cylinder", "mesh", "sphere"])
        # a pbr material whose models the selection chose: its factors, and the models
        chosen = [m for m in doc["materials"] if m["name"] == "chosen"][0]
        self.assertEqual(chosen["pbrMetallicRoughness"]["roughnessFactor"], 0.4)
        self.assertIn("models", chosen["extras"]["abrdf"])

    def test_maps_written(self):
        # embedded images: one image in the buffer for the three maps that read it
        seed = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "fuzz", "corpus",
                            "gltf", "strip.gltf")
        glb = self.path("strip.glb")
        r = abrdf("export", "--gltf", seed, "-o", glb)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(glb, "rb") as f:
            data = f.read()
        (jlen,) = struct.unpack("<I", data[12:16])
        doc = json.loads(data[20:20 + jlen])
        self.assertEqual(doc["images"], [{"bufferView": 0, "mimeType": "image/png"}])
        mat = doc["materials"][0]
        pm = mat["pbrMetallicRoughness"]
        self.assertEqual(pm["baseColorTexture"]["extensions"]["KHR_texture_transform"],
                         {"offset": [0.5, 0.0], "rotation": 0.3, "scale": [2.0, 2.0]})
        self.assertEqual(pm["metallicRoughnessTexture"], {"index": 0})
        self.assertEqual(mat["normalTexture"], {"index": 0, "scale": 0.5})
        # image files: a URI relative to the output, read back from there
        self.put("red.ppm", "P3\n1 1\n255\n255 0 0\n")
        self.put("quad.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                 "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n")
        scene = self.put("tex.scene", "camera position=0,0,3 look_at=0,0,0\n"
                         "material t pbr base_color_map=red.ppm occlusion_map=red.ppm "
                         "occlusion_strength=0.5\nmesh file=quad.obj material=t\n")
        os.mkdir(self.path("sub"))
        out = self.path("sub/tex.gltf")
        r = abrdf("export", "--gltf", scene, "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out) as f:
            doc = json.load(f)
        self.assertEqual(doc["images"], [{"uri": "../red.ppm"}])
        self.assertEqual(doc["materials"][0]["occlusionTexture"], {"index": 0, "strength": 0.5})
        r = abrdf("render", out, "-o", self.path("tex.exr"), "--width", "8", "--height", "8")
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_area_lights_refused(self):
        out = self.path("area.gltf")
        r = abrdf("export", "--gltf", os.path.join(SCENES, "area.scene"), "-o", out)
        err = checked_stderr(r)
        self.assertEqual(r.returncode, 1)
        self.assertEqual(err.count("\n"), 1, err)
        self.assertIn("area.scene: light", err)
        self.assertFalse(os.path.exists(out))


if __name__ == "__main__":
    unittest.main()
