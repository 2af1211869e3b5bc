"""abrdf materials: a Script node running the OSL port, wired to the Material Output.

The node is compiled from the extension's OSL files (osl/) into the node itself (Blender's
"Internal" script mode keeps the bytecode in the .blend, so a saved file renders without the
extension); its sockets are driven by the material's settings (Material.abrdf,
abrdf_ext_props). Evaluation mode takes the scene's point and sun lights as shader
parameters (sync_lights), with the conventions of `abrdf export --cycles`: a point light of
power P has intensity P / (4 pi), a sun's strength is the irradiance, its direction the
light object's +z axis.
"""
import hashlib
import math
import os
import re
import shutil

import bpy

import abrdf

from .osl import abrdf_cycles

OSL_DIR = os.path.join(os.path.dirname(__file__), "osl")
SHADERS = {"CLOSURE": "abrdf_material.osl", "EVALUATION": "abrdf_eval.osl"}
NODE = "abrdf"
MAX_LIGHTS = 4  # abrdf_eval.osl's light0 ... light3
# What a huang table is built for: a table holds only for them.
HUANG_TABLE_PARAMS = abrdf_cycles.HUANG_TABLE_PARAMS


def _osl():
    """Cycles' OSL helpers (compile, sockets from the compiled shader's parameters)."""
    return abrdf_cycles.cycles_osl()


def _text(path):
    """The text datablock of an OSL file of the extension (one per file, shared)."""
    for t in bpy.data.texts:
        if t.filepath and os.path.normpath(bpy.path.abspath(t.filepath)) == os.path.normpath(path):
            return t
    return bpy.data.texts.load(path, internal=False)


def _compile(node, mode):
    """Compile the mode's shader into `node` (its #includes resolve beside it in osl/)."""
    osl = _osl()
    node.mode = "INTERNAL"
    node.script = _text(os.path.join(OSL_DIR, SHADERS[mode]))
    messages = []
    if not osl.update_script_node(node, lambda kind, msg: messages.append(msg)):
        raise RuntimeError("OSL compilation of %s failed: %s" % (SHADERS[mode], messages))


def new_material(name="abrdf", mode="CLOSURE"):
    """A new material whose Script node runs the mode's shader, wired and set from the
    material's settings (their defaults)."""
    mat = bpy.data.materials.new(name)
    if mat.node_tree is None:
        mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    out.location = (300, 0)
    node = nt.nodes.new("ShaderNodeScript")
    node.name = node.label = NODE
    node.width = 240
    mat.abrdf.enabled = True
    mat.abrdf["mode"] = list(SHADERS).index(mode)  # set without the update: built below
    _compile(node, mode)
    nt.links.new(node.outputs[0], out.inputs["Surface"])
    push(mat)
    return mat


def node_of(mat):
    nt = mat.node_tree if mat else None
    return nt.nodes.get(NODE) if nt else None


def rebuild(mat):
    """Recompile for the current mode (its shader's sockets differ) and push the settings."""
    node = node_of(mat)
    if node is None:
        return
    _compile(node, mat.abrdf.mode)
    nt = mat.node_tree
    out = next((n for n in nt.nodes if n.bl_idname == "ShaderNodeOutputMaterial"), None)
    if out is not None:
        nt.links.new(node.outputs[0], out.inputs["Surface"])
    push(mat)


def huang_table_key(s):
    """What a huang table of settings s is built for, as a string: the parameters, the sizes
    and the library's version (a table holds only for the library that built it)."""
    return repr(tuple(getattr(s, p) for p in HUANG_TABLE_PARAMS) + tuple(s.hair_table_sizes)
                + (abrdf.__version__,))


def tables_dir(blend):
    """Where the tables of the .blend at path `blend` live: abrdf_tables/ beside it."""
    return os.path.join(os.path.dirname(os.path.abspath(blend)), "abrdf_tables")


def huang_table_file(s):
    """The file of the material's table: its path, else the file of its name in
    abrdf_tables/ beside the .blend (a .blend moved with its tables), else None."""
    if not s.hair_table:
        return None
    if os.path.isfile(s.hair_table):
        return s.hair_table
    if bpy.data.filepath:
        moved = os.path.join(tables_dir(bpy.data.filepath), os.path.basename(s.hair_table))
        if os.path.isfile(moved):
            return moved
    return None


def huang_table_state(s):
    """The material's huang table: "none", "current" (read by the evaluation shader),
    "stale" (built for other parameters, sizes or library: the shader integrates per call)
    or "missing" (its file is gone: per call too)."""
    if not s.hair_table:
        return "none"
    if s.hair_table_key != huang_table_key(s):
        return "stale"
    return "current" if huang_table_file(s) else "missing"


def build_huang_table(mat, threads=0):
    """Tabulate the material's huang (abrdf.huang_table at its settings' sizes, rows over
    `threads` threads, 0: every core) and write the table as a PFM image that the evaluation
    shader reads (docs/OSL.md, "huang from a table"): into abrdf_tables/ beside the .blend,
    or Blender's temporary directory for an unsaved file (keep_tables copies it beside the
    file when it is saved). Returns the file's path; ValueError when the model is not huang,
    abrdf.Error for sizes the material refuses, OSError when the directory cannot be made
    (before the build)."""
    s = mat.abrdf
    if s.model != "huang":
        raise ValueError("the model is %s, not huang" % s.model)
    where = (tables_dir(bpy.data.filepath) if bpy.data.filepath
             else os.path.join(bpy.app.tempdir, "abrdf_tables"))
    os.makedirs(where, exist_ok=True)
    sizes = tuple(s.hair_table_sizes)
    brdf = abrdf.BRDF("huang", **{p: getattr(s, p) for p in HUANG_TABLE_PARAMS})
    table = abrdf.huang_table(brdf, sizes, threads)
    key = huang_table_key(s)
    name = "%s_%s_%s.pfm" % (re.sub(r"[^A-Za-z0-9_-]", "_", mat.name)[:40],
                             "x".join(str(n) for n in sizes),
                             hashlib.sha1(key.encode()).hexdigest()[:12])
    path = os.path.join(where, name)
    abrdf_cycles.write_pfm(path, abrdf_cycles.huang_table_image(table.values, sizes))
    s.hair_table_key = key
    s.hair_table = path
    push(mat)
    return path


def _tabled():
    return [m for m in bpy.data.materials
            if getattr(m, "abrdf", None) is not None and m.abrdf.enabled and m.abrdf.hair_table]


@bpy.app.handlers.persistent
def keep_tables(*args):
    """Before a .blend is saved: every table not yet in abrdf_tables/ beside the file it is
    saved as (built before the first save, in Blender's temporary directory, or saved as
    another file) is copied there, and the material points at the copy."""
    blend = args[0] if args and isinstance(args[0], str) and args[0] else bpy.data.filepath
    if not blend:
        return
    where = tables_dir(blend)
    for mat in _tabled():
        src = huang_table_file(mat.abrdf)
        if not src or os.path.dirname(os.path.abspath(src)) == where:
            if src and src != mat.abrdf.hair_table:
                mat.abrdf.hair_table = src
            continue
        os.makedirs(where, exist_ok=True)
        dst = os.path.join(where, os.path.basename(src))
        shutil.copyfile(src, dst + ".part")
        os.replace(dst + ".part", dst)
        mat.abrdf.hair_table = dst


@bpy.app.handlers.persistent
def refresh_tables(*_):
    """After a .blend loads: every abrdf material with a hair table pushes its settings
    again, so that the shader reads the table where it is now (abrdf_tables/ beside a moved
    .blend), or integrates per call when its file is gone, instead of reading nothing."""
    for mat in _tabled():
        push(mat)


def socket_values(s):
    """The shader's inputs from the settings s, by socket identifier (the OSL names)."""
    current = s.model == "huang" and huang_table_state(s) == "current"
    v = {"huang_table": huang_table_file(s) if current else "",
         "huang_table_nt": s.hair_table_sizes[0], "huang_table_nv": s.hair_table_sizes[1],
         "huang_table_np": s.hair_table_sizes[2],
         "model": s.model, "model2": "" if s.model2 == "NONE" else s.model2,
         "adaptive": s.adaptive, "goal": s.goal, "surface": s.surface, "n_from_r": s.n_from_r,
         "max_rel_error": s.max_rel_error, "max_abs_error": s.max_abs_error,
         "tangent_rule": s.tangent_rule, "tangent_axis": tuple(s.tangent_axis),
         # Evaluation mode: the ambient term ka * Ia is given as ka, with Ia = 1.
         "ka": tuple(s.ambient), "ambient": (1.0, 1.0, 1.0)}
    for p in abrdf._abrdf.params():
        value = getattr(s, p["name"])
        v[p["name"]] = tuple(value) if p["kind"] == "rgb" else value
    return v


def _set(sock, value):
    if sock.bl_idname.startswith("NodeSocketColor"):
        value = tuple(value) + (1.0,)
    elif sock.bl_idname.startswith("NodeSocketInt"):
        value = int(value)
    elif sock.bl_idname.startswith("NodeSocketBool"):
        value = bool(value)
    sock.default_value = value


def push(mat):
    """Write the settings into the Script node's sockets."""
    node = node_of(mat)
    if node is None or not mat.abrdf.enabled:
        return
    values = socket_values(mat.abrdf)
    for sock in node.inputs:
        if sock.identifier in values and not sock.is_linked:
            _set(sock, values[sock.identifier])


def scene_lights(scene):
    """The scene's lights as evaluation-mode parameters: [(type, position, colour,
    intensity)], type 1 point (position), 2 directional (direction toward the light).
    ValueError for more than MAX_LIGHTS lights or a kind the shader does not have."""
    lights = sorted((o for o in scene.objects if o.type == "LIGHT" and not o.hide_render),
                    key=lambda o: o.name)
    if len(lights) > MAX_LIGHTS:
        raise ValueError("evaluation mode takes at most %d lights; the scene has %d"
                         % (MAX_LIGHTS, len(lights)))
    out = []
    for o in lights:
        d = o.data
        if d.type == "POINT":
            out.append((1, tuple(o.matrix_world.translation), tuple(d.color),
                        d.energy / (4.0 * math.pi)))
        elif d.type == "SUN":
            z = o.matrix_world.to_3x3().col[2].normalized()
            out.append((2, tuple(z), tuple(d.color), d.energy))
        else:
            raise ValueError("light %s: a %s light; evaluation mode has point and sun lights"
                             % (o.name, d.type.lower()))
    return out


def sync_lights(mat, scene):
    """Give the evaluation shader of `mat` the scene's lights; returns how many."""
    node = node_of(mat)
    if node is None or mat.abrdf.mode != "EVALUATION":
        return 0
    lights = scene_lights(scene)
    sockets = {s.identifier: s for s in node.inputs}
    for k in range(MAX_LIGHTS):
        kind, pos, col, inten = lights[k] if k < len(lights) else (0, (0, 0, 0), (1, 1, 1), 0)
        _set(sockets["light%d_type" % k], kind)
        _set(sockets["light%d_position" % k], pos)
        _set(sockets["light%d_color" % k], col)
        _set(sockets["light%d_intensity" % k], inten)
    return len(lights)


def selection_input(s):
    """What the flowchart starts from: the table's material, or the settings' values (as the
    shader's adaptive mode reads them: n only when n_from_r is off)."""
    if s.preset != "CUSTOM":
        return s.preset
    layers = tuple(abrdf.Layer(eta=getattr(s, "layer%d_eta" % k),
                               kappa=getattr(s, "layer%d_kappa" % k),
                               r=getattr(s, "layer%d_r" % k),
                               sigma_a=tuple(getattr(s, "layer%d_sigma_a" % k)),
                               depth=getattr(s, "layer%d_depth" % k))
                   for k in range(s.layer_count))
    return abrdf.Material(type=s.surface, n=None if s.n_from_r else s.n, r=s.r,
                          kd=tuple(s.kd), ks=tuple(s.ks), f0=tuple(s.f0),
                          anisotropy=s.anisotropic, melanin=s.melanin, redness=s.redness,
                          layers=layers)


def select(mat):
    """Run the flowchart for the material's settings and apply its choice: the models, their
    parameters, the trace. Returns the abrdf.Selection (abrdf.Error if the input is invalid)."""
    s = mat.abrdf
    sel = abrdf.select(selection_input(s), goal=s.goal, max_rel_error=s.max_rel_error,
                       max_abs_error=s.max_abs_error)
    s.adaptive = False
    s.model = sel.diffuse or sel.specular
    s.model2 = sel.specular if sel.diffuse else "NONE"
    if sel.material.name:
        s.surface = sel.type
    for brdf in (sel.diffuse_brdf, sel.specular_brdf):
        for k, v in (brdf.params.items() if brdf else ()):
            setattr(s, k, v)
    s.choice = "%s: %s%s" % (sel.goal, sel.diffuse + " + " if sel.diffuse else "", sel.specular)
    s.trace = sel.explain()
    return sel


def model_defaults(mat):
    """The chosen models' parameters to their registry defaults (the first model's, then the
    second's for the parameters only it reads)."""
    s = mat.abrdf
    seen = set()
    for name in (s.model, s.model2):
        if name == "NONE":
            continue
        for p in abrdf.model(name).params:
            if p.name not in seen:
                seen.add(p.name)
                setattr(s, p.name, (p.default,) * 3 if p.kind == "rgb" else
                        int(p.default) if p.kind == "int" else p.default)
