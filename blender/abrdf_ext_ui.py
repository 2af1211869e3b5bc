"""The abrdf panel (Material Properties and the Shader Editor's sidebar) and its operators:
a new abrdf material on the active object, Cycles set up for OSL, the selection run and
applied, the scene's lights given to an evaluation-mode material, a model's defaults; and the
advisor of the file's Principled materials (abrdf_ext_advise)."""
import os

import bpy
from bpy.props import EnumProperty

import abrdf

from . import abrdf_ext_advise as advise
from . import abrdf_ext_material as mats


def _cycles_ready(scene):
    c = scene.cycles if scene.render.engine == "CYCLES" else None
    return c is not None and c.device == "CPU" and c.shading_system


def setup_cycles(scene):
    """OSL runs in Cycles on the CPU only."""
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.shading_system = True


class ABRDF_OT_material_add(bpy.types.Operator):
    """Add an abrdf material (a Script node running the OSL port) to the active object"""

    bl_idname = "abrdf.material_add"
    bl_label = "New abrdf material"
    bl_options = {"REGISTER", "UNDO"}

    mode: EnumProperty(name="Mode", items=[
        ("CLOSURE", "Closure", "the models on Cycles' closures (osl/abrdf_material.osl)"),
        ("EVALUATION", "Evaluation", "the exact model under the scene's lights, as emission "
         "(osl/abrdf_eval.osl)")])

    @classmethod
    def poll(cls, context):
        ob = context.object
        return ob is not None and hasattr(ob.data, "materials")

    def execute(self, context):
        ob = context.object
        mat = mats.new_material("abrdf", self.mode)
        if ob.material_slots and ob.active_material_index < len(ob.material_slots):
            ob.material_slots[ob.active_material_index].material = mat
        else:
            ob.data.materials.append(mat)
        if not _cycles_ready(context.scene):
            setup_cycles(context.scene)
            self.report({"INFO"}, "Cycles set to the CPU with Open Shading Language")
        if self.mode == "EVALUATION":
            try:
                mats.sync_lights(mat, context.scene)
            except ValueError as e:
                self.report({"WARNING"}, str(e))
        return {"FINISHED"}


class ABRDF_OT_setup_cycles(bpy.types.Operator):
    """Render with Cycles on the CPU with Open Shading Language (what the shaders need)"""

    bl_idname = "abrdf.setup_cycles"
    bl_label = "Set up Cycles for OSL"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        setup_cycles(context.scene)
        return {"FINISHED"}


def _active_abrdf(context):
    mat = getattr(context, "material", None) or (context.object and context.object.active_material)
    return mat if mat is not None and mat.abrdf.enabled else None


class ABRDF_OT_select(bpy.types.Operator):
    """Run the paper's flowchart for this material and apply its choice (models, parameters)"""

    bl_idname = "abrdf.select"
    bl_label = "Select models"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return _active_abrdf(context) is not None

    def execute(self, context):
        mat = _active_abrdf(context)
        try:
            sel = mats.select(mat)
        except abrdf.Error as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report({"INFO"}, "abrdf: %s" % mat.abrdf.choice)
        if sel.error_rel_pct is not None:
            self.report({"INFO"}, "predicted error: %.3g%% relative, %.3g absolute"
                        % (sel.error_rel_pct, sel.error_abs))
        return {"FINISHED"}


class ABRDF_OT_sync_lights(bpy.types.Operator):
    """Give this evaluation-mode material the scene's point and sun lights (at most 4)"""

    bl_idname = "abrdf.sync_lights"
    bl_label = "Use the scene's lights"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        mat = _active_abrdf(context)
        return mat is not None and mat.abrdf.mode == "EVALUATION"

    def execute(self, context):
        try:
            n = mats.sync_lights(_active_abrdf(context), context.scene)
        except ValueError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report({"INFO"}, "abrdf: %d light%s" % (n, "" if n == 1 else "s"))
        return {"FINISHED"}


class ABRDF_OT_tabulate_hair(bpy.types.Operator):
    """Tabulate this huang material's residual lobes once (about a minute of one core at the
    default sizes, over every core): the evaluation shader then reads them, nearer the
    converged model than the per-call quadrature and far faster (14 times on the hair robot
    in Cycles, docs/OSL.md)"""

    bl_idname = "abrdf.tabulate_hair"
    bl_label = "Tabulate hair"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        mat = _active_abrdf(context)
        return mat is not None and mat.abrdf.mode == "EVALUATION" and mat.abrdf.model == "huang"

    def execute(self, context):
        try:
            path = mats.build_huang_table(_active_abrdf(context))
        except (ValueError, OSError, abrdf.Error) as e:
            self.report({"ERROR"}, "abrdf: %s" % e)
            return {"CANCELLED"}
        self.report({"INFO"}, "abrdf: hair table %s" % path)
        return {"FINISHED"}


class ABRDF_OT_model_defaults(bpy.types.Operator):
    """Set the chosen models' parameters to the library's defaults for those models"""

    bl_idname = "abrdf.model_defaults"
    bl_label = "Model defaults"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return _active_abrdf(context) is not None

    def execute(self, context):
        mats.model_defaults(_active_abrdf(context))
        return {"FINISHED"}


class ABRDF_OT_advise_principled(bpy.types.Operator):
    """Advise every material of the file whose Material Output takes a Principled BSDF: the
    models abrdf chooses for the goal or budget, their predicted error and cost (full trace
    in the text "abrdf advice")"""

    bl_idname = "abrdf.advise_principled"
    bl_label = "Advise Principled materials"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        settings = context.scene.abrdf_advice
        options = advise.select_options(settings)
        try:
            found = advise.advise(bpy.data.materials, options)
        except abrdf.Error as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        text = bpy.data.texts.get(advise.TEXT) or bpy.data.texts.new(advise.TEXT)
        text.from_string(advise.report(found, options, bpy.data.filepath))
        settings.results.clear()
        for a in found:
            r = settings.results.add()
            r.name = r.material = a.name  # name: the collection's key
            r.choice, r.error, r.cost = a.choice, a.error, a.cost
            r.notes = "\n".join(a.notes) if a.selection else a.skipped
        done = sum(1 for a in found if a.selection)
        if not done:
            self.report({"WARNING"}, "abrdf: no material takes a Principled BSDF at its "
                        "Material Output")
            return {"FINISHED"}
        self.report({"INFO"}, "abrdf: %d Principled material%s advised, %d not; the trace is "
                    "in the text \"%s\"" % (done, "" if done == 1 else "s", len(found) - done,
                                             advise.TEXT))
        return {"FINISHED"}


def draw_advice(layout, context):
    """The advisor: goal or budget, the button, one box per material."""
    st = context.scene.abrdf_advice
    layout.prop(st, "by", expand=True)
    if st.by == "BUDGET":
        layout.prop(st, "budget")
    else:
        layout.prop(st, "goal")
        if st.goal == "performance":
            layout.prop(st, "max_rel_error")
            layout.prop(st, "max_abs_error")
    layout.operator("abrdf.advise_principled")
    layout.label(text="Socket values only: texture-driven inputs are advised at their "
                 "socket's own value")
    for r in st.results:
        box = layout.box()
        if not r.choice:
            box.label(text="%s: not advised" % r.material, icon="BLANK1")
            box.label(text=r.notes)
            continue
        box.label(text="%s: %s" % (r.material, r.choice), icon="MATERIAL")
        box.label(text="%s; %s" % (r.error, r.cost or "no cost"))
        for line in r.notes.splitlines():
            box.label(text=line, icon="INFO")
    if st.results:
        layout.label(text="Full trace: the text \"%s\" (Text Editor)" % advise.TEXT)


def _shown_params(s):
    """The parameters the chosen models read, in registry order (all of them when the
    shader chooses by itself)."""
    if s.adaptive and s.mode == "CLOSURE":
        names = ["kd", "ks", "f0", "n", "r", "anisotropic", "melanin", "redness", "eta"]
        return names, False
    names, tangent = [], False
    for m in (s.model, s.model2 if s.mode == "CLOSURE" else "NONE"):
        if m == "NONE":
            continue
        info = abrdf.model(m)
        tangent |= "tangent" in info.needs
        names += [p.name for p in info.params if p.name not in names]
    return names, tangent


def draw(layout, context):
    scene = context.scene
    if not _cycles_ready(scene):
        box = layout.box()
        box.label(text="abrdf materials need Cycles on the CPU with OSL", icon="ERROR")
        box.operator("abrdf.setup_cycles")
    mat = _active_abrdf(context)
    row = layout.row(align=True)
    row.operator("abrdf.material_add", text="New: closure").mode = "CLOSURE"
    row.operator("abrdf.material_add", text="New: evaluation").mode = "EVALUATION"
    if mat is None:
        layout.label(text="The active material is not an abrdf material")
        return
    s = mat.abrdf
    layout.prop(s, "mode")
    col = layout.column()
    if s.mode == "CLOSURE":
        col.prop(s, "adaptive")
    if s.adaptive and s.mode == "CLOSURE":
        for name in ("goal", "surface", "n_from_r", "max_rel_error", "max_abs_error"):
            col.prop(s, name)
    else:
        col.prop(s, "model")
        if s.mode == "CLOSURE":
            col.prop(s, "model2")
    names, tangent = _shown_params(s)
    box = layout.box()
    head = box.row()
    head.label(text="Parameters")
    head.operator("abrdf.model_defaults", text="Defaults")
    for name in names:
        if name.startswith("layer") and name[5:6].isdigit() and int(name[5]) >= s.layer_count:
            continue
        box.prop(s, name)
    if tangent:
        box.prop(s, "tangent_rule")
        if s.tangent_rule == "axis":
            box.prop(s, "tangent_axis")
    if s.mode == "EVALUATION" and s.model == "huang":
        box = layout.box()
        box.label(text="Hair from a table (docs/OSL.md, huang from a table)")
        box.prop(s, "hair_table_sizes")
        box.operator("abrdf.tabulate_hair")
        state = mats.huang_table_state(s)
        if state != "none":
            box.label(text=os.path.basename(s.hair_table))
            box.label(text={"current": "read by the shader",
                            "stale": "built for other parameters: per call until rebuilt",
                            "missing": "the file is missing: per call until rebuilt"}[state],
                      icon="CHECKMARK" if state == "current" else "ERROR")
    if s.mode == "EVALUATION":
        box = layout.box()
        box.label(text="Lighting (point and sun lights, no shadows)")
        box.prop(s, "ambient")
        box.operator("abrdf.sync_lights")
    box = layout.box()
    box.label(text="Selection (Zavalniuk & Romanyuk 2024, Fig. 2)")
    box.prop(s, "preset")
    if s.preset == "CUSTOM":
        box.prop(s, "surface")
    box.prop(s, "goal")
    if s.goal == "performance":
        box.prop(s, "max_rel_error")
        box.prop(s, "max_abs_error")
    box.operator("abrdf.select")
    if s.choice:
        box.label(text=s.choice)
        for line in s.trace.splitlines():
            box.label(text=line)


class MATERIAL_PT_abrdf(bpy.types.Panel):
    bl_label = "abrdf"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "material"

    @classmethod
    def poll(cls, context):
        return context.object is not None

    def draw(self, context):
        draw(self.layout, context)


class NODE_PT_abrdf(bpy.types.Panel):
    bl_label = "abrdf"
    bl_space_type = "NODE_EDITOR"
    bl_region_type = "UI"
    bl_category = "abrdf"

    @classmethod
    def poll(cls, context):
        return context.space_data.tree_type == "ShaderNodeTree" and context.object is not None

    def draw(self, context):
        draw(self.layout, context)


class MATERIAL_PT_abrdf_advice(bpy.types.Panel):
    bl_label = "Advise Principled materials"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "material"
    bl_parent_id = "MATERIAL_PT_abrdf"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        draw_advice(self.layout, context)


class NODE_PT_abrdf_advice(bpy.types.Panel):
    bl_label = "Advise Principled materials"
    bl_space_type = "NODE_EDITOR"
    bl_region_type = "UI"
    bl_category = "abrdf"
    bl_parent_id = "NODE_PT_abrdf"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        draw_advice(self.layout, context)


_classes = (ABRDF_OT_material_add, ABRDF_OT_setup_cycles, ABRDF_OT_select, ABRDF_OT_sync_lights,
            ABRDF_OT_tabulate_hair, ABRDF_OT_model_defaults, ABRDF_OT_advise_principled,
            MATERIAL_PT_abrdf, NODE_PT_abrdf, MATERIAL_PT_abrdf_advice, NODE_PT_abrdf_advice)


def register():
    for c in _classes:
        bpy.utils.register_class(c)


def unregister():
    for c in reversed(_classes):
        bpy.utils.unregister_class(c)
