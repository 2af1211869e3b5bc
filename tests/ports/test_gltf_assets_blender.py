#!/usr/bin/env python3
"""The glTF files of tools/gen/gen_material_assets.py read by an independent reader, Blender's
glTF importer (bpy): each of the three forms (.gltf with .bin and PNG files, .glb, data URIs)
imports with its meshes, camera, light and decoded 8 x 8 images, and every constant
material's Principled BSDF holds the generator's factors (its CONSTANTS table, which
abrdf.load_gltf is held to in tests/python/test_py_gltf.py).

usage: test_gltf_assets_blender.py SOURCE_DIR WORK_DIR [unittest args]  (the Python with bpy)
"""
import importlib.util
import os
import shutil
import subprocess
import sys
import unittest

try:
    import bpy
except ImportError:
    sys.exit("test_gltf_assets_blender: the bpy module is missing; run scripts/setup_bpy.sh")

SRC, WORK = sys.argv[1:3]
del sys.argv[1:3]
SCRIPT = os.path.join(SRC, "tools", "gen", "gen_material_assets.py")
spec = importlib.util.spec_from_file_location("gen_material_assets", SCRIPT)
gen = importlib.util.module_from_spec(spec)
spec.loader.exec_module(gen)


def principled(material):
    return next(n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED")


class GltfAssetsInBlender(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        shutil.rmtree(WORK, ignore_errors=True)
        # the generator writes its PNGs through OpenImageIO, which Blender's Python does not
        # have: Debian's python3 runs it (python3-openimageio, scripts/setup.sh)
        subprocess.run(["/usr/bin/python3", SCRIPT, WORK], check=True)

    def load(self, name):
        bpy.ops.wm.read_factory_settings(use_empty=True)
        result = bpy.ops.import_scene.gltf(filepath=os.path.join(WORK, name))
        self.assertEqual(result, {"FINISHED"})

    def test_forms_import_whole(self):
        for name in ("scene.gltf", "scene.glb", "scene_datauri.gltf"):
            with self.subTest(name):
                self.load(name)
                self.assertEqual(len(bpy.data.meshes), len(gen.CONSTANTS) + 2)
                self.assertEqual((len(bpy.data.cameras), len(bpy.data.lights)), (1, 1))
                self.assertEqual(bpy.data.lights[0].type, "POINT")
                self.assertEqual(len(bpy.data.images), 4)
                for im in bpy.data.images:
                    self.assertEqual(tuple(im.size), (8, 8), im.name)
                    self.assertTrue(im.has_data or im.pixels[:] is not None)
                textured = principled(bpy.data.materials["textured"])
                for key in ("Base Color", "Metallic", "Roughness", "Normal"):
                    self.assertTrue(textured.inputs[key].is_linked, key)

    def test_constant_factors(self):
        self.load("scene.glb")
        for name, f in gen.CONSTANTS.items():
            g = dict(gen.DEFAULTS)
            g.update(f)
            p = principled(bpy.data.materials[name]).inputs
            want = {"Base Color": g["base_color"], "Metallic": g["metallic"],
                    "Roughness": g["roughness"], "Anisotropic": g["anisotropy"],
                    "Transmission Weight": g["transmission"], "Coat Weight": g["clearcoat"]}
            if "ior" in f:
                want["IOR"] = g["ior"]
            if "specular" in f:  # Blender's level is half glTF's specularFactor
                want["Specular IOR Level"] = g["specular"] / 2
                want["Specular Tint"] = g["specular_color"]
            if "clearcoat" in f:
                want["Coat Roughness"] = g["clearcoat_roughness"]
            if "sheen_color" in f:
                want["Sheen Tint"] = g["sheen_color"]
                want["Sheen Roughness"] = g["sheen_roughness"]
            for key, v in want.items():
                got = p[key].default_value
                got = tuple(got)[:3] if isinstance(v, tuple) else got
                with self.subTest(material=name, input=key):
                    if isinstance(v, tuple):
                        for a, b in zip(got, v):
                            self.assertAlmostEqual(a, b, places=6)
                    else:
                        self.assertAlmostEqual(got, v, places=6)


if __name__ == "__main__":
    unittest.main()
