#!/usr/bin/env python3
"""Cycles' own Principled Hair BSDF (model Huang) as an independent oracle for `huang`.

The OSL cross-checks run abrdf's own port inside Cycles; this one renders fibres as Cycles
curve primitives shaded by Cycles' C++ closure, and compares them with abrdf.

THE EQUIVALENCE. An orthographic camera looks along -z at parallel fibres (3D curves) of
radius RADIUS, a fifth of a pixel across, lit by one sun (angle 0: a directional light of
irradiance E = 1, no sampling noise) in a black world, direct light only. Cycles shades
a camera hit on a curve with the far-field model when half the pixel footprint exceeds the
projected radius (its `pixel_coverage`: 0.5 dP / radius > 1 here), and the far-field value
does not depend on where on the fibre's width the ray hits: it is Huang's S(light, view)
integrated over the whole visible width. Each hit therefore returns E S, and a pixel holds
E S times the fraction of it the fibre covers (alpha, the film being transparent). Summing
RGB and alpha over the band of pixels around a fibre gives sum(RGB) / sum(alpha) = E S: the
abrdf side is S itself, the fibre function of hair.h, `abrdf eval` f_r times N.wi. No abrdf
render is needed, and none could match: abrdf draws fibres on a surface with a pinhole
camera, while a far-field Cycles fibre is thinner than a pixel. A white diffuse fibre lit
along the view checks the units and the coverage: the mean over a cylinder's width of
cos(gamma) / pi is 1/4.

WHAT IS COMPARED, per configuration (fibre direction, light; view along +z), for the
brightest channel:
  C  Cycles: the full closure, and the lobes through the node's weights: R (1, 0, 0), TT
     (0, 1, 0), TRT + TRRT+ (0, 0, 1), TRRT+ alone (0, 0, 1e-6: Cycles sums TRRT+ in the TRT
     branch without the TRT weight); TRT is the difference. Noise: the standard error over
     the N_FIBRES fibres (each an independent band of pixels).
  Q  abrdf in Cycles' quadrature (`hair_huang_lobes --h-nodes --trrt-const`, hair.h
     `cycles_nodes`: Blender 5.0's Simpson over h, h clipped to +-0.999, weights dgamma/dh,
     TRRT+ weighted by the constant 2/pi) with fine VNDF grids (FINE_GRIDS): what a Cycles
     render estimates. THE ORACLE: C and Q agree within ORACLE_TOL plus 4 standard errors.
     What is left is Cycles' Monte Carlo energy tables against abrdf's regenerated ones, the
     fine grid's remaining error and float. This fails when abrdf's integrand (Fresnel, GGX,
     absorption, tilt, frame, ellipse, tables) departs from Cycles'.
  M  abrdf, the model (Simpson over gamma, TRRT+ weighted by the projected width, the
     default VNDF grids): `abrdf eval` f_r N.wi, which must equal hair_huang_lobes' total.
     M / C is explained as a product of factors, each computed here from the same integrand:
       M / Mc     the model's quadrature error, its VNDF grids' and its Simpson count's (Mc:
                  --refine 8 with the VNDF grids REF_GRIDS, converged);
       Mc / Hc    the clip of h to +-0.999 and R's per-node tests (Hc: --h-nodes --refine 8,
                  REF_GRIDS, converged over h); within CLIP_TOL of 1: the two quadratures
                  integrate one integrand, which this checks;
       Hc / Hk    the TRRT+ weight, projected width against 2/pi (Hk: Hc + --trrt-const);
       Hk / Q     Cycles' Simpson error over h, and FINE_GRIDS' against REF_GRIDS';
       Q / C      the energy tables and Cycles' noise (the oracle above).
     M / Mc must stay within MODEL_TOL (abrdf's own quadrature error at one direction pair,
     docs/MODELS.md, "Convergence").

usage: test_hair_cycles_oracle.py ABRDF HAIR_HUANG_LOBES WORK_DIR  (the Python with bpy)
Fails, never skips, when bpy is missing: scripts/setup_bpy.sh installs it.
"""
import math
import os
import subprocess
import sys
import time

try:
    import bpy
    import numpy as np
    from mathutils import Vector
except ImportError:
    sys.exit("test_hair_cycles_oracle: the bpy module is missing; run scripts/setup_bpy.sh "
             "(it installs Blender's bpy from PyPI into .venv)")

ABRDF, LOBES, WORK = sys.argv[1:4] if len(sys.argv) >= 4 else (None, None, None)

WIDTH = 48            # pixels across; the frame is 1 unit wide (orthographic scale 1)
N_FIBRES = 8          # fibres, one band of BAND rows each
BAND = 6
RADIUS = 0.002        # fibre radius: 0.19 pixel across, far field (0.5 dP / radius = 5.2)
SPP = 256             # Cycles samples per pixel
FINE_GRIDS = (24, 24)  # VNDF grids of Q
REF_GRIDS = (16, 16)   # VNDF grids of the converged quadratures Mc, Hc, Hk (with --refine 8)
# C against Q, relative, per lobe and in total, beyond 4 standard errors: the energy tables
# (Cycles' Monte Carlo ones and abrdf's quadrature; R, one interaction, measures them) and
# FINE_GRIDS' remaining error (TRRT+ moves by up to 20% from 16 x 12 to 24 x 24). Measured
# on the judged lobes: R 0.4%, TT 1.1%, TRT 5.1%, TRRT+ 2.8%, total 1.8% (docs/MODELS.md,
# "Cycles as an oracle").
ORACLE_TOL = {"R": 0.015, "TT": 0.03, "TRT": 0.08, "TRRT+": 0.15, "total": 0.03}
# Mc / Hc: converged over gamma and over h differ by the clip (the 0.045 rad of gamma next to
# each silhouette that |h| > 0.999 holds), in R by what Cycles decides per node (its D is
# blind to the sign of wm.wh where abrdf cuts R's range at wm.wh = 0), and by what REF_GRIDS
# leave at one pair (the two quadratures' Simpson nodes differ, so do their grids' shifts).
# Measured: R 4.2% (forward scattering), TRT 3.9% (grazing), the others 2.4% at most.
CLIP_TOL = {"R": 0.06, "TT": 0.03, "TRT": 0.05, "TRRT+": 0.03, "total": 0.03}
# M / Mc: the model's own quadrature error at one direction pair, its shifted VNDF grids'
# and its Simpson count's (docs/MODELS.md, "Convergence": 8.1% RMS over 48 pairs, in total).
# Measured on the judged lobes: R 0.9%, TT 6.1%, TRT 21% (TRT's exit is the narrowest peak in
# the VNDF squares), TRRT+ 2.0%, total 7.0%. With the grids unshifted TRT reached 64%.
MODEL_TOL = {"R": 0.03, "TT": 0.08, "TRT": 0.30, "TRRT+": 0.05, "total": 0.10}
# Lobes carrying less than this share of the total are reported, not judged (their ratio is
# noise over a tiny number).
MIN_SHARE = 0.02
LOBE_NAMES = ("R", "TT", "TRT", "TRRT+", "total")
NORMAL_MODE_FREE = 2  # Blender's curve normal modes: minimum twist, Z up, free (custom_normal)
# The major axis of an elliptical section, made normal to the fibre: off the image plane and
# off the view, so that the section is seen neither edge-on nor face-on.
MAJOR_HINT = (0.0, 0.6, 0.8)

# (name, Cycles' node inputs, abrdf's parameters). Cycles' defaults are abrdf's: roughness
# 0.3 = r, IOR 1.55 = eta, offset 2 deg = cuticle_tilt, melanin 0.8, redness 1.
PARAM_SETS = [
    ("round", {"Aspect Ratio": 1.0}, {"aspect_ratio": 1.0}),
    ("low_melanin", {"Aspect Ratio": 1.0, "Melanin": 0.2, "Roughness": 0.2,
                     "Offset": math.radians(-3.0)},
     {"aspect_ratio": 1.0, "melanin": 0.2, "r": 0.2, "cuticle_tilt": -3.0}),
    ("elliptic", {"Aspect Ratio": 0.6, "Melanin": 0.5}, {"aspect_ratio": 0.6, "melanin": 0.5}),
]

# Configurations in fibre angles: view longitudinal angle, light longitudinal angle, light
# azimuth from the view's about the fibre (deg). Generic: off the coplanar and the
# backscatter directions, where the quadratures of both are least smooth.
CONFIGS = [
    ("side", 10.0, -5.0, 40.0),
    ("cone", 30.0, -35.0, 70.0),
    ("forward", 20.0, -15.0, 150.0),
    ("grazing", 50.0, -40.0, 110.0),
    ("off_cone", 0.0, 45.0, 60.0),
]

LOBE_WEIGHTS = {"all": (1, 1, 1), "R": (1, 0, 0), "TT": (0, 1, 0), "TRT_plus": (0, 0, 1),
                "TRRT+": (0, 0, 1e-6)}


def unit(v):
    return Vector(v).normalized()


def geometry(theta_v, theta_l, phi_l):
    """World directions for the view along +z: the fibre t with t.v = sin(theta_v), the
    light l at longitudinal angle theta_l and azimuth phi_l from the view about t."""
    tv = math.radians(theta_v)
    t = Vector((math.cos(tv), 0.0, math.sin(tv)))
    v = Vector((0.0, 0.0, 1.0))
    u1 = unit(v - v.dot(t) * t)       # the view's azimuth direction in the normal plane
    u2 = t.cross(u1)
    tl, pl = math.radians(theta_l), math.radians(phi_l)
    l = unit(math.sin(tl) * t + math.cos(tl) * (math.cos(pl) * u1 + math.sin(pl) * u2))
    # The fibres lie side by side in the plane of t and y: a light near that plane would
    # reach one fibre through its neighbour (a shadow ray from a fibre passes the next, BAND
    # pixels away, closer than RADIUS when |l.n| < RADIUS / (BAND / WIDTH) |l.y|).
    assert abs(l.dot(t.cross(Vector((0.0, 1.0, 0.0))))) > 0.2, "light in the fibres' plane"
    return t, v, l


# ---- Cycles ------------------------------------------------------------------------------

def new_scene(seed):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    sc.render.engine = "CYCLES"
    sc.cycles.device = "CPU"
    sc.cycles.samples = SPP
    sc.cycles.seed = seed
    sc.cycles.use_adaptive_sampling = False
    sc.cycles.use_denoising = False
    sc.cycles.pixel_filter_type = "BOX"  # each sample in one pixel: the band sums are exact
    sc.cycles.filter_width = 1.0
    sc.cycles.max_bounces = 0            # direct light only: no light between fibres
    sc.cycles_curves.shape = "THICK"     # round 3D curves, not ribbons
    sc.render.threads_mode = "FIXED"
    sc.render.threads = 2
    sc.render.resolution_x, sc.render.resolution_y = WIDTH, N_FIBRES * BAND
    sc.render.resolution_percentage = 100
    sc.render.film_transparent = True    # alpha = the fibre's coverage
    sc.view_settings.view_transform = "Standard"
    st = sc.render.image_settings
    st.file_format, st.color_mode, st.color_depth = "OPEN_EXR", "RGBA", "32"
    world = bpy.data.worlds.new("black")
    world.color = (0.0, 0.0, 0.0)
    if world.node_tree is not None:  # a new world's Background is 0.05 grey: no light
        for node in world.node_tree.nodes:
            if node.type == "BACKGROUND":
                node.inputs["Strength"].default_value = 0.0
    sc.world = world
    cam = bpy.data.cameras.new("camera")
    cam.type, cam.ortho_scale, cam.clip_end = "ORTHO", 1.0, 100.0
    co = bpy.data.objects.new("camera", cam)
    co.location = (0.0, 0.0, 10.0)
    sc.collection.objects.link(co)
    sc.camera = co
    return sc


def material(kind, inputs=None, weights=(1, 1, 1)):
    m = bpy.data.materials.new(kind)
    m.use_nodes = True
    nt = m.node_tree
    for node in list(nt.nodes):
        nt.nodes.remove(node)
    if kind == "diffuse":
        bsdf = nt.nodes.new("ShaderNodeBsdfDiffuse")
        bsdf.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    else:
        bsdf = nt.nodes.new("ShaderNodeBsdfHairPrincipled")
        bsdf.model, bsdf.parametrization = "HUANG", "MELANIN"
        for k, val in inputs.items():
            bsdf.inputs[k].default_value = val
        for k, w in zip(("Reflection", "Transmission", "Secondary Reflection"), weights):
            bsdf.inputs[k].default_value = w
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    nt.links.new(bsdf.outputs[0], out.inputs["Surface"])
    return m


def fibres(sc, mat, t, major):
    """N_FIBRES straight curves along t, one per band, long enough to cross the frame. Their
    normals, which Cycles aligns an elliptical section's major axis with, are set to major
    (the curves' "free" normal mode and its custom_normal attribute)."""
    c = bpy.data.hair_curves.new("fibres")
    c.add_curves([2] * N_FIBRES)
    pos = []
    for k in range(N_FIBRES):
        centre = Vector((0.0, ((k + 0.5) / N_FIBRES - 0.5) * N_FIBRES * BAND / WIDTH, 0.0))
        pos += [*(centre - 3.0 * t), *(centre + 3.0 * t)]
    c.position_data.foreach_set("vector", np.array(pos, dtype=np.float32))
    c.attributes.new("radius", "FLOAT", "POINT").data.foreach_set(
        "value", np.full(2 * N_FIBRES, RADIUS, dtype=np.float32))
    c.attributes.new("normal_mode", "INT8", "CURVE").data.foreach_set(
        "value", [NORMAL_MODE_FREE] * N_FIBRES)
    c.attributes.new("custom_normal", "FLOAT_VECTOR", "POINT").data.foreach_set(
        "vector", np.tile(np.array(major, dtype=np.float32), 2 * N_FIBRES))
    c.materials.append(mat)
    ob = bpy.data.objects.new("fibres", c)
    sc.collection.objects.link(ob)


def sun(sc, l):
    li = bpy.data.lights.new("sun", "SUN")
    li.energy, li.angle = 1.0, 0.0
    ob = bpy.data.objects.new("sun", li)
    ob.rotation_mode = "QUATERNION"
    ob.rotation_quaternion = Vector((0.0, 0.0, 1.0)).rotation_difference(l)  # +z to l
    sc.collection.objects.link(ob)


def render_bands(sc, name):
    path = os.path.join(WORK, name + ".exr")
    sc.render.filepath = path
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(path)
    px = np.array(img.pixels[:], dtype=np.float64).reshape(N_FIBRES, BAND, WIDTH, 4)
    bpy.data.images.remove(img)
    sums = px.sum(axis=(1, 2))
    return sums[:, :3] / sums[:, 3:4], sums[:, 3] / WIDTH  # E S per fibre, coverage per column


def cycles_lobes(inputs, t, major, l, tag, seed=0):
    """Mean and standard error of E S per lobe set (LOBE_WEIGHTS) over the fibres."""
    out = {}
    for lobe, w in LOBE_WEIGHTS.items():
        sc = new_scene(seed)
        fibres(sc, material("hair", inputs, w), t, major)
        sun(sc, l)
        per_fibre, _ = render_bands(sc, "%s_%s" % (tag, lobe.replace("+", "p")))
        out[lobe] = (per_fibre.mean(axis=0), per_fibre.std(axis=0, ddof=1) / math.sqrt(N_FIBRES))
    trt_plus, trrt = out.pop("TRT_plus"), out["TRRT+"]
    out["TRT"] = (trt_plus[0] - trrt[0], np.hypot(trt_plus[1], trrt[1]))
    out["total"] = out.pop("all")
    return out


# ---- abrdf -------------------------------------------------------------------------------

def local(w, t, major):
    """abrdf's fibre frame: T = +x, the section's major axis B = +y, N = B x T = +z."""
    n = major.cross(t)
    return [w.dot(t), w.dot(major), w.dot(n)]


def abrdf_lobes(params, wi, wo, *options):
    """S per lobe (R, TT, TRT, TRRT+, total; RGB) from hair_huang_lobes with its options."""
    args = [LOBES, *options] + ["%s=%r" % kv for kv in params.items()]
    line = " ".join(repr(x) for x in wi + wo) + "\n"
    v = [float(x) for x in subprocess.run(args, input=line, check=True, capture_output=True,
                                          text=True).stdout.split()]
    return {lobe: np.array(v[3 * k:3 * k + 3]) for k, lobe in enumerate(LOBE_NAMES)}


def abrdf_eval_s(params, wi, wo):
    """S from the public command: f_r times N.wi."""
    args = [ABRDF, "eval", "huang", "--wi", "%r,%r,%r" % tuple(wi), "--wo", "%r,%r,%r" % tuple(wo)]
    for kv in params.items():
        args += ["--set", "%s=%r" % kv]
    out = subprocess.run(args, check=True, capture_output=True, text=True).stdout.split()
    return np.array([float(x) for x in out[-3:]]) * wi[2]


# ---- the checks --------------------------------------------------------------------------

def check_units():
    """A white diffuse fibre lit along the view: mean radiance E/4 over its width, and the
    coverage 2 RADIUS per unit length."""
    sc = new_scene(0)
    fibres(sc, material("diffuse"), Vector((1.0, 0.0, 0.0)), Vector((0.0, 1.0, 0.0)))
    sun(sc, Vector((0.0, 0.0, 1.0)))
    per_fibre, cover = render_bands(sc, "diffuse")
    mean, sem = per_fibre.mean(), per_fibre.std(ddof=1) / math.sqrt(per_fibre.size)
    cov = cover.mean() / (2.0 * RADIUS * WIDTH)
    print("units: white diffuse fibre E S = %.5f +- %.5f (expect 0.25), coverage %.4f of 2r"
          % (mean, sem, cov))
    return ([] if abs(mean - 0.25) < 4 * sem + 0.005 else
            ["diffuse fibre %.5f, not 0.25" % mean]) + \
           ([] if abs(cov - 1) < 0.05 else ["coverage %.4f of 2r" % cov])


def ratio(a, b):
    return a / b if b > 0 else float("nan")


def main():
    os.makedirs(WORK, exist_ok=True)
    t0 = time.time()
    failures = check_units()
    fine = ["entry_grid=%d" % FINE_GRIDS[0], "internal_grid=%d" % FINE_GRIDS[1]]
    ref = ["entry_grid=%d" % REF_GRIDS[0], "internal_grid=%d" % REF_GRIDS[1]]
    print("\nper lobe, brightest channel: C (Cycles, its noise), Q, M, and the factors of M/C")
    print("%-11s %-8s %-5s %11s %9s %11s %7s %11s %7s | %6s %6s %6s %6s %6s" %
          ("set", "config", "lobe", "C", "noise", "Q", "C/Q", "M", "M/C", "M/Mc", "Mc/Hc",
           "Hc/Hk", "Hk/Q", "Q/C"))
    for set_name, inputs, params in PARAM_SETS:
        for cname, theta_v, theta_l, phi_l in CONFIGS:
            t, v, l = geometry(theta_v, theta_l, phi_l)
            # The major axis: the curves' normal; for a round fibre t x v, which puts abrdf's
            # ribbon normal N = major x t in the view's azimuth. Its sign puts the view above
            # the ribbon; the section is symmetric.
            hint = Vector(MAJOR_HINT) if params["aspect_ratio"] < 1.0 else t.cross(v)
            major = unit(hint - hint.dot(t) * t)
            if major.cross(t).dot(v) < 0.0:
                major = -major
            cyc = cycles_lobes(inputs, t, major, l, "%s_%s" % (set_name, cname))
            wi, wo = local(l, t, major), local(v, t, major)
            s = {"Q": abrdf_lobes(params, wi, wo, "--h-nodes", "--trrt-const", *fine),
                 "Hk": abrdf_lobes(params, wi, wo, "--h-nodes", "--trrt-const", "--refine", "8",
                                   *ref),
                 "Hc": abrdf_lobes(params, wi, wo, "--h-nodes", "--refine", "8", *ref),
                 "Mc": abrdf_lobes(params, wi, wo, "--refine", "8", *ref),
                 "M": abrdf_lobes(params, wi, wo)}
            if wi[2] > 0.0:  # the light above the ribbon too: the public f_r applies
                pub = abrdf_eval_s(params, wi, wo)
                if not np.allclose(pub, s["M"]["total"], rtol=1e-6, atol=1e-12):
                    failures.append("%s %s: abrdf eval S %s != lobes' total %s"
                                    % (set_name, cname, pub, s["M"]["total"]))
            for lobe in LOBE_NAMES:
                c, sem = cyc[lobe]
                k = int(np.argmax(s["Q"]["total"]))  # the brightest channel
                v_ = {key: val[lobe][k] for key, val in s.items()}
                print("%-11s %-8s %-5s %11.4e %9.2e %11.4e %7.4f %11.4e %7.4f | %6.3f %6.3f "
                      "%6.3f %6.3f %6.3f" %
                      (set_name, cname, lobe, c[k], sem[k], v_["Q"], ratio(c[k], v_["Q"]),
                       v_["M"], ratio(v_["M"], c[k]), ratio(v_["M"], v_["Mc"]),
                       ratio(v_["Mc"], v_["Hc"]), ratio(v_["Hc"], v_["Hk"]),
                       ratio(v_["Hk"], v_["Q"]), ratio(v_["Q"], c[k])))
                if v_["Q"] < MIN_SHARE * s["Q"]["total"][k]:
                    continue
                where = "%s %s %s" % (set_name, cname, lobe)
                tol = ORACLE_TOL[lobe] * v_["Q"] + 4.0 * sem[k]
                if not abs(c[k] - v_["Q"]) <= tol:
                    failures.append("%s: Cycles %.5e vs abrdf in Cycles' quadrature %.5e "
                                    "(tolerance %.2e)" % (where, c[k], v_["Q"], tol))
                if not abs(ratio(v_["Mc"], v_["Hc"]) - 1.0) <= CLIP_TOL[lobe]:
                    failures.append("%s: converged over gamma / over h %.4f (tolerance %g)"
                                    % (where, ratio(v_["Mc"], v_["Hc"]), CLIP_TOL[lobe]))
                if not abs(ratio(v_["M"], v_["Mc"]) - 1.0) <= MODEL_TOL[lobe]:
                    failures.append("%s: the model / its converged quadrature %.4f "
                                    "(tolerance %g)" % (where, ratio(v_["M"], v_["Mc"]),
                                                        MODEL_TOL[lobe]))
    print("time %.1f s" % (time.time() - t0))
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    if ABRDF is None:
        sys.exit(__doc__)
    sys.exit(main())
