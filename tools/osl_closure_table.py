#!/usr/bin/env python3
"""Closure mode measured: abrdf_material.osl (the models mapped onto Cycles' closures,
Cycles' own lights and path tracing) against `abrdf render` of the same scene, NMSE per
model and per material class of the selection. Prints Markdown tables (docs/OSL.md).

usage: .venv/bin/python tools/osl_closure_table.py ABRDF SOURCE_DIR WORK_DIR [SAMPLES]

Both renderers integrate the pixel (box filter): the C renderer on SAMPLES (a square)
stratified points, Cycles on SAMPLES random points; the scene has one directional light,
so Cycles' light sampling adds no noise. The mesh is a 128 x 64 UV sphere with smooth
normals; its silhouette and interpolated normals are part of the measured error.
"""
import json
import os
import runpy
import subprocess
import sys

import bpy  # noqa: F401

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


def run(*args):
    p = subprocess.run([ABRDF, *args], capture_output=True, text=True)
    return p.returncode, p.stdout


def measure(tag, scene_text=None, model=None):
    d = os.path.join(WORK, tag)
    os.makedirs(d, exist_ok=True)
    scene = os.path.join(d, "scene.scene")
    with open(scene, "w") as f:
        f.write(scene_text or BASE.format(material="diffuse=lambert specular=disney_specular "
                                          "kd=0.18,0.30,0.60 ks=1 f0=0.04 r=0.35"))
    extra = ["--model", model] if model else []
    ref, test, script = (os.path.join(d, n) for n in ("c.exr", "cycles.exr", "scene.py"))
    run("render", scene, "-o", ref, "--spp", str(SAMPLES), "--no-preview", *extra)
    run("export", "--cycles", scene, "-o", script, "--mode", "closure", "--spp", str(SAMPLES),
        *extra)
    s = runpy.run_path(script, run_name="abrdf_scene")["SCENE"]
    sc = abrdf_cycles.build(s, "closure", os.path.join(d, "osl"), os.path.join(SRC, "osl"),
                            segments=64)
    abrdf_cycles.render(sc, test)
    rc, out = run("compare", ref, test, "--json")
    return json.loads(out)["nmse"]


def row(name, nmse):
    cls = ("no visible difference" if nmse < 1e-4 else "slight" if nmse < 2.5e-4
           else "noticeable" if nmse < 1e-3 else "significant")
    return "| %s | %.1e | %s |" % (name, nmse, cls)


def main():
    os.makedirs(WORK, exist_ok=True)
    # Models over layers have no closure (docs/OSL.md); the hair models map onto Cycles'
    # fibre closures.
    models = [m["name"] for m in json.loads(run("models", "--json")[1])["models"]
              if "layers" not in m["needs"]]
    lines = ["Closure mode vs `abrdf render`, one model on the sphere (%d samples):" % SAMPLES,
             "| model | NMSE | Table-8 class |", "|---|---|---|"]
    for m in models:
        lines.append(row(m, measure("model_" + m, model=m)))
    lines += ["", "Closure mode vs `abrdf render`, per material class (%d samples):" % SAMPLES,
              "| material class | NMSE | Table-8 class |", "|---|---|---|"]
    for k, (name, mat) in enumerate(CLASSES):
        lines.append(row(name, measure("class_%d" % k, BASE.format(material=mat))))
    sys.stdout.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
