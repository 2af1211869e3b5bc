#!/usr/bin/env python3
"""The Blender extension (blender/, docs/OSL.md, "The Blender extension") in Blender's
`bpy` module, headless:

1. the built .zip installs (Install from Disk's operator) into a scratch user directory and
   enables; its bundled abrdf package is the one the add-on imports;
2. the material's model lists are the registry's, and its parameter ranges are the OSL
   shader's metadata (read from the compiled node with oslquery);
3. an abrdf material added by the extension's operator to every object of a test scene
   renders as `abrdf render` does: closure mode on the sphere (64x64, 64 samples, the bar of
   test_osl_cycles.py's test_closure_mode_renders), evaluation mode on the lit box with the
   scene's lights taken by the extension (48x48, 64 samples, the bar of
   test_generic_shader_on_a_box): NMSE < 1e-4;
4. the selection panel's operator applies the flowchart's choice as `abrdf advise` makes it;
5. the add-on disables cleanly.

usage: test_blender_extension.py ABRDF SOURCE_DIR WORK_DIR ZIP [unittest args]  (with bpy)
Fails, never skips, when bpy or the zip is missing.
"""
import math
import os
import re
import shutil
import sys
import tempfile
import unittest
import zipfile

import numpy as np

if len(sys.argv) < 5:
    sys.exit(__doc__)
ZIP = os.path.abspath(sys.argv[4])
# Blender's user directory (preferences, extensions) in the scratch directory, before bpy loads.
USER = os.path.join(os.path.abspath(sys.argv[3]), "blender_user")
shutil.rmtree(USER, ignore_errors=True)
os.environ["BLENDER_USER_RESOURCES"] = USER

import test_osl_cycles as osl_test  # noqa: E402  (bpy, abrdf_cycles, the cross-check helpers)
from test_osl_cycles import NMSE_MAX, SRC, WORK, abrdf_cycles, captured_fds, render_pair, run  # noqa: E402

import bpy  # noqa: E402

MODULE = "bl_ext.user_default.abrdf"


def enable():
    """Enable the add-on (abrdf_cycles.build's factory reset disables it)."""
    if MODULE not in bpy.context.preferences.addons:
        bpy.ops.preferences.addon_enable(module=MODULE)
    return sys.modules[MODULE]


def objects(s):
    """(Blender object, scene object, scene material) in abrdf_cycles.build's naming."""
    for k, o in enumerate(s["objects"]):
        yield bpy.data.objects["%s%d" % (o["shape"], k)], o, s["materials"][o["material"]]


def add_material(ob, mode):
    with bpy.context.temp_override(object=ob, active_object=ob):
        assert bpy.ops.abrdf.material_add(mode=mode) == {"FINISHED"}
    return ob.active_material


def set_settings(mat, o, m, mode):
    """The scene material's values as the extension's settings (what a user types in)."""
    inputs = abrdf_cycles.material_inputs(m)
    st = mat.abrdf
    for key, value in inputs.items():
        if key == "model2":
            value = value or "NONE"
            if mode == "EVALUATION":
                continue
        setattr(st, key, tuple(value) if isinstance(value, (list, tuple)) else value)
    st.tangent_rule = o.get("tangent", "u")
    st.tangent_axis = tuple(o.get("tangent_axis", (1, 0, 0)))
    if mode == "EVALUATION":
        st.ambient = tuple(m["ambient"])


def use_extension(mode, hair_table=None):
    """A render_pair `prepare`: every object gets the extension's material in `mode`; with
    hair_table (sizes), its huang tabulated by the extension's operator."""
    def prepare(sc, s):
        enable()
        if mode == "EVALUATION":
            abrdf_cycles.setup_lights(sc, s)  # the extension takes the lights from the scene
        for ob, o, m in objects(s):
            ob.data.materials.clear()
            mat = add_material(ob, mode)
            set_settings(mat, o, m, mode)
            if mode == "EVALUATION":
                with bpy.context.temp_override(object=ob, active_object=ob, material=mat):
                    assert bpy.ops.abrdf.sync_lights() == {"FINISHED"}
                    if hair_table:
                        mat.abrdf.hair_table_sizes = hair_table
                        assert bpy.ops.abrdf.tabulate_hair() == {"FINISHED"}
    return prepare


class Install(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        if not os.path.isfile(ZIP):
            raise AssertionError("%s is missing: the build makes it with .venv-python "
                                 "(scripts/setup_python.sh; then re-run cmake)" % ZIP)
        with captured_fds():
            r = bpy.ops.extensions.package_install_files(filepath=ZIP, repo="user_default",
                                                         enable_on_install=True)
        assert r == {"FINISHED"}, r
        assert MODULE in bpy.context.preferences.addons

    def test_1_bundled_package_and_versions(self):
        ext = enable()
        import abrdf
        self.assertTrue(os.path.realpath(abrdf.__file__).startswith(os.path.realpath(USER)),
                        abrdf.__file__)
        version = run("models", "--json")
        self.assertIn('"version": "%s"' % abrdf.__version__, version)
        with zipfile.ZipFile(ZIP) as z:
            manifest = z.read("blender_manifest.toml").decode()
            names = z.namelist()
        self.assertRegex(manifest, r'(?m)^version = "%s"$' % re.escape(abrdf.__version__))
        self.assertIn("osl/abrdf_material.osl", names)
        self.assertIn("osl/abrdf_eval.osl", names)
        for f in os.listdir(os.path.join(SRC, "osl")):
            if f.endswith((".h", ".osl")):
                self.assertIn("osl/" + f, names)
        self.assertTrue(hasattr(ext, "register"))

    def test_2_models_and_ranges(self):
        enable()
        import abrdf
        abrdf_cycles.cycles_osl()  # puts Blender's oslquery on sys.path
        import oslquery
        bpy.ops.wm.read_factory_settings(use_empty=True)
        enable()
        props = bpy.types.Material.bl_rna.properties["abrdf"].fixed_type.bl_rna.properties
        names = [m.name for m in abrdf.models()]
        self.assertEqual([i.identifier for i in props["model"].enum_items], names)
        self.assertEqual([i.identifier for i in props["model2"].enum_items], ["NONE"] + names)
        bpy.ops.mesh.primitive_cube_add()
        ob = bpy.context.object
        for mode in ("CLOSURE", "EVALUATION"):
            mat = add_material(ob, mode)
            node = mat.node_tree.nodes["abrdf"]
            self.assertTrue(node.bytecode)
            self.assertEqual(node.outputs[0].links[0].to_node.bl_idname, "ShaderNodeOutputMaterial")
            with tempfile.TemporaryDirectory() as d:
                oso = os.path.join(d, "shader.oso")
                with open(oso, "w") as f:
                    f.write(node.bytecode)
                params = oslquery.OSLQuery(oso).parameters
            checked = 0
            for p in params:
                meta = {m.name: m.value for m in p.metadata}
                if p.name not in props or "min" not in meta or props[p.name].type not in ("FLOAT", "INT"):
                    continue
                rna = props[p.name]
                lo = rna.hard_min
                hi = rna.hard_max
                with self.subTest(mode=mode, param=p.name):
                    self.assertTrue(math.isclose(lo, meta["min"], rel_tol=1e-6), (lo, meta["min"]))
                    self.assertTrue(math.isclose(hi, meta["max"], rel_tol=1e-6), (hi, meta["max"]))
                checked += 1
            # Every model parameter of the registry has a socket with a range.
            self.assertGreaterEqual(checked, len(abrdf._abrdf.params()))

    def test_3_closure_mode_renders_as_abrdf_render(self):
        nmse = render_pair("sphere", "scenes/sphere.scene", 64, 64, None, samples=64,
                           mode="closure", c_spp=64, variant="_extension",
                           prepare=use_extension("CLOSURE"))
        sys.stdout.write("\nextension, closure mode, sphere: NMSE %.1e\n" % nmse)
        self.assertLess(nmse, NMSE_MAX)

    def test_4_evaluation_mode_renders_as_abrdf_render(self):
        for model in ("disney_specular", "belcour"):
            with self.subTest(model=model):
                nmse = render_pair("box_point", "tests/data/scenes/box_point.scene", 48, 48,
                                   model, samples=64, mode="generic", c_spp=64,
                                   variant="_extension", prepare=use_extension("EVALUATION"))
                sys.stdout.write("\nextension, evaluation mode, %s on the box: NMSE %.1e\n"
                                 % (model, nmse))
                self.assertLess(nmse, NMSE_MAX)

    def test_4b_evaluation_mode_reads_a_hair_table(self):
        # The extension's operator tabulates a huang material (abrdf.huang_table) and the
        # evaluation shader reads the table, as abrdf render --hair-table reads the same one;
        # a parameter changed since makes it stale (per call), and changing it back reads it
        # again.
        sizes = (12, 3, 8, 1)
        seen = {}

        def prepare(sc, s):
            use_extension("EVALUATION", sizes)(sc, s)
            mat = next(objects(s))[0].active_material
            node, st = mat.node_tree.nodes["abrdf"], mat.abrdf
            path = node.inputs["huang_table"].default_value
            seen["path"] = path
            self.assertTrue(os.path.isfile(path), path)
            self.assertEqual([node.inputs["huang_table_n" + a].default_value for a in "tvp"],
                             list(sizes[:3]))
            with open(path, "rb") as f:  # a float RGB image, nt np x nt nv texels
                self.assertEqual(f.read(14), b"PF\n96 36\n-1.0\n")
                got = np.frombuffer(f.read(), "<f4").reshape(36, 96, 3)[::-1]  # bottom row first
            import abrdf
            table = abrdf.huang_table(abrdf.BRDF("huang", **{
                p: getattr(st, p) for p in enable().abrdf_ext_material.HUANG_TABLE_PARAMS}), sizes)
            # the library's values after its header, a row per view node, in float32
            self.assertTrue(np.array_equal(
                got, np.asarray(table.values[8:], "<f4").reshape(12 * 3, 12 * 8, 3)))
            st.melanin += 0.1
            self.assertEqual(node.inputs["huang_table"].default_value, "")
            st.melanin -= 0.1
            self.assertEqual(node.inputs["huang_table"].default_value, path)
            # a .blend loaded where the table's file is gone: per call, not a black lobe
            mats = enable().abrdf_ext_material
            os.rename(path, path + ".away")
            mats.refresh_tables()
            self.assertEqual((mats.huang_table_state(st), node.inputs["huang_table"].default_value),
                             ("missing", ""))
            os.rename(path + ".away", path)
            mats.refresh_tables()
            self.assertEqual(node.inputs["huang_table"].default_value, path)

        nmse = render_pair("box_point", "tests/data/scenes/box_point.scene", 48, 48, "huang",
                           samples=64, mode="generic", c_spp=64, variant="_extension_table",
                           prepare=prepare, c_args=("--hair-table-sizes", "12,3,8,1"))
        sys.stdout.write("\nextension, evaluation mode, huang from its table on the box: "
                         "NMSE %.1e\n" % nmse)
        self.assertIn("path", seen)
        self.assertLess(nmse, NMSE_MAX)

    def test_4c_hair_tables_follow_the_blend(self):
        # A table built before the first save (Blender's temporary directory) is copied into
        # abrdf_tables/ beside the .blend when it is saved; a .blend moved with that folder
        # reads it from there.
        bpy.ops.wm.read_factory_settings(use_empty=True)
        mats = enable().abrdf_ext_material
        bpy.ops.mesh.primitive_cube_add()
        ob = bpy.context.object
        mat = add_material(ob, "EVALUATION")
        st = mat.abrdf
        st.model, st.aspect_ratio, st.hair_table_sizes = "huang", 1.0, (4, 1, 4, 1)
        with bpy.context.temp_override(object=ob, active_object=ob, material=mat):
            self.assertEqual(bpy.ops.abrdf.tabulate_hair(), {"FINISHED"})
        name, mat_name = os.path.basename(st.hair_table), mat.name
        self.assertTrue(st.hair_table.startswith(bpy.app.tempdir), st.hair_table)
        a, b = os.path.join(WORK, "blend_a"), os.path.join(WORK, "blend_b")
        for d in (a, b):
            shutil.rmtree(d, ignore_errors=True)
        os.makedirs(a)
        with captured_fds():
            bpy.ops.wm.save_as_mainfile(filepath=os.path.join(a, "hair.blend"))
        kept = os.path.join(a, "abrdf_tables", name)
        self.assertEqual(st.hair_table, kept)
        self.assertTrue(os.path.isfile(kept))
        self.assertEqual(mat.node_tree.nodes["abrdf"].inputs["huang_table"].default_value, kept)
        shutil.copytree(a, b)
        shutil.rmtree(a)
        with captured_fds():
            bpy.ops.wm.open_mainfile(filepath=os.path.join(b, "hair.blend"))
        mat = bpy.data.materials[mat_name]
        self.assertEqual(mats.huang_table_state(mat.abrdf), "current")
        self.assertEqual(mat.node_tree.nodes["abrdf"].inputs["huang_table"].default_value,
                         os.path.join(b, "abrdf_tables", name))

    def test_5_selection_applies_advise(self):
        bpy.ops.wm.read_factory_settings(use_empty=True)
        enable()
        bpy.ops.mesh.primitive_uv_sphere_add()
        ob = bpy.context.object
        mat = add_material(ob, "CLOSURE")
        node = mat.node_tree.nodes["abrdf"]
        cases = [("gold", "performance", ["gold"]), ("velvet", "photoreal", ["velvet"]),
                 ("CUSTOM", "photoreal", ["--r", "0.02"])]
        for preset, goal, args in cases:
            with self.subTest(preset=preset, goal=goal):
                st = mat.abrdf
                st.preset, st.goal = preset, goal
                if preset == "CUSTOM":
                    st.surface, st.r, st.n_from_r = "general", 0.02, True
                with bpy.context.temp_override(object=ob, active_object=ob, material=mat):
                    self.assertEqual(bpy.ops.abrdf.select(), {"FINISHED"})
                ref = __import__("json").loads(run("advise", *args, "--goal", goal, "--json"))
                want = [m for m in (ref["diffuse"], ref["specular"]) if m]
                got = [m for m in (st.model, st.model2) if m != "NONE"]
                self.assertEqual(got, want)
                self.assertEqual([node.inputs[k].default_value for k in ("model", "model2")],
                                 want + [""] * (2 - len(want)))
                self.assertTrue(math.isclose(st.n, ref["params"]["n"], rel_tol=1e-6))
                self.assertTrue(math.isclose(node.inputs["n"].default_value, ref["params"]["n"],
                                             rel_tol=1e-6))
                self.assertEqual(st.trace.splitlines()[-1].split(". ", 1)[1],
                                 ref["trace"][-1]["text"])

    def test_6_disables_cleanly(self):
        enable()
        bpy.ops.preferences.addon_disable(module=MODULE)
        self.assertNotIn(MODULE, bpy.context.preferences.addons)
        self.assertFalse(hasattr(bpy.types.Material, "abrdf"))
        self.assertEqual([f.__name__ for f in bpy.app.handlers.save_pre + bpy.app.handlers.load_post
                          if f.__name__ in ("keep_tables", "refresh_tables")], [])
        enable()
        self.assertTrue(hasattr(bpy.types.Material, "abrdf"))


if __name__ == "__main__":
    os.makedirs(WORK, exist_ok=True)
    unittest.main(argv=[sys.argv[0]] + sys.argv[5:], verbosity=2)
