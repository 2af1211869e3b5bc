"""The abrdf material's settings, Material.abrdf, built from the library's registry (the
bundled abrdf package): the models by their stable names, every parameter with the range of
the OSL shaders' metadata (the widest range over the models, as tools/gen/osl_headers.py
writes osl/abrdf_meta.h) and the library's default, the adaptive mode's inputs, and the
selection panel's inputs and last result. Every change is written into the material's
Script node (abrdf_ext_material.push). Scene.abrdf_advice: the advisor of the file's
Principled materials (abrdf_ext_advise), its goal or budget and its last results."""
import bpy
from bpy.props import (BoolProperty, CollectionProperty, EnumProperty, FloatProperty,
                       FloatVectorProperty, IntProperty, IntVectorProperty, PointerProperty,
                       StringProperty)

import abrdf
from abrdf import _abrdf

from . import abrdf_ext_material

# Colour parameters shown with a colour picker (their range is [0, 1]).
COLOURS = ("kd", "ks", "f0")

# Enum items must outlive the properties that use them (Blender keeps the pointers).
_items = {}


def param_ranges():
    """{name: (kind, min, max, help)}: each parameter's widest range over the models, as the
    OSL shaders' min/max metadata (ABRDF_P_*_MIN/MAX of osl/abrdf_meta.h)."""
    out = {}
    for m in abrdf.models():
        for p in m.params:
            kind, lo, hi, help_ = out.get(p.name, (p.kind, p.min, p.max, p.help))
            out[p.name] = (kind, min(lo, p.min), max(hi, p.max), help_)
    return out


def _update(self, context):
    abrdf_ext_material.push(self.id_data)


def _update_mode(self, context):
    abrdf_ext_material.rebuild(self.id_data)


def _param_property(name, kind, lo, hi, help_, default):
    if kind == "rgb":
        return FloatVectorProperty(name=name, description=help_, size=3, min=lo, max=hi,
                                   default=(default,) * 3,
                                   subtype="COLOR" if name in COLOURS else "NONE",
                                   update=_update)
    if kind == "int":
        return IntProperty(name=name, description=help_, min=int(lo), max=int(hi),
                           default=int(default), update=_update)
    return FloatProperty(name=name, description=help_, min=lo, max=hi, default=default,
                         precision=4, update=_update)


def settings_class():
    """The PropertyGroup class, its annotations made from the registry."""
    models = abrdf.models()
    _items["model"] = [(m.name, m.name, "%s (%s)" % (m.title, m.equation)) for m in models]
    _items["model2"] = [("NONE", "none", "no second lobe")] + _items["model"]
    _items["goal"] = [(g, g, "the flowchart's %s branch" % g) for g in abrdf.goals()]
    _items["surface"] = [(s, s, "surface class %s" % s) for s in abrdf.surfaces()]
    _items["preset"] = [("CUSTOM", "This material's parameters",
                         "the surface class, r (or n), colours and anisotropy set here")] + [
        (name, name, m.source) for name, m in abrdf.materials().items()]
    rules = _abrdf.rules()
    defaults = {p["name"]: p["default"] for p in _abrdf.params()}
    ann = {
        "enabled": BoolProperty(name="abrdf material", default=False,
                                description="the material was made by abrdf"),
        "mode": EnumProperty(
            name="Mode", update=_update_mode, items=[
                ("CLOSURE", "Closure", "osl/abrdf_material.osl: the models on Cycles' own "
                 "closures, lit, shadowed and sampled by Cycles"),
                ("EVALUATION", "Evaluation", "osl/abrdf_eval.osl: the exact model under the "
                 "scene's point and sun lights (at most 4), as emission, without shadows")]),
        "model": EnumProperty(name="Model", items=_items["model"], default="lambert",
                              update=_update, description="the first lobe"),
        "model2": EnumProperty(name="Second model", items=_items["model2"],
                               default="disney_specular", update=_update,
                               description="a second lobe, summed with the first (closure mode)"),
        "adaptive": BoolProperty(name="Adaptive in the shader", default=False, update=_update,
                                 description="the shader runs the flowchart itself "
                                 "(osl/abrdf_osl_select.h) from the goal, surface class, r "
                                 "(or n) and anisotropy, per shading point"),
        "goal": EnumProperty(name="Goal", items=_items["goal"], default="photoreal",
                             update=_update),
        "surface": EnumProperty(name="Surface", items=_items["surface"], default="general",
                                update=_update),
        "n_from_r": BoolProperty(name="n from r", default=True, update=_update,
                                 description="derive the exponent n from r; off: n is given"),
        "max_rel_error": FloatProperty(name="Max rel. error %", min=0.0, max=1e30,
                                       default=rules["default_max_rel_pct"], update=_update,
                                       description="performance: max relative error of the "
                                       "Table-1 lobe in the highlight, percent"),
        "max_abs_error": FloatProperty(name="Max abs. error", min=0.0, max=1e30,
                                       default=rules["default_max_abs"], update=_update,
                                       description="performance: max absolute error of the "
                                       "Table-1 lobe"),
        "tangent_rule": EnumProperty(
            name="Tangent rule", default="dPdu", update=_update,
            items=[(r, r, "tangent field for anisotropic and fibre models: %s" % r)
                   for r in ("dPdu", "u", "v", "radial", "axis")]),
        "tangent_axis": FloatVectorProperty(name="Tangent axis", size=3,
                                            default=(1.0, 0.0, 0.0), update=_update,
                                            description="object-space axis of the axis rule"),
        "ambient": FloatVectorProperty(name="Ambient", size=3, subtype="COLOR", min=0.0,
                                       max=1e6, default=(0.0, 0.0, 0.0), update=_update,
                                       description="evaluation mode: the ambient term ka * Ia"),
        "preset": EnumProperty(name="Material", items=_items["preset"],
                               description="what the selection starts from: a material of "
                               "the table (data/materials.csv) or this material's values"),
        "hair_table": StringProperty(
            name="Hair table", default="", update=_update,
            description="evaluation mode, huang: the table image Tabulate hair wrote "
            "(docs/OSL.md, huang from a table); read only while the parameters, sizes and "
            "library are those it was built for"),
        "hair_table_key": StringProperty(name="Hair table built for", default=""),
        "hair_table_sizes": IntVectorProperty(
            name="Table sizes", size=4, min=1, max=256, default=(24, 9, 32, 16),
            update=_update, description="theta nodes, view azimuths (1 for a round fibre), "
            "light azimuths, shift sets; the default takes about a minute of one core"),
        "choice": StringProperty(name="Choice", default=""),
        "trace": StringProperty(name="Trace", default=""),
    }
    for name, (kind, lo, hi, help_) in param_ranges().items():
        ann[name] = _param_property(name, kind, lo, hi, help_, defaults[name])
    return type("AbrdfMaterialSettings", (bpy.types.PropertyGroup,), {"__annotations__": ann})


class AbrdfAdviceResult(bpy.types.PropertyGroup):
    """One material's advice, as the panel shows it (the full trace is in the text)."""

    material: StringProperty(name="Material")
    choice: StringProperty(name="Choice", description="the chosen models; empty: not advised")
    error: StringProperty(name="Predicted error")
    cost: StringProperty(name="Cost")
    notes: StringProperty(name="Notes", description="one note a line: inputs driven by "
                          "nodes, ignored inputs, why the material was not advised")


def advice_class():
    """Scene.abrdf_advice: the advisor's goal or budget and its last results."""
    _items["advice_goal"] = [(g, g, "the flowchart's %s branch" % g) for g in abrdf.goals()]
    _items["budget"] = [(b, b, "predicted image NMSE below %g (Table 8: %s difference)"
                         % (abrdf.budget_nmse(b), "no visible" if b == "none" else b))
                        for b in ("none", "slight", "noticeable")]
    rules = _abrdf.rules()
    ann = {
        "by": EnumProperty(name="Choose by", items=[
            ("GOAL", "Goal", "the paper's flowchart for a goal"),
            ("BUDGET", "Budget", "the cheapest fitted model whose predicted image error is "
             "within a class of the paper's Table 8")]),
        "goal": EnumProperty(name="Goal", items=_items["advice_goal"], default="photoreal"),
        "max_rel_error": FloatProperty(name="Max rel. error %", min=0.0, max=1e30,
                                       default=rules["default_max_rel_pct"],
                                       description="performance: max relative error of the "
                                       "Table-1 lobe in the highlight, percent"),
        "max_abs_error": FloatProperty(name="Max abs. error", min=0.0, max=1e30,
                                       default=rules["default_max_abs"],
                                       description="performance: max absolute error of the "
                                       "Table-1 lobe"),
        "budget": EnumProperty(name="Budget", default="slight", items=_items["budget"]),
        "results": CollectionProperty(type=AbrdfAdviceResult),
    }
    return type("AbrdfAdviceSettings", (bpy.types.PropertyGroup,), {"__annotations__": ann})


_classes = []


def register():
    cls = settings_class()
    bpy.utils.register_class(cls)
    _classes.append(cls)
    bpy.types.Material.abrdf = PointerProperty(type=cls)
    bpy.utils.register_class(AbrdfAdviceResult)
    _classes.append(AbrdfAdviceResult)
    adv = advice_class()
    bpy.utils.register_class(adv)
    _classes.append(adv)
    bpy.types.Scene.abrdf_advice = PointerProperty(type=adv)


def unregister():
    del bpy.types.Scene.abrdf_advice
    del bpy.types.Material.abrdf
    while _classes:
        bpy.utils.unregister_class(_classes.pop())
