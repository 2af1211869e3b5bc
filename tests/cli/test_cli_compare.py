"""`abrdf compare` checked against an independent computation: NMSE recomputed with numpy in
float64 from pixels read by OpenImageIO's Python bindings, PSNR and the maximum error from
OpenImageIO's own ImageBufAlgo.compare. Plus exit codes, errors and the heat map.
Usage: test_cli_compare.py PATH/TO/abrdf   (run with the system python3)."""
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np
import OpenImageIO as oiio

ABRDF = None
REL = 1e-9


def write(path, pixels, fmt="float"):
    """Write an H x W x C float array with OpenImageIO."""
    h, w, c = pixels.shape
    buf = oiio.ImageBuf(oiio.ImageSpec(w, h, c, fmt))
    buf.set_pixels(oiio.ROI(0, w, 0, h, 0, 1, 0, c), pixels.astype(np.float32))
    assert buf.write(path), buf.geterror()


def read(path):
    buf = oiio.ImageBuf(path)
    return buf.get_pixels(oiio.FLOAT).astype(np.float64)


def run(*args):
    p = subprocess.run([ABRDF, "compare", *args], capture_output=True, text=True)
    # In sanitizer builds a report must fail the test even where exit status 1 is expected.
    assert "Sanitizer" not in p.stderr, p.stderr
    return p.returncode, p.stdout, p.stderr


class CompareTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.rng = np.random.default_rng(20240611)

    def tearDown(self):
        self.tmp.cleanup()

    def path(self, name):
        return os.path.join(self.tmp.name, name)

    def pair(self, w=67, h=45, noise=0.01, fmt="float", ext="exr"):
        ref = self.rng.uniform(0.0, 2.0, (h, w, 3))
        test = ref + self.rng.normal(0.0, noise, (h, w, 3))
        a, b = self.path("ref." + ext), self.path("test." + ext)
        write(a, ref, fmt)
        write(b, test, fmt)
        return a, b

    def json_compare(self, a, b, *extra):
        rc, out, err = run(a, b, "--json", *extra)
        self.assertIn(rc, (0, 1), err)
        return rc, json.loads(out)

    def assertRel(self, got, want, rel=REL):
        self.assertLessEqual(abs(got - want), rel * abs(want), f"{got!r} vs {want!r}")

    def check_against_independent(self, a, b):
        rc, res = self.json_compare(a, b)
        r, t = read(a), read(b)  # the first image is the reference
        nmse = np.sum((t - r) ** 2) / np.sum(r ** 2)
        self.assertRel(res["nmse"], nmse)
        self.assertRel(res["mse"], np.mean((t - r) ** 2))
        cmp = oiio.ImageBufAlgo.compare(oiio.ImageBuf(b), oiio.ImageBuf(a), 1e30, 1e30)
        self.assertRel(res["psnr"], cmp.PSNR)
        self.assertRel(res["max_abs_error"], cmp.maxerror)
        self.assertEqual(res["max_pixel"], [cmp.maxx, cmp.maxy])
        self.assertEqual(res["max_channel"], "RGB"[cmp.maxc])
        return res

    def test_float_exr_agrees_with_numpy_and_oiio(self):
        res = self.check_against_independent(*self.pair())
        self.assertGreater(res["nmse"], 0)
        self.assertEqual(res["width"], 67)
        self.assertEqual(res["height"], 45)

    def test_half_exr_and_hdr_agree(self):
        self.check_against_independent(*self.pair(fmt="half", noise=0.05))
        self.check_against_independent(*self.pair(ext="hdr", noise=0.05))

    def test_reference_is_first_argument(self):
        a, b = self.path("one.exr"), self.path("two.exr")
        write(a, np.full((4, 4, 3), 1.0))
        write(b, np.full((4, 4, 3), 2.0))
        self.assertRel(self.json_compare(a, b)[1]["nmse"], 1.0)
        self.assertRel(self.json_compare(b, a)[1]["nmse"], 0.25)

    def test_table8_classes_and_fail_threshold(self):
        ref = self.rng.uniform(0.1, 1.0, (16, 16, 3))
        a = self.path("r.exr")
        write(a, ref)
        # test = ref * (1 + k): NMSE = k^2 (up to float rounding of the stored test image).
        for target, cls in ((5e-5, "none"), (1.5e-4, "slight"), (5e-4, "noticeable"), (2e-3, "significant")):
            b = self.path(f"t{target}.exr")
            write(b, ref * (1 + math.sqrt(target)))
            rc, res = self.json_compare(a, b)
            self.assertRel(res["nmse"], target, 1e-5)
            self.assertEqual(res["class"], cls)
            self.assertEqual(rc, 0 if cls == "none" else 1)  # default threshold 1e-4
            if cls == "noticeable":
                self.assertEqual(run(a, b, "--fail", str(target * 1.01))[0], 0)
                self.assertEqual(run(a, b, "--fail", str(target * 0.99))[0], 1)

    def test_identical_images(self):
        a, _ = self.pair()
        rc, res = self.json_compare(a, a)
        self.assertEqual(rc, 0)
        self.assertEqual(res["nmse"], 0)
        self.assertIsNone(res["psnr"])  # infinite
        self.assertEqual(res["class"], "none")

    def test_black_reference_is_undefined(self):
        a, b = self.path("black.exr"), self.path("grey.exr")
        write(a, np.zeros((4, 4, 3)))
        write(b, np.full((4, 4, 3), 0.5))
        rc, out, err = run(a, b)
        self.assertEqual(rc, 2)
        self.assertIn("undefined", out)
        self.assertIn("all black", err)

    def test_errors_exit_2(self):
        a, b = self.pair(w=8, h=8)
        c = self.path("small.exr")
        write(c, np.ones((7, 8, 3)))
        rc, _, err = run(a, c)
        self.assertEqual(rc, 2)
        self.assertIn("size", err)
        d = self.path("rgba.exr")
        write(d, np.ones((8, 8, 4)))
        rc, _, err = run(a, d)
        self.assertEqual(rc, 2)
        self.assertIn("4 channels", err)
        rc, _, err = run(a, self.path("missing.exr"))
        self.assertEqual(rc, 2)
        self.assertIn("missing.exr", err)
        nan = np.ones((8, 8, 3))
        nan[3, 5, 1] = np.nan
        e = self.path("nan.exr")
        write(e, nan)
        rc, _, err = run(a, e)
        self.assertEqual(rc, 2)
        self.assertIn("(5, 3)", err)
        self.assertEqual(run(a)[0], 2)
        self.assertEqual(run(a, b, "--fail", "-1")[0], 2)
        self.assertEqual(run(a, b, "--bogus")[0], 2)

    def test_heat_map(self):
        ref = np.full((10, 12, 3), 0.5)
        test = ref.copy()
        test[7, 9, :] += 0.2   # the largest error: brightest (yellow) pixel of the map
        test[2, 3, 0] += 0.1   # half of it
        a, b, heat = self.path("r.exr"), self.path("t.exr"), self.path("heat.png")
        write(a, ref)
        write(b, test)
        rc, out, err = run(a, b, "--diff", heat)
        self.assertEqual(rc, 1, err)
        self.assertIn("heat.png", out)
        h = oiio.ImageBuf(heat)
        self.assertEqual((h.spec().width, h.spec().height, h.spec().nchannels), (12, 10, 3))
        self.assertEqual(h.spec().format, oiio.UINT8)
        px = h.get_pixels(oiio.UINT8).astype(int)
        self.assertLess(px[0, 0].sum(), 10)                 # no error: black
        self.assertGreater(px[7, 9, 0], 200)                # maximum: yellow
        self.assertGreater(px[7, 9, 1], 200)
        mid = px[2, 3]
        self.assertTrue(px[0, 0].sum() < mid.sum() < px[7, 9].sum())
        self.assertEqual(run(a, b, "--diff", self.path("no/such/dir/h.png"))[0], 2)

    def test_png_inputs_are_decoded_to_linear(self):
        # 8-bit sRGB code 118 decodes to linear 0.1812; code 255 to 1.
        a, b = self.path("a.png"), self.path("b.png")
        write(a, np.full((2, 2, 3), 1.0), "uint8")
        write(b, np.full((2, 2, 3), 118 / 255), "uint8")
        _, res = self.json_compare(a, b)
        lin = ((118 / 255 + 0.055) / 1.055) ** 2.4
        self.assertRel(res["nmse"], (1 - lin) ** 2, 1e-4)
        g = self.path("grey.png")
        write(g, np.full((2, 2, 1), 1.0), "uint8")
        rc, _, err = run(a, g)
        self.assertEqual(rc, 2)
        self.assertIn("1 channels", err)


if __name__ == "__main__":
    ABRDF = sys.argv.pop(1)
    unittest.main(verbosity=2)
