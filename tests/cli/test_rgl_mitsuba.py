#!/usr/bin/env python3
"""Mitsuba 3 as the oracle for abrdf's RGL .bsdf files (tools/measured/rgl_bsdf.h).

rgl_oracle (tests/unit) writes a .bsdf file with rgl_write from a closed form (a Lambert of
kd = 0.5; a coloured Lambert plus a GGX lobe, tests/unit/rgl_models.c) and evaluates it with
rgl_eval at a few hundred random direction pairs above the horizon. Mitsuba 3's `measured`
plugin loads the same file; its eval(ctx, si, wo) with si.wi = abrdf's wi (the file's incident
direction) returns f_r cos(theta_wo), so f_r = eval / wo.z. THE ORACLE: the two agree within
REL_TOL relative (plus ABS_TOL): both interpolate the same float tables, Mitsuba in float,
abrdf in double. Mitsuba also accepts the file (its loader checks every field's type and
shape), and below the horizon both give 0.

Printed, not asserted here: the file against the closed form (the tabulation's error; the
round trip through rgl_read is bounded in tests/unit/test_rgl.c).

Usage: test_rgl_mitsuba.py RGL_ORACLE WORK_DIR. Without mitsuba the test fails.
"""
import os
import subprocess
import sys
import unittest

try:
    import numpy as np
    import mitsuba as mi
except ImportError as e:  # a missing oracle is a failure, never a skip
    sys.exit(f"test_rgl_mitsuba: {e} (scripts/setup_python.sh installs mitsuba in .venv-python)")

ORACLE, WORK = sys.argv[1], sys.argv[2]
PAIRS = 400
REL_TOL = 1e-4  # Mitsuba computes in float32 (sqrt, divisions of CDF values): measured 4.9e-5
ABS_TOL = 1e-6  # 1/sr, for values near 0
GRIDS = {"default": [], "coarse": ["4", "16", "8"]}


def rgl_oracle(*args):
    r = subprocess.run([ORACLE, *args], capture_output=True, text=True)
    if r.returncode != 0:
        raise AssertionError(f"rgl_oracle {' '.join(args)}: {r.stderr.strip()}")
    return r.stdout


def mitsuba_fr(path, wi, wo):
    """f_r of the file by Mitsuba 3: its eval divided by the cosine of wo."""
    bsdf = mi.load_dict({"type": "measured", "filename": path})
    ctx = mi.BSDFContext()
    si = mi.SurfaceInteraction3f()
    si.n = mi.Vector3f(0, 0, 1)
    si.sh_frame = mi.Frame3f(si.n)
    out = np.zeros((len(wi), 3))
    for k in range(len(wi)):
        si.wi = mi.Vector3f(*wi[k])
        v = bsdf.eval(ctx, si, mi.Vector3f(*wo[k]))
        out[k] = np.array([v[0], v[1], v[2]]) / wo[k][2]
    return out


class RglMitsuba(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        mi.set_variant("scalar_rgb")
        os.makedirs(WORK, exist_ok=True)

    def check(self, model, grid, seed):
        path = os.path.join(WORK, f"{model}_{grid}.bsdf")
        rgl_oracle("write", path, model, *GRIDS[grid])
        rows = np.loadtxt(rgl_oracle("eval", path, str(PAIRS), str(seed), model).splitlines())
        wi, wo, ours, closed = rows[:, 0:3], rows[:, 3:6], rows[:, 6:9], rows[:, 9:12]
        theirs = mitsuba_fr(path, wi, wo)
        diff = np.abs(theirs - ours)
        rel = diff / np.maximum(np.abs(ours), ABS_TOL / REL_TOL)
        table = np.abs(ours - closed) / closed
        print(f"{model} ({grid} grid): {PAIRS} pairs, abrdf vs Mitsuba max relative "
              f"{rel.max():.2e}, max absolute {diff.max():.2e} 1/sr; file vs closed form "
              f"median {np.median(table):.2e}, max {table.max():.2e}")
        worst = np.unravel_index(np.argmax(rel), rel.shape)
        self.assertTrue(np.all(diff <= REL_TOL * np.abs(ours) + ABS_TOL),
                        f"{model}: pair {worst[0]} (wi {wi[worst[0]]}, wo {wo[worst[0]]}): "
                        f"abrdf {ours[worst[0]]}, Mitsuba {theirs[worst[0]]}")
        self.assertTrue(np.all(ours > 0), f"{model}: a pair above the horizon gave 0")

    def test_lambert(self):
        self.check("lambert", "default", 1)

    def test_ggx(self):
        self.check("ggx", "default", 2)

    def test_ggx_coarse(self):
        """A coarse grid: interpolation between few slices is mixed the same way."""
        self.check("ggx", "coarse", 3)

    def test_below_horizon(self):
        path = os.path.join(WORK, "horizon.bsdf")
        rgl_oracle("write", path, "ggx", *GRIDS["coarse"])
        wi = np.array([[0.6, 0.0, 0.8], [0.6, 0.0, -0.8], [0.0, 0.0, 1.0]])
        wo = np.array([[0.0, 0.6, -0.8], [0.0, 0.6, 0.8], [0.0, 0.0, 1.0]])
        theirs = mitsuba_fr(path, wi, wo * np.array([1, 1, 1]))
        self.assertTrue(np.all(theirs[:2] == 0), theirs)
        self.assertTrue(np.all(theirs[2] > 0), theirs)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
