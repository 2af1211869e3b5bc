"""abrdf_cycles.py - builds and renders an abrdf scene in Blender's Cycles (bpy), for the
scripts that `abrdf export --cycles` writes (they hold the scene as data and call main()).

Two modes:
  eval     evaluation mode: every surface runs the scene's generated OSL shader, which
           re-traces the pixel-centre camera ray and the shadow rays against the exact
           analytic primitives (abrdf_trace.h) and returns the built-in renderer's direct
           lighting as emission (abrdf_osl.h models). Analytic primitives get no host
           geometry: a backdrop sphere makes every pixel run the shader. Triangle meshes
           (`mesh` objects) are Cycles geometry with the scene's corner normals: on a mesh the
           shader takes Cycles' point and interpolated normal, so a scene with meshes renders
           one sample per pixel (Cycles' first sample lies at the pixel centre), and meshes
           cast shadows through OSL's trace(). The image matches `abrdf render --spp 1`.
  generic  abrdf_eval.osl, the host-independent evaluation shader, on the meshes with the
           scene's lights as parameters (one lobe per material, at most four lights, no
           shadows); exact where the mesh is (boxes), approximate on curved shapes.
  closure  closure mode: meshes with abrdf_material.osl (the models mapped onto Cycles'
           built-in closures), Cycles point/sun lights, path tracing with direct light only.

Cycles settings of both: CPU, OSL shading system, Standard view transform, box pixel filter
1 px wide, fixed sample count (no adaptive sampling, no denoising), linear 32-bit EXR.

Runs in any Python that imports bpy (the PyPI `bpy` package) or inside Blender
(blender -b -P scene.py -- ARGS).
"""
import argparse
import base64
import glob
import math
import os
import shutil
import sys
import tempfile

import numpy as np

import bpy  # first: bmesh and mathutils come with it
import bmesh
import mathutils

HEADERS = ("abrdf_osl.h", "abrdf_osl_guards.h", "abrdf_osl_kernels.h", "abrdf_meta.h", "abrdf_fkub.h", "abrdf_belcour_tables.h", "abrdf_hair.h",
           "abrdf_hair_tables.h", "abrdf_osl_select.h", "abrdf_trace.h")
SHAPES = {"sphere": 0, "cylinder": 1, "capsule": 2, "box": 3}


def cycles_osl():
    """Blender's OSL helpers (compile + node sockets); oslquery lives in bpy's own Python."""
    base = os.path.dirname(bpy.__file__)
    for pat in ("*/python/lib/python3*/site-packages", "../*/python/lib/python3*/site-packages"):
        for d in glob.glob(os.path.join(base, pat)) + glob.glob(
                os.path.join(bpy.utils.resource_path("LOCAL"), "python", "lib", "python3*",
                             "site-packages")):
            if os.path.isdir(os.path.join(d, "oslquery")) and d not in sys.path:
                sys.path.append(d)
    import cycles.osl  # noqa: E402  (the Cycles add-on shipped with bpy)
    return cycles.osl


def compile_script_node(node, path):
    osl = cycles_osl()  # before the node is touched: its update callback needs oslquery
    node.mode = "EXTERNAL"
    node.filepath = path
    msgs = []
    ok = osl.update_script_node(node, lambda kind, msg: msgs.append((kind, msg)))
    if not ok:
        raise RuntimeError("OSL compilation of %s failed: %s" % (path, msgs))
    return node


def new_material(name):
    mat = bpy.data.materials.new(name)
    if mat.node_tree is None:
        mat.use_nodes = True
    mat.node_tree.nodes.clear()
    return mat


def shader_material(name, osl_path, inputs=None):
    mat = new_material(name)
    nt = mat.node_tree
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    node = compile_script_node(nt.nodes.new("ShaderNodeScript"), osl_path)
    for key, value in (inputs or {}).items():
        sock = node.inputs[key]
        if sock.bl_idname == "NodeSocketColor":
            value = tuple(value) + (1.0,)
        sock.default_value = value
    nt.links.new(node.outputs["result"], out.inputs["Surface"])
    return mat


def eval_material(osl_path):
    """The generated scene shader, told which mesh object a surface is by the object's
    custom property abrdf_object (index + 1; absent on the backdrop: 0)."""
    mat = shader_material("abrdf_eval", osl_path)
    nt = mat.node_tree
    script = next(n for n in nt.nodes if n.bl_idname == "ShaderNodeScript")
    attr = nt.nodes.new("ShaderNodeAttribute")
    attr.attribute_type = "OBJECT"
    attr.attribute_name = "abrdf_object"
    nt.links.new(attr.outputs["Fac"], script.inputs["mesh_id"])
    return mat


def mesh_for(o, segments):
    """Mesh of an analytic primitive in object space (the scene format's axes: y up)."""
    bm = bmesh.new()
    shape = o["shape"]
    if shape == "box":
        bmesh.ops.create_cube(bm, size=1.0)
        bmesh.ops.scale(bm, vec=o["size"], verts=bm.verts)
    elif shape == "sphere":
        bmesh.ops.create_uvsphere(bm, u_segments=2 * segments, v_segments=segments,
                                  radius=o["radius"])
    elif shape == "capsule":
        # A UV sphere with an odd ring count has no equator ring: moving each half by
        # +-height/2 opens it into the tube.
        bmesh.ops.create_uvsphere(bm, u_segments=2 * segments, v_segments=segments | 1,
                                  radius=o["radius"])
        for v in bm.verts:
            v.co.z += math.copysign(0.5 * o["height"], v.co.z)
    else:  # cylinder
        bmesh.ops.create_cone(bm, cap_ends=True, segments=2 * segments, radius1=o["radius"],
                              radius2=o["radius"], depth=o["height"])
    if shape in ("sphere", "capsule", "cylinder"):  # their axis is z in bmesh; the format's is y
        bmesh.ops.rotate(bm, verts=bm.verts, matrix=mathutils.Matrix.Rotation(-math.pi / 2, 3, "X"))
    me = bpy.data.meshes.new(shape)
    bm.to_mesh(me)
    bm.free()
    if shape != "box":
        me.shade_smooth()
    return me


# What a huang table depends on of a material's entry, in the order its "params" lists them.
HUANG_TABLE_PARAMS = ("eta", "melanin", "redness", "cuticle_tilt", "aspect_ratio", "r",
                      "entry_grid", "internal_grid")


def huang_table_image(values, sizes):
    """A huang table's texture (osl/abrdf_hair.h, abrdf_huang_tabulated): the library's values
    after its header of 8 as float32 RGB, nt np texels wide and nt nv high, the first row at
    the top."""
    nt, nv, np_ = sizes[:3]
    return np.asarray(values[8:], dtype="<f4").reshape(nt * nv, nt * np_, 3)


def write_pfm(path, rgb):
    """rgb (height, width, 3; the first row at the top) as a PFM image at path, whole or not
    at all: a float image Cycles' OSL texture() reads texel for texel."""
    h, w = rgb.shape[:2]
    tmp = path + ".part"
    try:
        with open(tmp, "wb") as f:
            # PFM: negative scale for little-endian, rows from the bottom up
            f.write(b"PF\n%d %d\n-1.0\n" % (w, h))
            f.write(np.ascontiguousarray(np.asarray(rgb, dtype="<f4")[::-1]).tobytes())
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def write_huang_tables(s, workdir):
    """The eval shader's text with its huang tables in place: each tabulated material's table
    (SCENE["materials"][m]["huang_table"], float32 RGB, the first row at the top) written as
    workdir/abrdf_huang_<m>.pfm, a float image Cycles' OSL texture() reads texel for texel,
    and the shader's @ABRDF_TABLES@ turned into workdir (docs/OSL.md, "huang from a table").
    A material whose parameters differ from those its table was built for is refused."""
    for m in s["materials"]:  # every one checked before any file is written
        t = m.get("huang_table")
        if t and [m[p] for p in HUANG_TABLE_PARAMS] != list(t["params"]):
            raise SystemExit("abrdf_cycles: material '%s': its huang table was built for %s, "
                             "not %s; export the scene again" % (
                                 m["name"], t["params"], [m[p] for p in HUANG_TABLE_PARAMS]))
    for k, m in enumerate(s["materials"]):
        t = m.get("huang_table")
        if not t:
            continue
        v = np.frombuffer(base64.b64decode(t["data"]), dtype="<f4")
        write_pfm(os.path.join(workdir, "abrdf_huang_%d.pfm" % k),
                  v.reshape(t["height"], t["width"], 3))
    where = os.path.abspath(workdir).replace("\\", "\\\\").replace('"', '\\"')
    return s["osl"].replace("@ABRDF_TABLES@", where)


def mesh_from_data(m, smooth, name="mesh"):
    """A `mesh` object's triangles (SCENE["meshes"] entry, object space) with the scene's
    corner normals. Blender 4.5+ keeps them exactly as a float custom_normal attribute on
    the face corners ("free" normals); older versions encode custom normals in 16 bits per
    angle (normals_split_custom_set), which moves them by up to about 6e-5."""
    pos = np.frombuffer(base64.b64decode(m["positions"]), dtype="<f4").astype(np.float32)
    tri = np.frombuffer(base64.b64decode(m["tri"]), dtype="<i4").astype(np.int32)
    nv, nt = len(pos) // 3, len(tri) // 3
    me = bpy.data.meshes.new(name)
    me.vertices.add(nv)
    me.vertices.foreach_set("co", pos)
    me.loops.add(3 * nt)
    me.loops.foreach_set("vertex_index", tri)
    me.polygons.add(nt)
    me.polygons.foreach_set("loop_start", np.arange(0, 3 * nt, 3, dtype=np.int32))
    me.update(calc_edges=True)
    if not smooth:
        me.shade_flat()
        return me
    me.shade_smooth()
    nrm = np.frombuffer(base64.b64decode(m["normals"]), dtype="<f4").reshape(-1, 3)
    corner = nrm[np.frombuffer(base64.b64decode(m["tri_normal"]), dtype="<i4")]
    corner = np.ascontiguousarray(corner, dtype=np.float32)
    try:
        if "custom_normal" in me.attributes:
            me.attributes.remove(me.attributes["custom_normal"])
        attr = me.attributes.new("custom_normal", "FLOAT_VECTOR", "CORNER")
        attr.data.foreach_set("vector", corner.ravel())
        me.update()
        if me.has_custom_normals:
            return me
        me.attributes.remove(me.attributes["custom_normal"])
    except (RuntimeError, TypeError, AttributeError):
        pass
    me.normals_split_custom_set([tuple(v) for v in corner.astype(np.float64)])
    return me


def add_object(name, me, o=None):
    ob = bpy.data.objects.new(name, me)
    if o:
        ob.scale = o["scale"]
        ob.rotation_mode = "XYZ"  # R = Rz Ry Rx, the scene format's order
        ob.rotation_euler = [math.radians(a) for a in o["rotate"]]
        ob.location = o["translate"]
    bpy.context.scene.collection.objects.link(ob)
    return ob


def setup_render(sc, s, samples):
    sc.render.engine = "CYCLES"
    sc.cycles.device = "CPU"
    sc.cycles.shading_system = True
    sc.cycles.samples = samples
    sc.cycles.use_adaptive_sampling = False
    sc.cycles.use_denoising = False
    sc.cycles.seed = 0
    sc.cycles.pixel_filter_type = "BOX"
    sc.cycles.filter_width = 1.0
    sc.render.resolution_x = s["width"]
    sc.render.resolution_y = s["height"]
    sc.render.resolution_percentage = 100
    sc.render.pixel_aspect_x = sc.render.pixel_aspect_y = 1.0
    sc.render.film_transparent = False
    sc.view_settings.view_transform = "Standard"
    sc.view_settings.look = "None"
    sc.view_settings.exposure = 0.0
    sc.view_settings.gamma = 1.0
    st = sc.render.image_settings
    st.file_format = "OPEN_EXR"
    st.color_mode = "RGB"
    st.color_depth = "32"
    world = bpy.data.worlds.new("black")
    world.color = (0.0, 0.0, 0.0)
    if world.node_tree is not None:  # a new world's Background node is 0.05 grey: no light
        for node in world.node_tree.nodes:
            if node.type == "BACKGROUND":
                node.inputs["Strength"].default_value = 0.0
    sc.world = world


def setup_camera(sc, s):
    c = s["camera"]
    eye = mathutils.Vector(c["position"])
    fwd = (mathutils.Vector(c["look_at"]) - eye).normalized()
    right = fwd.cross(mathutils.Vector(c["up"])).normalized()
    up = right.cross(fwd)
    rot = mathutils.Matrix((right, up, -fwd)).transposed()  # columns: camera x, y, -view
    cam = bpy.data.cameras.new("camera")
    cam.type = "PERSP"
    cam.sensor_fit = "VERTICAL"  # fov is the full vertical angle, as in the scene format
    cam.angle_y = math.radians(c["fov_deg"])
    cam.shift_x = cam.shift_y = 0.0
    cam.clip_start = 1e-4 * s["extent"]
    cam.clip_end = 1e3 * s["extent"]
    ob = bpy.data.objects.new("camera", cam)
    ob.matrix_world = mathutils.Matrix.Translation(eye) @ rot.to_4x4()
    sc.collection.objects.link(ob)
    sc.camera = ob


def setup_environment(sc, l):
    """abrdf's environment light as Cycles' world, radiance map * color * intensity. abrdf's
    lat-long mapping (tools/render/envmap.h): a direction d has theta from +y, column
    0.5 + atan2(d.x, -d.z) / 2pi, nearest pixel. Cycles' equirectangular lookup of a direction
    e has column 0.5 - atan2(e.y, e.x) / 2pi and the elevation above +z, so the world looks
    up e = (-d.z, -d.x, d.y), a rotation of d. Camera rays do not see it, as in abrdf."""
    w = sc.world
    w.use_nodes = True
    nt = w.node_tree
    nt.nodes.clear()
    node = nt.nodes.new
    coord, sep, comb = (node("ShaderNodeTexCoord"), node("ShaderNodeSeparateXYZ"),
                        node("ShaderNodeCombineXYZ"))
    neg = []
    for _ in range(2):
        m = node("ShaderNodeMath")
        m.operation = "MULTIPLY"
        m.inputs[1].default_value = -1.0
        neg.append(m)
    tex = node("ShaderNodeTexEnvironment")
    tex.image = bpy.data.images.load(l["file"])
    tex.image.colorspace_settings.name = "Non-Color"  # the file's values, as abrdf reads them
    tex.interpolation = "Closest"
    tex.projection = "EQUIRECTANGULAR"
    tint = node("ShaderNodeVectorMath")
    tint.operation = "MULTIPLY"
    tint.inputs[1].default_value = l["color"]
    bg, out = node("ShaderNodeBackground"), node("ShaderNodeOutputWorld")
    bg.inputs["Strength"].default_value = l["intensity"]
    link = nt.links.new
    link(coord.outputs["Generated"], sep.inputs[0])
    link(sep.outputs["Z"], neg[0].inputs[0])
    link(neg[0].outputs[0], comb.inputs["X"])
    link(sep.outputs["X"], neg[1].inputs[0])
    link(neg[1].outputs[0], comb.inputs["Y"])
    link(sep.outputs["Y"], comb.inputs["Z"])
    link(comb.outputs[0], tex.inputs["Vector"])
    link(tex.outputs["Color"], tint.inputs[0])
    link(tint.outputs[0], bg.inputs["Color"])
    link(bg.outputs[0], out.inputs["Surface"])
    w.cycles_visibility.camera = False


def setup_lights(sc, s):
    """Cycles lights for closure mode: E = color * intensity (/ d^2 for point lights); sphere
    and rect lights of radiance L = color * intensity; the environment as the world."""
    for k, l in enumerate(s["lights"]):
        if l["kind"] == "environment":
            setup_environment(sc, l)
            continue
        if l["kind"] == "sphere":
            # Cycles' sphere light (a point light with a radius, soft falloff off) of power P
            # has radiance P / (4 pi * pi r^2): P = 4 pi^2 r^2 L.
            r = l["radius"]
            ld = bpy.data.lights.new("light%d" % k, "POINT")
            ld.energy = 4.0 * math.pi ** 2 * r * r * l["intensity"]
            ld.shadow_soft_size = r
            if hasattr(ld, "use_soft_falloff"):
                ld.use_soft_falloff = False
            ob = bpy.data.objects.new(ld.name, ld)
            ob.location = l["position"]
        elif l["kind"] == "rect":
            # Cycles' area light emits along its local -z, its sides along x (size) and y
            # (size_y); a one-sided Lambertian emitter of power P and area A has radiance
            # P / (pi A): P = pi A L.
            u, v = mathutils.Vector(l["u"]), mathutils.Vector(l["v"])
            ld = bpy.data.lights.new("light%d" % k, "AREA")
            ld.shape = "RECTANGLE"
            ld.size, ld.size_y = u.length, v.length
            ld.energy = math.pi * u.length * v.length * l["intensity"]
            if hasattr(ld, "spread"):
                ld.spread = math.pi
            ob = bpy.data.objects.new(ld.name, ld)
            x, y = u.normalized(), -v.normalized()  # x cross y = -(u x v): -z along u x v
            rot = mathutils.Matrix((x, y, x.cross(y))).transposed()
            ob.matrix_world = mathutils.Matrix.Translation(l["position"]) @ rot.to_4x4()
        elif l["kind"] == "point":
            ld = bpy.data.lights.new("light%d" % k, "POINT")
            # Cycles' point light of power P has radiant intensity P / (4 pi) W/sr, so
            # irradiance P / (4 pi d^2): P = 4 pi * intensity gives the scene's E.
            ld.energy = 4.0 * math.pi * l["intensity"]
            ld.shadow_soft_size = 0.0
            if hasattr(ld, "use_soft_falloff"):
                ld.use_soft_falloff = False
            ob = bpy.data.objects.new(ld.name, ld)
            ob.location = l["position"]
        else:
            ld = bpy.data.lights.new("light%d" % k, "SUN")
            ld.energy = l["intensity"]  # sun strength is irradiance, W/m^2
            ld.angle = 0.0
            ob = bpy.data.objects.new(ld.name, ld)
            # A sun shines along its -z axis; point -z away from the light direction.
            ob.rotation_euler = mathutils.Vector(l["direction"]).to_track_quat("Z", "Y").to_euler()
        ld.color = l["color"]
        if l["kind"] in ("sphere", "rect") and hasattr(ob, "visible_camera"):
            ob.visible_camera = False  # abrdf's lights light surfaces; the camera never sees them
        sc.collection.objects.link(ob)


def material_inputs(m):
    lobes = m["lobes"] + [""] * (2 - len(m["lobes"]))
    d = {"model": lobes[0], "model2": lobes[1], "kd": m["kd"], "ks": m["ks"], "f0": m["f0"],
         "n": m["n"], "r": m["r"], "anisotropic": m["anisotropic"], "sigma": m["sigma"],
         "clearcoat_gloss": m["clearcoat_gloss"], "k_amp": m["k_amp"], "eta": m["eta"],
         "melanin": m["melanin"], "redness": m["redness"], "cuticle_tilt": m["cuticle_tilt"],
         "aspect_ratio": m["aspect_ratio"], "layer_count": m["layer_count"]}
    for k, ly in enumerate(m["layers"]):
        for field in ("eta", "kappa", "r", "sigma_a", "depth"):
            d["layer%d_%s" % (k, field)] = ly[field]
    return d


def eval_inputs(s, m, table=None):
    """abrdf_eval.osl's inputs: one lobe, the scene's first four lights, the ambient term, and
    the path of the material's huang table when it has one."""
    if len(m["lobes"]) != 1 or len(s["lights"]) > 4:
        raise ValueError("generic mode: one lobe per material and at most 4 lights")
    d = material_inputs(m)
    del d["model2"]
    d["entry_grid"], d["internal_grid"] = m["entry_grid"], m["internal_grid"]
    if table:
        d["huang_table"] = table
        sizes = m["huang_table"]["sizes"]
        d["huang_table_nt"], d["huang_table_nv"], d["huang_table_np"] = sizes[:3]
    d["ka"] = m["ambient"]
    d["ambient"] = (1.0, 1.0, 1.0)  # ka * Ia is already in "ambient" of the material
    for k, l in enumerate(s["lights"]):
        d["light%d_type" % k] = 1 if l["kind"] == "point" else 2
        d["light%d_position" % k] = l["position"] if l["kind"] == "point" else l["direction"]
        d["light%d_color" % k] = l["color"]
        d["light%d_intensity" % k] = l["intensity"]
    for k in range(len(s["lights"]), 4):
        d["light%d_type" % k] = 0
    return d


def build(s, mode, workdir, osl_dir, segments=64):
    """Build the scene in an empty file; return the scene datablock."""
    if '"' in os.path.abspath(workdir):
        raise SystemExit("abrdf_cycles: work directory %r: its path has a double quote, and the "
                         "shaders compiled there would not load" % workdir)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    setup_render(sc, s, s["samples"])
    setup_camera(sc, s)
    os.makedirs(workdir, exist_ok=True)
    # The host compiles next to the .osl file and resolves #include there: work on copies.
    for h in HEADERS + (("abrdf_material.osl",) if mode == "closure" else ()):
        shutil.copy2(os.path.join(osl_dir, h), os.path.join(workdir, h))
    mats = []
    area = [l["kind"] for l in s["lights"] if l["kind"] not in ("point", "directional")]
    if area and mode != "closure":
        raise SystemExit("abrdf_cycles: %s lights need --mode closure (Cycles' own lights)"
                         % ", ".join(sorted(set(area))))
    if mode == "eval":
        path = os.path.join(workdir, s["osl_name"] + ".osl")
        with open(path, "w") as f:
            f.write(write_huang_tables(s, workdir))
        mats = [eval_material(path)]
        sc.cycles.max_bounces = 0  # emission seen by the camera only
    elif mode == "generic":
        path = os.path.join(workdir, "abrdf_eval.osl")
        shutil.copy2(os.path.join(osl_dir, "abrdf_eval.osl"), path)
        write_huang_tables(s, workdir)
        sc.cycles.max_bounces = 0
    else:
        path = os.path.join(workdir, "abrdf_material.osl")
        setup_lights(sc, s)
        for key in ("diffuse", "glossy", "transmission", "volume", "transparent_max"):
            setattr(sc.cycles, key + "_bounces", 0)
        sc.cycles.light_sampling_threshold = 0.0  # no light is skipped as too dim
        sc.cycles.max_bounces = 0  # direct light only, as the built-in renderer
    # generic/closure: one Blender material per (scene material, tangent field), since the
    # tangent rule belongs to the object and the shader reads it as a parameter.
    variants = {}
    has_mesh = any(o["shape"] == "mesh" for o in s["objects"])
    if mode == "eval" and has_mesh:
        # On a mesh the shader shades Cycles' own sample point, and only a pixel's first
        # sample lies at its centre (measured: the same image with box filters 1 and 0.01
        # pixel wide; from the second sample on, samples spread over the pixel whatever the
        # filter width): one sample per pixel, the built-in renderer's --spp 1.
        sc.cycles.samples = 1
    for k, o in enumerate(s["objects"]):
        if o["shape"] == "mesh":
            me = mesh_from_data(s["meshes"][o["mesh"]], o["smooth"], "mesh%d" % k)
        elif mode == "eval":
            continue  # re-traced exactly by the shader; the backdrop runs it
        else:
            me = mesh_for(o, segments)
        if mode == "eval":
            mat = mats[0]
        else:
            key = (o["material"], o.get("tangent", "u"), tuple(o.get("tangent_axis", (1, 0, 0))))
            if key not in variants:
                m = s["materials"][o["material"]]
                table = os.path.join(os.path.abspath(workdir), "abrdf_huang_%d.pfm" % o["material"])
                inputs = (eval_inputs(s, m, table if m.get("huang_table") else None)
                          if mode == "generic" else material_inputs(m))
                inputs["tangent_rule"], inputs["tangent_axis"] = key[1], key[2]
                variants[key] = shader_material("%s.%d" % (m["name"], len(variants)), path, inputs)
            mat = variants[key]
        me.materials.append(mat)
        ob = add_object("%s%d" % (o["shape"], k), me, o)
        if o["shape"] == "mesh":
            ob["abrdf_object"] = k + 1  # read by eval_material's attribute node
    if mode == "eval":
        # Backdrop: an inward-facing sphere around everything, so every pixel runs the
        # shader (a pixel whose centre hits an object may have samples that miss it).
        bm = bmesh.new()
        bmesh.ops.create_uvsphere(bm, u_segments=16, v_segments=8, radius=1e2 * s["extent"])
        bmesh.ops.reverse_faces(bm, faces=bm.faces)
        me = bpy.data.meshes.new("backdrop")
        bm.to_mesh(me)
        bm.free()
        me.materials.append(mats[0])
        ob = add_object("abrdf_backdrop", me)
        ob.location = s["camera"]["position"]
    return sc


def render(sc, out):
    sc.render.filepath = os.path.abspath(out)
    bpy.ops.render.render(write_still=True)


def main(s, argv=None):
    if argv is None:
        argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    ap = argparse.ArgumentParser(description="Render the abrdf scene %s in Cycles" % s["source"])
    ap.add_argument("-o", "--out", default=s["osl_name"] + ".exr", help="linear EXR to write")
    ap.add_argument("--mode", choices=("eval", "closure", "generic"), default=s["mode"])
    ap.add_argument("--samples", type=int, default=s["samples"])
    ap.add_argument("--workdir", default=None,
                    help="where the OSL files are copied and compiled; default: a temporary directory")
    ap.add_argument("--osl-dir", default=s["osl_dir"], help="abrdf's osl/ directory")
    ap.add_argument("--threads", type=int, default=0, help="0: Cycles' default")
    ap.add_argument("--build-only", action="store_true", help="build the scene, do not render")
    a = ap.parse_args(argv)
    s = dict(s, samples=a.samples)
    # A built-only scene keeps its compiled shaders (Cycles reads them at render time).
    tmp = None if a.workdir or a.build_only else tempfile.TemporaryDirectory(prefix="abrdf_cycles_")
    workdir = a.workdir or (tmp.name if tmp else tempfile.mkdtemp(prefix="abrdf_cycles_"))
    sc = build(s, a.mode, workdir, a.osl_dir)
    if a.threads > 0:
        sc.render.threads_mode = "FIXED"
        sc.render.threads = a.threads
    if not a.build_only:
        render(sc, a.out)
    if tmp:
        tmp.cleanup()
    return sc
