#!/usr/bin/env python3
"""The Blender extension's advisor of Principled materials (blender/abrdf_ext_advise.py,
docs/OSL.md "Advising Principled materials") in Blender's `bpy` module, headless:

1. a .blend made here with Principled materials (a gold metal r 0.3, a smooth dielectric
   r 0.02, a coated one with a tinted Specular IOR Level, a sheen, one of Specular IOR
   Level 0, one whose roughness an Image Texture drives) and one Emission material is
   saved and opened again;
2. "Advise Principled materials" (the installed extension's operator) for the photoreal
   and performance goals and a budget chooses, per material, what `abrdf advise FILE.scene
   --json` chooses for `material NAME pbr` lines holding the glTF values this test derives
   from the sockets by the documented mapping; the values the extension read (its text's
   `abrdf_pbr:` line) are those, and the trace lines are the command's;
3. the text "abrdf advice" holds every advised material's trace, the driven input is named
   with the value advised on, and the Emission material is listed as not advised;
4. the panel draws the goal's settings, the button and each material's result;
5. an IOR below 1 or above 4 is read at the same dielectric F0;
6. a Base Color above 1 cancels the run with one line naming the material and the field,
   leaving the last results and the text as they were.

usage: test_blender_advise.py ABRDF SOURCE_DIR WORK_DIR ZIP [unittest args]  (with bpy)
Fails, never skips, when bpy or the zip is missing.
"""
import json
import math
import os
import shutil
import subprocess
import sys
import unittest

if len(sys.argv) < 5:
    sys.exit(__doc__)
ABRDF, SRC, WORK, ZIP = (os.path.abspath(a) for a in sys.argv[1:5])
# Blender's user directory (preferences, extensions) in the scratch directory, before bpy loads.
USER = os.path.join(WORK, "blender_user")
shutil.rmtree(USER, ignore_errors=True)
os.environ["BLENDER_USER_RESOURCES"] = USER

import bpy  # noqa: E402

MODULE = "bl_ext.user_default.abrdf"
BLEND = os.path.join(WORK, "principled.blend")

# name: Principled BSDF inputs (the rest at Blender's defaults)
MATERIALS = {
    "Gold": {"Base Color": (1.0, 0.766, 0.336), "Metallic": 1.0, "Roughness": 0.3},
    "Glaze": {"Base Color": (0.2, 0.3, 0.6), "Metallic": 0.0, "Roughness": 0.02},
    "Lacquer": {"Base Color": (0.6, 0.05, 0.05), "Roughness": 0.4, "IOR": 1.45,
                "Specular IOR Level": 0.7, "Specular Tint": (1.0, 0.9, 0.8),
                "Coat Weight": 1.0, "Coat Roughness": 0.05},
    "Cloth": {"Base Color": (0.3, 0.3, 0.5), "Roughness": 0.8, "Sheen Weight": 0.8,
              "Sheen Tint": (0.9, 0.5, 0.5), "Sheen Roughness": 0.7},
    "Scuffed": {"Base Color": (0.5, 0.5, 0.5), "Metallic": 1.0, "Roughness": 0.45},
    "Chalk": {"Base Color": (0.9, 0.9, 0.85), "Roughness": 0.9, "Specular IOR Level": 0.0},
}
DRIVEN = ("Scuffed", "Roughness")  # an Image Texture drives this input


def run(*args):
    r = subprocess.run([ABRDF, *args], capture_output=True, text=True)
    if r.returncode:
        raise AssertionError("abrdf %s: %s" % (" ".join(args), r.stderr.strip()))
    return r.stdout


def on_object(mat):
    """An object that uses the material (a .blend keeps only materials in use)."""
    mesh = bpy.data.meshes.new(mat.name)
    mesh.materials.append(mat)
    bpy.context.scene.collection.objects.link(bpy.data.objects.new(mat.name, mesh))
    return mat


def make_blend():
    """The test file: objects with the Principled materials and an Emission material."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    for name, inputs in MATERIALS.items():
        mat = on_object(bpy.data.materials.new(name))
        if mat.node_tree is None:
            mat.use_nodes = True
        bsdf = next(n for n in mat.node_tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled")
        for key, value in inputs.items():
            bsdf.inputs[key].default_value = value + (1.0,) if isinstance(value, tuple) else value
    img = bpy.data.images.new("scratches", 4, 4)
    mat = bpy.data.materials[DRIVEN[0]]
    tex = mat.node_tree.nodes.new("ShaderNodeTexImage")
    tex.image = img
    bsdf = next(n for n in mat.node_tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled")
    mat.node_tree.links.new(tex.outputs["Color"], bsdf.inputs[DRIVEN[1]])
    mat = on_object(bpy.data.materials.new("Lamp"))
    if mat.node_tree is None:
        mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    nt.links.new(nt.nodes.new("ShaderNodeEmission").outputs[0], out.inputs["Surface"])
    bpy.ops.wm.save_as_mainfile(filepath=BLEND)


def gltf_values(bsdf):
    """The glTF values of a Principled BSDF, by the mapping docs/OSL.md states (written
    here from the sockets, independently of the extension)."""
    v = {s.name: (tuple(s.default_value)[:3] if hasattr(s.default_value, "__len__")
                  else s.default_value) for s in bsdf.inputs if hasattr(s, "default_value")}
    level = v["Specular IOR Level"]
    lobe = level > 0 and v["IOR"] != 1  # F0 0: Cycles has no specular lobe
    return {"base_color": v["Base Color"], "metallic": v["Metallic"],
            "roughness": v["Roughness"], "ior": v["IOR"],
            "specular": 1.0 if lobe else 0.0,
            "specular_color": (tuple(2 * level * t for t in v["Specular Tint"]) if lobe
                               else (1.0, 1.0, 1.0)),
            "clearcoat": v["Coat Weight"], "clearcoat_roughness": v["Coat Roughness"],
            "sheen_color": tuple(v["Sheen Weight"] * t for t in v["Sheen Tint"]),
            "sheen_roughness": v["Sheen Roughness"], "anisotropy": v["Anisotropic"],
            "transmission": v["Transmission Weight"]}


def scene_file():
    """The materials as `material NAME pbr` lines of a scene `abrdf advise` reads, and
    their glTF values by name."""
    lines = ["camera position=0,0,4 look_at=0,0,0 up=0,1,0 fov=30 resolution=8,8",
             "light directional direction=-1,1,1 color=1,1,1 intensity=3"]
    values = {}
    for name in MATERIALS:
        bsdf = next(n for n in bpy.data.materials[name].node_tree.nodes
                    if n.bl_idname == "ShaderNodeBsdfPrincipled")
        values[name] = gltf_values(bsdf)
        words = ["%s=%s" % (k, ",".join(repr(float(c)) for c in v) if isinstance(v, tuple)
                            else repr(float(v))) for k, v in values[name].items()]
        lines.append("material %s pbr %s" % (name, " ".join(words)))
    lines.append("sphere material=Gold radius=1")
    path = os.path.join(WORK, "principled.scene")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path, values


class Layout:
    """A stand-in for a panel's layout: records labels, checks that every property drawn
    exists on its data and every operator is registered."""

    def __init__(self, out):
        self.out = out

    def prop(self, data, name, **kw):
        assert name in data.bl_rna.properties, name
        self.out.append("prop " + name)

    def operator(self, idname, **kw):
        mod, op = idname.split(".")
        assert hasattr(getattr(bpy.ops, mod), op), idname
        self.out.append("operator " + idname)

    def label(self, text="", **kw):
        self.out.append(text)

    def box(self):
        return self


class Advise(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        if not os.path.isfile(ZIP):
            raise AssertionError("%s is missing: the build makes it with .venv-python "
                                 "(scripts/setup_python.sh; then re-run cmake)" % ZIP)
        r = bpy.ops.extensions.package_install_files(filepath=ZIP, repo="user_default",
                                                     enable_on_install=True)
        assert r == {"FINISHED"}, r
        make_blend()
        bpy.ops.wm.open_mainfile(filepath=BLEND)
        if MODULE not in bpy.context.preferences.addons:
            bpy.ops.preferences.addon_enable(module=MODULE)
        cls.scene, cls.values = scene_file()

    def advise(self, **settings):
        st = bpy.context.scene.abrdf_advice
        for k, v in settings.items():
            setattr(st, k, v)
        self.assertEqual(bpy.ops.abrdf.advise_principled(), {"FINISHED"})
        return {r.material: r for r in st.results}

    def check(self, args, **settings):
        got = self.advise(**settings)
        ref = {m["material"]: m for m in json.loads(run("advise", self.scene, *args,
                                                        "--json"))["materials"]}
        text = bpy.data.texts["abrdf advice"].as_string()
        self.assertEqual(sorted(ref), sorted(n for n, r in got.items() if r.choice))
        for name, m in ref.items():
            with self.subTest(material=name, args=args):
                want = "%s%s" % (m["diffuse"] + " + " if m["diffuse"] else "", m["specular"])
                self.assertEqual(got[name].choice, want)
                block = text.split("\n%s: " % name, 1)[1].split("\n\n", 1)[0]
                self.assertTrue(block.startswith(want + "\n"), block)
                # The values the extension read: the mapping stated in docs/OSL.md.
                pbr = dict(w.split("=") for w in block.split("\n  abrdf_pbr: ", 1)[1]
                           .split("\n", 1)[0].split())
                for key, want_v in self.values[name].items():
                    read_v = [float(c) for c in pbr[key].split(",")]
                    want_v = list(want_v) if isinstance(want_v, tuple) else [want_v]
                    self.assertEqual(len(read_v), len(want_v), key)
                    for a, b in zip(read_v, want_v):
                        self.assertTrue(math.isclose(a, b, rel_tol=1e-5, abs_tol=1e-6),
                                        (key, read_v, want_v))
                trace = [line.split(". ", 1)[1] for line in block.splitlines()
                         if line.startswith("  ") and line[2:4].strip().isdigit()]
                self.assertEqual(trace, [s["text"] for s in m["trace"]])
        return got, text

    def test_photoreal(self):
        got, text = self.check(["--goal", "photoreal"], by="GOAL", goal="photoreal")
        self.assertEqual(got["Gold"].choice, "disney_diffuse + disney_specular")
        self.assertEqual(got["Glaze"].choice, "lambert_fresnel + f_2e")
        self.assertNotEqual(got["Lacquer"].choice, got["Glaze"].choice)
        self.assertIn("Roughness is driven by a node (Image Texture \"Image Texture\"): "
                      "advised on its default value 0.45", got["Scuffed"].notes)
        self.assertIn("note: Roughness is driven by a node", text)
        self.assertEqual(got["Lamp"].choice, "")
        self.assertIn("Lamp: not advised: its Surface comes from Emission", text)

    def test_performance(self):
        got, _ = self.check(["--goal", "performance", "--max-rel-error", "5"],
                            by="GOAL", goal="performance", max_rel_error=5.0)
        self.assertTrue(got["Gold"].error.startswith("predicted error"), got["Gold"].error)

    def test_budget(self):
        got, _ = self.check(["--budget", "slight"], by="BUDGET", budget="slight")
        self.assertTrue(got["Glaze"].error.startswith("predicted NMSE"))

    def test_panel(self):
        self.advise(by="GOAL", goal="performance", max_rel_error=5.0)
        ui = sys.modules[MODULE + ".abrdf_ext_ui"]
        out = []
        ui.draw_advice(Layout(out), bpy.context)
        self.assertIn("prop max_rel_error", out)
        self.assertIn("operator abrdf.advise_principled", out)
        results = bpy.context.scene.abrdf_advice.results
        for r in results:
            line = "%s: %s" % (r.material, r.choice) if r.choice else r.material + ": not advised"
            self.assertIn(line, out)
        gold = out.index("Gold: %s" % results["Gold"].choice)
        self.assertRegex(out[gold + 1], r"^predicted error .* relative, .* absolute; cost ")

    def test_ior_outside_abrdf_pbr(self):
        """IOR below 1 or above 4 is read at the same dielectric F0 (docs/OSL.md's table)."""
        import abrdf
        adv = sys.modules[MODULE + ".abrdf_ext_advise"]
        bsdf = next(n for n in bpy.data.materials["Lacquer"].node_tree.nodes
                    if n.bl_idname == "ShaderNodeBsdfPrincipled")
        values, _ = adv.socket_inputs(bsdf)
        level, tint = values["Specular IOR Level"], values["Specular Tint"]
        for ior in (0.4, 1.0 / 0.4, 6.0, 1.0 / 6.0):
            with self.subTest(ior=ior):
                fields, notes = adv.pbr_fields(dict(values, IOR=ior))
                self.assertTrue(1 <= fields["ior"] <= 4, fields["ior"])
                f0 = ((ior - 1) / (ior + 1)) ** 2
                want = [min(f0 * 2 * level * t, 1.0) for t in tint]
                got = abrdf.pbr_material(abrdf.Pbr(**fields)).f0
                for a, b in zip(got, want):
                    self.assertTrue(math.isclose(a, b, rel_tol=1e-9), (got, want))
                self.assertEqual(any(n.startswith("IOR ") for n in notes),
                                 max(ior, 1 / ior) > 4)

    def test_refuses_out_of_range(self):
        self.advise(by="GOAL", goal="photoreal")
        before = bpy.data.texts["abrdf advice"].as_string()
        sock = next(n for n in bpy.data.materials["Glaze"].node_tree.nodes
                    if n.bl_idname == "ShaderNodeBsdfPrincipled").inputs["Base Color"]
        old = tuple(sock.default_value)
        sock.default_value = (1.5, 0.3, 0.6, 1.0)
        try:
            with self.assertRaisesRegex(RuntimeError, r'material "Glaze": base_color'):
                bpy.ops.abrdf.advise_principled()
        finally:
            sock.default_value = old
        self.assertEqual(bpy.data.texts["abrdf advice"].as_string(), before)
        self.assertEqual(len(bpy.context.scene.abrdf_advice.results), len(MATERIALS) + 1)


if __name__ == "__main__":
    os.makedirs(WORK, exist_ok=True)
    unittest.main(argv=[sys.argv[0]] + sys.argv[5:], verbosity=2)
