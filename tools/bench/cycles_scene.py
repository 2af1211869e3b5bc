"""cycles_scene.py - render a scene file (docs/RENDERER.md, "Scene format") with Blender Cycles
through bpy, for the renderer speed comparison of docs/BENCHMARKS.md (tools/bench/renderers.sh).

    python cycles_scene.py SCENE [--samples 1] [--threads 2] [--reps 3] [--out OUT.png]

Builds the same camera, directional/point lights and analytic primitives (capsules as a
cylinder and two spheres) with Cycles' own Principled BSDF (base colour kd, roughness r,
specular IOR level from F0), CPU device, direct light only (no bounces), no denoising, no
adaptive sampling. Prints one line per repetition, "cycles_render_seconds S", the wall time
of bpy.ops.render.render (scene sync, BVH build and path tracing), after one untimed render.
"""
import argparse
import math
import sys
import time

import bpy
from mathutils import Matrix, Vector


def parse_scene(path):
    cam, lights, mats, objs = {}, [], {}, []
    for raw in open(path):
        line = raw.split("#", 1)[0].split()
        if not line:
            continue
        kw = dict(t.split("=", 1) for t in line[1:] if "=" in t)
        vec = lambda k, d=None: [float(x) for x in kw[k].split(",")] if k in kw else d
        if line[0] == "camera":
            cam = {"pos": vec("position"), "at": vec("look_at"), "up": vec("up", [0, 1, 0]),
                   "fov": float(kw.get("fov", 40)), "res": [int(x) for x in kw["resolution"].split(",")]}
        elif line[0] == "light":
            lights.append({"kind": line[1], "dir": vec("direction"), "pos": vec("position"),
                           "color": vec("color", [1, 1, 1]), "intensity": float(kw.get("intensity", 1))})
        elif line[0] == "material":
            mats[line[1]] = {"kd": vec("kd", [0.5] * 3), "r": float(kw.get("r", 0.5)),
                             "f0": vec("f0", [0.04] * 3)}
        elif line[0] in ("sphere", "box", "cylinder", "capsule"):
            objs.append({"shape": line[0], "mat": kw["material"], "radius": float(kw.get("radius", 1)),
                         "height": float(kw.get("height", 1)), "size": vec("size", [1, 1, 1]),
                         "scale": vec("scale", [1, 1, 1]), "rotate": vec("rotate", [0, 0, 0]),
                         "translate": vec("translate", [0, 0, 0])})
    return cam, lights, mats, objs


# The scene format is y-up, Blender z-up: (x, y, z) -> (x, -z, y).
Y_UP = Matrix(((1, 0, 0, 0), (0, 0, -1, 0), (0, 1, 0, 0), (0, 0, 0, 1)))


def to_blender(v):
    return Vector((v[0], -v[2], v[1]))


def object_matrix(o):
    """p_world = T * Rz * Ry * Rx * S * p_object, in the scene's y-up frame."""
    rx, ry, rz = (math.radians(a) for a in o["rotate"])
    m = (Matrix.Translation(Vector(o["translate"])) @ Matrix.Rotation(rz, 4, "Z") @
         Matrix.Rotation(ry, 4, "Y") @ Matrix.Rotation(rx, 4, "X") @
         Matrix.Diagonal(Vector(o["scale"] + [1])))
    return Y_UP @ m


def material(name, m):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = m["kd"] + [1]
    bsdf.inputs["Roughness"].default_value = math.sqrt(m["r"])  # Blender squares it: alpha = r^2
    f0 = sum(m["f0"]) / 3
    if f0 > 0.2:  # a conductor's F0: metallic with that colour
        bsdf.inputs["Metallic"].default_value = 1.0
        bsdf.inputs["Base Color"].default_value = m["f0"] + [1]
    else:  # dielectric: F0 = ((ior - 1)/(ior + 1))^2
        s = math.sqrt(max(f0, 1e-6))
        bsdf.inputs["IOR"].default_value = (1 + s) / (1 - s)
    return mat


def add_primitive(o, mat):
    # Blender's primitives: axis z; the scene's cylinders and capsules: axis y (object space).
    axis_y = Matrix.Rotation(-math.pi / 2, 4, "X")
    parts = []
    if o["shape"] == "sphere":
        bpy.ops.mesh.primitive_uv_sphere_add(radius=o["radius"], segments=48, ring_count=24)
        parts.append((bpy.context.object, Matrix()))
    elif o["shape"] == "box":
        bpy.ops.mesh.primitive_cube_add(size=1)
        parts.append((bpy.context.object, Matrix.Diagonal(Vector(o["size"] + [1]))))
    else:
        bpy.ops.mesh.primitive_cylinder_add(radius=o["radius"], depth=o["height"], vertices=48)
        parts.append((bpy.context.object, axis_y))
        if o["shape"] == "capsule":
            for y in (-o["height"] / 2, o["height"] / 2):
                bpy.ops.mesh.primitive_uv_sphere_add(radius=o["radius"], segments=48, ring_count=24)
                parts.append((bpy.context.object, Matrix.Translation(Vector((0, y, 0)))))
    for ob, local in parts:
        ob.matrix_world = object_matrix(o) @ local
        bpy.ops.object.shade_smooth()
        ob.data.materials.append(mat)


def build(path, samples, threads):
    cam, lights, mats, objs = parse_scene(path)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    sc.render.engine = "CYCLES"
    cy = sc.cycles
    cy.device = "CPU"
    cy.samples = samples
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    cy.max_bounces = 0
    cy.use_light_tree = False
    sc.render.threads_mode = "FIXED"
    sc.render.threads = threads
    sc.render.resolution_x, sc.render.resolution_y = cam["res"]
    sc.render.resolution_percentage = 100
    sc.render.film_transparent = False
    world = bpy.data.worlds.new("w")
    sc.world = world
    world.color = (0, 0, 0)
    cd = bpy.data.cameras.new("cam")
    cd.sensor_fit = "VERTICAL"
    cd.angle_y = math.radians(cam["fov"])
    co = bpy.data.objects.new("cam", cd)
    sc.collection.objects.link(co)
    eye, at = to_blender(cam["pos"]), to_blender(cam["at"])
    co.location = eye
    co.rotation_euler = (at - eye).to_track_quat("-Z", "Y").to_euler()
    sc.camera = co
    for i, l in enumerate(lights):
        if l["kind"] == "directional":
            ld = bpy.data.lights.new(f"l{i}", "SUN")
            ld.angle = 0.0
            ld.energy = l["intensity"]
        else:
            ld = bpy.data.lights.new(f"l{i}", "POINT")
            ld.shadow_soft_size = 0.0
            ld.energy = l["intensity"] * 4 * math.pi  # W -> radiant intensity I = P/(4 pi)
        ld.color = l["color"]
        lo = bpy.data.objects.new(f"l{i}", ld)
        sc.collection.objects.link(lo)
        if l["kind"] == "directional":
            lo.rotation_euler = to_blender(l["dir"]).to_track_quat("Z", "Y").to_euler()
        else:
            lo.location = to_blender(l["pos"])
    bmats = {n: material(n, m) for n, m in mats.items()}
    for o in objs:
        add_primitive(o, bmats[o["mat"]])
    return sc


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("--samples", type=int, default=1)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--out")
    a = ap.parse_args(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:])
    sc = build(a.scene, a.samples, a.threads)
    bpy.ops.render.render()  # untimed: kernel set-up, first sync
    for _ in range(a.reps):
        t0 = time.perf_counter()
        bpy.ops.render.render()
        print(f"cycles_render_seconds {time.perf_counter() - t0:.4f}", flush=True)
    if a.out:
        sc.render.filepath = a.out
        bpy.ops.render.render(write_still=True)


if __name__ == "__main__":
    main()
