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


def _handlers():
    """The hair tables' file handlers (abrdf_ext_material): kept beside a saved .blend,
    found again after one loads."""
    return ((bpy.app.handlers.save_pre, abrdf_ext_material.keep_tables),
            (bpy.app.handlers.load_post, abrdf_ext_material.refresh_tables))


def register():
    abrdf_ext_props.register()
    abrdf_ext_ui.register()
    for handlers, f in _handlers():
        if f not in handlers:
            handlers.append(f)


def unregister():
    for handlers, f in _handlers():
        if f in handlers:
            handlers.remove(f)
    abrdf_ext_ui.unregister()
    abrdf_ext_props.unregister()
