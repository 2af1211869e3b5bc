#!/usr/bin/env python3
"""Closure mode measured: abrdf_material.osl (the models mapped onto Cycles' closures,
Cycles' own lights and path tracing) against `abrdf render` of the same scene, NMSE per
model and per material class of the selection. Prints Markdown tables (docs/OSL.md).

usage: .venv/bin/python tools/measure/osl_closure_table.py ABRDF SOURCE_DIR WORK_DIR [SAMPLES]
ABRDF_OSL_MODELS=m1,m2 measures only those models and the classes that use them.

Both renderers integrate the pixel (box filter): the C renderer on SAMPLES (a square)
stratified points, Cycles on SAMPLES random points; the scene has one directional light,
so Cycles' light sampling adds no noise. The mesh is a 128 x 64 UV sphere with smooth
normals; its silhouette and interpolated normals are part of the measured error.

Two more columns separate the mapping from the sampling: "floor" is the NMSE of the C
renderer against itself with jittered strata (`--jitter`), what 64 different sample
positions alone change; "converged" is the NMSE over the pixels where those two C images
agree to 5 % (a near-mirror highlight of a light, far smaller than a pixel, is hit by a
handful of samples or none, so no 64-sample image resolves it), with the number of pixels
left out.
"""
import json
import os
import runpy
import subprocess
import sys

import bpy
import numpy  # comes with bpy

ABRDF, SRC, WORK = sys.argv[1:4]
SAMPLES = int(sys.argv[4]) if len(sys.argv) > 4 else 64
sys.path.insert(0, os.path.join(SRC, "osl"))
import abrdf_cycles  # noqa: E402

BASE = """camera position=0,0,4 look_at=0,0,0 up=0,1,0 fov=30 resolution=64,64
light directional direction=-1,1,1 color=1,1,1 intensity=3
ambient 0
material m {material}
sphere material=m radius=1
"""

# The selection's outcomes for general surfaces (abrdf advise --rules): material classes.
CLASSES = [
    ("performance (Lambert + Blinn-Phong)", "diffuse=lambert specular=blinn_phong kd=0.18,0.30,0.60 ks=0.5 n=100"),
    ("performance (Lambert + f4)", "diffuse=lambert specular=f4 kd=0.18,0.30,0.60 ks=0.5 n=100"),
    ("photoreal rough (Disney diffuse + GGX)", "diffuse=disney_diffuse specular=disney_specular kd=0.18,0.30,0.60 ks=1 f0=0.04 r=0.35"),
    ("photoreal rough metal (Disney diffuse + GGX)", "diffuse=disney_diffuse specular=disney_specular kd=0.02 ks=1 f0=0.95,0.64,0.54 r=0.3"),
    ("photoreal rough anisotropic (Disney diffuse + aniso GGX)", "diffuse=disney_diffuse specular=disney_specular_aniso kd=0.18,0.30,0.60 ks=1 f0=0.04 r=0.35 anisotropic=0.8"),
    ("photoreal smooth (Lambert*(1-F) + f_2E)", "diffuse=lambert_fresnel specular=f_2e kd=0.18,0.30,0.60 ks=1 f0=0.04 n=1000"),
]
# Four interfaces, coloured absorbing media, a less dense layer, a dielectric bottom: the
# stack of tests/ports/test_osl_cycles.py (CrossCheck.STACK).
STACK = ("layer_count=4", "layer0_eta=1.4", "layer0_r=0.3", "layer0_sigma_a=0.5,2,4",
         "layer0_depth=0.3", "layer1_eta=0.7", "layer1_r=0.15", "layer2_eta=1.9",
         "layer2_r=0.5", "layer2_sigma_a=3,1,0.2", "layer2_depth=0.2", "layer3_eta=1.3",
         "layer3_r=0.6")
# The layered classes of the selection (abrdf advise --rules, special surfaces): the
# material-table entries of each class, with the parameters the selection gives them.
LAYERED_ENTRIES = [("layered_plastic", "car_paint"), ("layered_plastic", "varnished_wood"),
                   ("layered_plate", "transparent_plate"), ("layered_plate", "frosted_plate"),
                   ("layered_metal", "coated_steel"), ("layered_metal", "coated_chrome")]


def fmt(v):
    return ",".join("%.17g" % x for x in v) if isinstance(v, list) else "%.17g" % v


def layered_classes(model_params):
    """(name, material line) of each layered entry, from `abrdf advise ENTRY --json`."""
    out = []
    for cls, entry in LAYERED_ENTRIES:
        a = json.loads(run("advise", entry, "--json")[1])
        model, p = a["specular"], a["params"]
        vals = {"layer_count": len(p["layers"])}
        for k, ly in enumerate(p["layers"]):
            for field in ("eta", "kappa", "r", "sigma_a", "depth"):
                vals["layer%d_%s" % (k, field)] = ly[field]
        vals.update((k, v) for k, v in p.items() if k != "layers")
        line = "model=%s " % model + " ".join(
            "%s=%s" % (k, fmt(vals[k])) for k in model_params[model] if k in vals)
        out.append(("%s: %s (%s)" % (cls, entry, model), model, line))
    return out


def run(*args):
    p = subprocess.run([ABRDF, *args], capture_output=True, text=True)
    return p.returncode, p.stdout


def measure(tag, scene_text=None, model=None, sets=()):
    d = os.path.join(WORK, tag)
    os.makedirs(d, exist_ok=True)
    scene = os.path.join(d, "scene.scene")
    with open(scene, "w") as f:
        f.write(scene_text or BASE.format(material="diffuse=lambert specular=disney_specular "
                                          "kd=0.18,0.30,0.60 ks=1 f0=0.04 r=0.35"))
    extra = ["--model", model] if model else []
    for a in sets:
        extra += ["--set", a]
    ref, test, script = (os.path.join(d, n) for n in ("c.exr", "cycles.exr", "scene.py"))
    run("render", scene, "-o", ref, "--spp", str(SAMPLES), "--no-preview", *extra)
    run("export", "--cycles", scene, "-o", script, "--mode", "closure", "--spp", str(SAMPLES),
        *extra)
    s = runpy.run_path(script, run_name="abrdf_scene")["SCENE"]
    sc = abrdf_cycles.build(s, "closure", os.path.join(d, "osl"), os.path.join(SRC, "osl"),
                            segments=64)
    abrdf_cycles.render(sc, test)
    jit = os.path.join(d, "c_jitter.exr")
    run("render", scene, "-o", jit, "--spp", str(SAMPLES), "--jitter", "--no-preview", *extra)
    c, cj, cy = (load(p) for p in (ref, jit, test))
    nmse = json.loads(run("compare", ref, test, "--json")[1])["nmse"]
    floor = json.loads(run("compare", ref, jit, "--json")[1])["nmse"]
    ok = (abs(cj - c).max(axis=2) <= CONVERGED_REL * numpy.maximum(abs(c).max(axis=2), 1e-3))
    den = (c[ok] ** 2).sum()
    conv = ((cy[ok] - c[ok]) ** 2).sum() / den if den > 1e-6 * c.size else None
    return nmse, floor, conv, int((~ok).sum())


CONVERGED_REL = 0.05


def load(path):
    img = bpy.data.images.load(os.path.abspath(path))
    w, h = img.size
    a = numpy.empty(w * h * 4, dtype=numpy.float32)
    img.pixels.foreach_get(a)
    bpy.data.images.remove(img)
    return a.reshape(h, w, 4)[..., :3].astype(numpy.float64)


def table8(nmse):
    return ("no visible difference" if nmse < 1e-4 else "slight" if nmse < 2.5e-4
            else "noticeable" if nmse < 1e-3 else "significant")


def row(name, m):
    nmse, floor, conv, excluded = m
    return "| %s | %.1e | %s | %.1e | %s |" % (
        name, nmse, table8(nmse), floor,
        "%.1e (%d px out)" % (conv, excluded) if conv is not None else
        "n/a: black outside the highlight")


HEAD = "| %s | NMSE | Table-8 class | floor: C vs C jittered | converged pixels |\n|---|---|---|---|---|"


def main():
    os.makedirs(WORK, exist_ok=True)
    info = json.loads(run("models", "--json")[1])["models"]
    only = os.environ.get("ABRDF_OSL_MODELS")
    only = only.split(",") if only else None
    # Every model has a closure mapping: the layered ones onto stacked GGX lobes, the hair
    # models onto Cycles' fibre closures (docs/OSL.md).
    models = [m["name"] for m in info]
    params = {m["name"]: [p["name"] for p in m["params"]] for m in info}
    lines = ["Closure mode vs `abrdf render`, one model on the sphere (%d samples):" % SAMPLES,
             HEAD % "model"]
    for m in models:
        if not only or m in only:
            lines.append(row(m, measure("model_" + m, model=m)))
    for m in models:  # the layered models on a deeper stack
        if "layers" in params[m] or any(p.startswith("layer") for p in params[m]):
            if not only or m in only:
                lines.append(row(m + ", 4-layer stack",
                                 measure("stack_" + m, model=m, sets=STACK)))
    lines += ["", "Closure mode vs `abrdf render`, per material class (%d samples):" % SAMPLES,
              HEAD % "material class"]
    classes = [(name, mat.split()[1].split("=")[1], mat) for name, mat in CLASSES]
    classes += layered_classes(params)
    for k, (name, model, mat) in enumerate(classes):
        if not only or model in only or any(("=%s " % m) in mat for m in only):
            lines.append(row(name, measure("class_%d" % k, BASE.format(material=mat))))
    sys.stdout.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
