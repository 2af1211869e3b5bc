"""abrdf for Blender: the library's reflectance models and the paper's adaptive selection
(Zavalniuk & Romanyuk 2024) as materials for Cycles' Open Shading Language (CPU).

Shader Editor or Material Properties > abrdf: "New abrdf material" adds a material whose
Script node runs the OSL port (osl/abrdf_material.osl: the models on Cycles' closures; or
osl/abrdf_eval.osl: the exact model under the scene's lights, as emission), with every model
of the library in a list and its parameters within their ranges; "Select models" runs the
flowchart (the abrdf Python package, bundled as a wheel) and applies its choice. "Advise
Principled materials" gives the choice for every Principled BSDF material of the file.
docs/OSL.md, "The Blender extension".
"""
import bpy

from . import abrdf_ext_material, abrdf_ext_props, abrdf_ext_ui


def register():
    abrdf_ext_props.register()
    abrdf_ext_ui.register()
    bpy.app.handlers.load_post.append(abrdf_ext_material.refresh_tables)


def unregister():
    if abrdf_ext_material.refresh_tables in bpy.app.handlers.load_post:
        bpy.app.handlers.load_post.remove(abrdf_ext_material.refresh_tables)
    abrdf_ext_ui.unregister()
    abrdf_ext_props.unregister()
