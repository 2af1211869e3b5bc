#!/usr/bin/env python3
"""The OSL selection flowchart (osl/abrdf_osl_select.h, abrdf_select()) in a real OSL host,
Blender's Cycles, against the C library's `abrdf advise --json`: for every case of the
table below (every surface class x both goals, r around the smooth threshold, anisotropic
0 and 0.5, given exponents, performance tolerances, out-of-range inputs) the same diffuse
and specular model, the same exponent n, and the same verdict on invalid input. Also the
float error analysis (abrdf_approx_error) against the C one (Tables 2-3) at a few n.

A probe shader, generated here with the cases as constant arrays, runs abrdf_select() for
case i in pixel i of an N x 1 orthographic render (one sample: emission is exact) and
emits (index of the diffuse model in ABRDF_MODEL_NAMES + 1, 0 = none; the same for the
specular model, 0 = invalid input; n). Compile + render take a few seconds.

usage: test_osl_select.py ABRDF SOURCE_DIR WORK_DIR [unittest args]  (the Python with bpy)
"""
import json
import os
import shutil
import subprocess
import sys
import unittest

try:
    import bpy  # noqa: F401
except ImportError:
    sys.exit("test_osl_select: the bpy module is missing; run scripts/setup_bpy.sh")

ABRDF, SRC, WORK = sys.argv[1:4]
del sys.argv[1:4]
OSL_DIR = os.path.join(SRC, "osl")
sys.path.insert(0, OSL_DIR)
import abrdf_cycles  # noqa: E402

SURFACES = ["general", "cloth_rough", "cloth_shiny", "hair", "layered_plastic",
            "layered_plate", "layered_metal"]
NONE = None  # not given (C: unset / CLI: option left out); tolerance: "none" = no limit
NO_LIMIT = 1e30


def cases():
    """(goal, surface, n, r, anisotropic, max_rel_pct, max_abs); None = not given."""
    out = []
    for surf in SURFACES:
        for goal in ("photoreal", "performance"):
            for r in (0.02, 0.03, 0.031, 0.2):
                for an in (0.0, 0.5):
                    out.append((goal, surf, NONE, r, an, 2.0, 0.05))
            for n in (2.0, 300.0):  # a given exponent (r derived from it)
                out.append((goal, surf, n, NONE, 0.0, 2.0, 0.05))
            out.append((goal, surf, 1000.0, 0.02, 0.0, 2.0, 0.05))  # both given
    # performance: the tolerances move the cheapest candidate (docs/SELECTION.md)
    for n in (0.5, 10.0, 100.0, 300.0, 1000.0, 20000.0, 1e5, 3e5):
        for rel, ab in ((2.0, 0.05), (4.0, 0.1), (0.5, NONE), (NONE, NONE), (10.0, 0.3)):
            out.append(("performance", "general", n, NONE, 0.0, rel, ab))
    # photoreal general: the smooth exponent clamp and r = 1, r = 0
    for n, r in ((0.5, 0.01), (NONE, 0.0), (NONE, 1.0), (1e6, NONE)):
        out.append(("photoreal", "general", n, r, 0.0, 2.0, 0.05))
    # invalid input: C exits with status 2 (ABRDF_E_RANGE)
    out += [("photoreal", "general", NONE, 1.5, 0.0, 2.0, 0.05),
            ("photoreal", "general", 2e6, NONE, 0.0, 2.0, 0.05),
            ("photoreal", "general", NONE, 0.2, 1.5, 2.0, 0.05),
            ("performance", "general", 300.0, NONE, 0.0, -1.0, 0.05),
            ("photoreal", "hair", NONE, 0.02, 0.0, 2.0, 0.05)]
    return out


CASES = cases()
# (model, n): the float analysis (in t = 1 - c, osl/abrdf_osl_select.h) against the C one in
# double, within 2e-3 relative (measured: at most 8e-4, f16 at n = 20000).
ERR_TOL = 2e-3
ERRORS = [("f2", 2.0), ("f4", 100.0), ("f8", 300.0), ("fs", 20.0), ("fkub", 100.0),
          ("fkv", 1000.0), ("f16", 20000.0), ("fkub", 3e5), ("f8", 1e6)]


def osl_num(v):
    return "-1.0" if v is None else repr(float(v))


def probe_source(cases):
    arr = lambda name, kind, vals: "    %s %s[%d] = {%s};\n" % (kind, name, len(vals), ", ".join(vals))
    s = ['#include "abrdf_osl.h"\n',
         "shader abrdf_select_probe(\n"
         '    output closure color result = 0 [[ string help = "case i: (diffuse index + 1, '
         'specular index + 1, n)", string label = "Result" ]])\n{\n',
         arr("goal", "string", ['"%s"' % c[0] for c in cases]),
         arr("surface", "string", ['"%s"' % c[1] for c in cases]),
         arr("n", "float", [osl_num(c[2]) for c in cases]),
         arr("r", "float", [osl_num(c[3]) for c in cases]),
         arr("an", "float", [osl_num(c[4]) for c in cases]),
         arr("rel", "float", [osl_num(NO_LIMIT if c[5] is None else c[5]) for c in cases]),
         arr("ab", "float", [osl_num(NO_LIMIT if c[6] is None else c[6]) for c in cases]),
         "    int i = clamp((int)floor(P[0]), 0, %d);\n" % (len(cases) - 1),
         "    string names[64];\n"
         '    int count = split(ABRDF_MODEL_NAMES, names, " ", 64);\n'
         "    string d, sp;\n    float nn;\n"
         "    int ok = abrdf_select(goal[i], surface[i], n[i], r[i], an[i], rel[i], ab[i], d, sp, nn);\n"
         "    float di = 0.0, si = 0.0;\n"
         "    for (int k = 0; k < count; ++k) {\n"
         "        if (names[k] == d) di = k + 1;\n"
         "        if (names[k] == sp) si = k + 1;\n"
         "    }\n"
         "    if (!ok) { di = 0.0; si = 0.0; nn = 0.0; }\n"
         "    result = color(di, si, nn) * emission();\n}\n"]
    return "".join(s)


def error_probe_source():
    s = ['#include "abrdf_osl.h"\n',
         "shader abrdf_error_probe(\n"
         '    output closure color result = 0 [[ string help = "case i: (rel %, abs, 0)", '
         'string label = "Result" ]])\n{\n',
         "    string model[%d] = {%s};\n" % (len(ERRORS), ", ".join('"%s"' % m for m, _ in ERRORS)),
         "    float n[%d] = {%s};\n" % (len(ERRORS), ", ".join(repr(float(n)) for _, n in ERRORS)),
         "    int i = clamp((int)floor(P[0]), 0, %d);\n" % (len(ERRORS) - 1),
         "    float rel, ab;\n    int ok = abrdf_approx_error(model[i], n[i], rel, ab);\n",
         "    result = color(rel, ab, ok) * emission();\n}\n"]
    return "".join(s)


def render_row(name, source, width, workdir):
    """Render the probe on a plane x in [0, width], one pixel per unit: pixel i runs case i."""
    os.makedirs(workdir, exist_ok=True)
    for h in abrdf_cycles.HEADERS:
        shutil.copy2(os.path.join(OSL_DIR, h), workdir)
    path = os.path.join(workdir, name + ".osl")
    with open(path, "w") as f:
        f.write(source)
    sc = row_scene(width)
    mat = abrdf_cycles.shader_material(name, path)
    add_quad(0, width, mat)
    return render_and_read(sc, name, width, workdir)


def row_scene(width):
    """An empty Cycles scene: CPU + OSL, direct light only, one sample, an orthographic
    camera looking down -z at x in [0, width] (one pixel per unit), 4 rows."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    # Blender renders at least 4 rows; every row runs the same cases.
    abrdf_cycles.setup_render(sc, {"width": width, "height": 4}, 1)
    sc.render.threads_mode = "FIXED"
    sc.render.threads = 2
    for key in ("diffuse", "glossy", "transmission", "volume", "transparent_max"):
        setattr(sc.cycles, key + "_bounces", 0)
    sc.cycles.max_bounces = 0
    cam = bpy.data.cameras.new("camera")
    cam.type = "ORTHO"
    cam.sensor_fit = "HORIZONTAL"
    cam.ortho_scale = width
    ob = bpy.data.objects.new("camera", cam)
    ob.location = (width / 2.0, 0.0, 10.0)  # looking down -z at the plane
    sc.collection.objects.link(ob)
    sc.camera = ob
    return sc


def add_quad(x0, x1, mat):
    me = bpy.data.meshes.new("quad")
    me.from_pydata([(x0, -4, 0), (x1, -4, 0), (x1, 4, 0), (x0, 4, 0)], [], [(0, 1, 2, 3)])
    me.materials.append(mat)
    abrdf_cycles.add_object("quad%g" % x0, me)


def render_and_read(sc, name, width, workdir, same_rows=True):
    out = os.path.join(workdir, name + ".exr")
    abrdf_cycles.render(sc, out)
    img = bpy.data.images.load(out)
    px = list(img.pixels)  # RGBA, float, bottom row first
    rows = [[tuple(px[4 * (y * width + i):4 * (y * width + i) + 3]) for i in range(width)]
            for y in range(4)]
    if not same_rows:
        return rows
    assert all(row == rows[0] for row in rows), "the rows of the probe differ"
    return rows[0]


def advise(goal, surf, n, r, an, rel, ab):
    cmd = [ABRDF, "advise", "--goal", goal, "--type", surf, "--anisotropy", repr(an), "--json"]
    if n is not None:
        cmd += ["--n", repr(n)]
    if r is not None:
        cmd += ["--r", repr(r)]
    cmd += ["--max-rel-error", "none" if rel is None else repr(rel),
            "--max-abs-error", "none" if ab is None else repr(ab)]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode == 2:
        return None  # ABRDF_E_RANGE
    p.check_returncode()
    return json.loads(p.stdout)


class OslSelect(unittest.TestCase):
    def test_select_matches_advise(self):
        with open(os.path.join(OSL_DIR, "abrdf_meta.h")) as f:
            line = next(l for l in f if l.startswith("#define ABRDF_MODEL_NAMES"))
        names = line.split('"')[1].split()
        got = render_row("abrdf_select_probe", probe_source(CASES), len(CASES),
                         os.path.join(WORK, "select"))
        failures = []
        for case, (di, si, nn) in zip(CASES, got):
            ref = advise(*case)
            if ref is None:
                want = ("invalid", "invalid", 0.0)
            else:
                want = (ref["diffuse"] or "", ref["specular"], float(ref["params"]["n"]))
            if si == 0:
                have = ("invalid", "invalid", nn)
            else:
                have = (names[int(di) - 1] if di > 0 else "", names[int(si) - 1], nn)
            same_n = abs(have[2] - want[2]) <= 1e-6 * max(1.0, abs(want[2]))
            if have[:2] != want[:2] or not same_n:
                failures.append("%s: OSL %s, C %s" % (case, have, want))
        sys.stdout.write("\nOSL abrdf_select vs abrdf advise: %d cases, %d differ\n"
                         % (len(CASES), len(failures)))
        self.assertEqual(failures, [], "\n".join(failures))

    def test_approx_error_matches_c(self):
        got = render_row("abrdf_error_probe", error_probe_source(), len(ERRORS),
                         os.path.join(WORK, "error"))
        for (m, n), (rel, ab, ok) in zip(ERRORS, got):
            ref = advise("performance", "general", n, None, 0.0, None, None)
            step = next(s for s in ref["trace"] if s.get("model") == m and s.get("step") == "candidate")
            with self.subTest(model=m, n=n):
                sys.stdout.write("%s n %g: rel %% OSL %.6g C %.6g, abs OSL %.6g C %.6g\n"
                                 % (m, n, rel, step["value"], ab, step["value2"]))
                self.assertEqual(ok, 1.0)
                # near zero (f2 at n = 2 is exact: C 2e-14 %) in absolute terms
                self.assertLess(abs(rel - step["value"]), ERR_TOL * max(1.0, step["value"]))
                self.assertLess(abs(ab - step["value2"]), ERR_TOL * max(1e-2, step["value2"]))

    # abrdf_material.osl in adaptive mode renders the closures of the models `abrdf advise`
    # chooses: quad 2i adaptive, quad 2i + 1 the same material with Model / Second model / n
    # set to the C choice. A sun of zero angle (a delta light, so only light sampling, no
    # noise) at 20 degrees from the view: both pixels evaluate the same closures at the same
    # directions and must be equal, and not black.
    MATERIAL_CASES = [  # goal, surface, r, anisotropic, n_from_r (else n = 300)
        ("photoreal", "general", 0.2, 0.0, 1), ("photoreal", "general", 0.2, 0.5, 1),
        ("photoreal", "general", 0.02, 0.0, 1), ("photoreal", "general", 0.02, 0.0, 0),
        ("photoreal", "cloth_rough", 0.5, 0.0, 1), ("photoreal", "cloth_shiny", 0.5, 0.0, 1),
        ("photoreal", "layered_plastic", 0.2, 0.0, 1), ("photoreal", "layered_metal", 0.2, 0.0, 1),
        ("performance", "general", 0.3, 0.0, 0), ("performance", "hair", 0.3, 0.0, 1)]

    def test_material_adaptive_uses_the_selection(self):
        work = os.path.join(WORK, "material")
        os.makedirs(work, exist_ok=True)
        for h in abrdf_cycles.HEADERS + ("abrdf_material.osl",):
            shutil.copy2(os.path.join(OSL_DIR, h), work)
        path = os.path.join(work, "abrdf_material.osl")
        width = 2 * len(self.MATERIAL_CASES)
        sc = row_scene(width)
        sun = bpy.data.lights.new("sun", "SUN")
        sun.angle = 0.0
        sun.energy = 3.0
        ob = bpy.data.objects.new("sun", sun)
        ob.rotation_euler = (0.0, 0.349066, 0.0)  # 20 degrees about y: light from +x
        sc.collection.objects.link(ob)
        wants = []
        for i, (goal, surf, r, an, from_r) in enumerate(self.MATERIAL_CASES):
            ref = advise(goal, surf, None if from_r else 300.0, r, an, 2.0, 0.05)
            wants.append((ref["diffuse"] or "", ref["specular"]))
            common = {"r": r, "anisotropic": an, "n": 300.0}
            adaptive = dict(common, adaptive=1, goal=goal, surface=surf, n_from_r=from_r,
                            model="lambert", model2="")
            explicit = dict(common, adaptive=0, n=float(ref["params"]["n"]),
                            model=ref["specular"] if not ref["diffuse"] else ref["diffuse"],
                            model2=ref["specular"] if ref["diffuse"] else "")
            add_quad(2 * i, 2 * i + 1, abrdf_cycles.shader_material("a%d" % i, path, adaptive))
            add_quad(2 * i + 1, 2 * i + 2, abrdf_cycles.shader_material("e%d" % i, path, explicit))
        # (rows may differ: the two triangles of a quad have different dPdu, the tangent of
        # the anisotropic lobes; the pair of a case shares its row)
        rows = render_and_read(sc, "material", width, work, same_rows=False)
        for i, case in enumerate(self.MATERIAL_CASES):
            for row in rows:
                a, e = row[2 * i], row[2 * i + 1]
                with self.subTest(case=case, models=wants[i]):
                    self.assertGreater(max(a), 0.0)
                    for x, y in zip(a, e):
                        self.assertLessEqual(abs(x - y), 1e-6 * max(1.0, abs(y)))
            sys.stdout.write("%s -> %s: adaptive %.6g, explicit %.6g\n"
                             % (case, wants[i], rows[0][2 * i][0], rows[0][2 * i + 1][0]))

if __name__ == "__main__":
    unittest.main(verbosity=2)
