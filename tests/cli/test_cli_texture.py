"""`abrdf render` with textures: a large generated texture (4096 x 4096, tiled and mip-mapped
by OpenImageIO's make_texture, never committed) rendered under a small --texture-cache, with
OpenImageIO's own statistics showing the cache stayed within its bound while reading more than
it holds; bad textures refused with one line and nothing written.
Usage: test_cli_texture.py PATH/TO/abrdf   (run with the system python3: python3-openimageio,
python3-numpy)."""
import os
import re
import subprocess
import sys
import tempfile
import unittest

import numpy as np
import OpenImageIO as oiio

ABRDF = None

QUAD = """v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
f 1/1 2/2 3/3
f 1/1 3/3 4/4
"""
CAMERA = "camera position=0,0,1 look_at=0,0,0 fov=90 resolution=64,64\n"
LIGHT = "light point position=0.3,0.5,2 intensity=4\nambient 0.1\n"
STATS = re.compile(r"textures: (\d+) files, cache bound ([\d.]+) MB: peak ([\d.]+) MB, now (\d+) "
                   r"bytes, peak (\d+) tiles; (\d+) lookups, (\d+) bytes read")


def write_image(path, pixels, fmt):
    h, w, c = pixels.shape
    buf = oiio.ImageBuf(oiio.ImageSpec(w, h, c, fmt))
    buf.set_pixels(oiio.ROI(0, w, 0, h, 0, 1, 0, c), pixels)
    assert buf.write(path), buf.geterror()


class TextureTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        with open(self.path("quad.obj"), "w") as f:
            f.write(QUAD)

    def tearDown(self):
        self.tmp.cleanup()

    def path(self, name):
        return os.path.join(self.tmp.name, name)

    def scene(self, material, obj="mesh file=quad.obj material=m"):
        with open(self.path("t.scene"), "w") as f:
            f.write(CAMERA + LIGHT + "material m pbr " + material + "\n" + obj + "\n")
        return self.path("t.scene")

    def render(self, *args):
        p = subprocess.run([ABRDF, "render", self.path("t.scene"), "-o", self.path("out.exr"),
                            "--threads", "2", *args], capture_output=True, text=True)
        self.assertNotIn("Sanitizer", p.stderr)
        return p

    def test_a_texel_of_one_takes_the_mapping_like_its_neighbours(self):
        """A roughness map whose left quarter is 1 (255), the rest 0.2: the chosen models
        get the mapped parameters at every hit. Changing the 1 to 254/255 moves the image by
        what a 0.4 % rougher surface moves it, not by a switch to another block at the texels
        that happen to be exactly 1 (for every way a pbr material is chosen)."""
        for how in ("", " goal=photoreal", " goal=performance", " budget=slight"):
            images = []
            for top in (255, 254):
                tex = np.full((16, 16, 3), 51, np.uint8)  # glTF: roughness in G
                tex[:, :4, :] = top  # a quarter: the map's median texel is 0.2
                write_image(self.path("r.png"), tex, oiio.UINT8)
                self.scene("base_color=0.8,0.5,0.3 metallic=1 roughness=0.8 roughness_map=r.png"
                           + how)
                p = self.render("--no-preview")
                self.assertEqual(p.returncode, 0, p.stderr)
                inp = oiio.ImageInput.open(self.path("out.exr"))  # no cache: a new file each time
                images.append(inp.read_image(oiio.FLOAT))
                inp.close()
            a, b = images
            nmse = float(((a - b) ** 2).sum() / (b ** 2).sum())
            self.assertLess(nmse, 1e-3, how)

    def test_cache_bound_holds_on_a_large_texture(self):
        # 4096^2 8-bit RGB noise, made into a tiled MIP-mapped file
        rng = np.random.default_rng(29)
        big = oiio.ImageBuf(oiio.ImageSpec(4096, 4096, 3, "uint8"))
        big.set_pixels(oiio.ROI(0, 4096, 0, 4096, 0, 1, 0, 3),
                       rng.integers(0, 256, size=(4096, 4096, 3), dtype=np.uint8))
        config = oiio.ImageSpec()
        config.attribute("tile_width", 64)
        config.attribute("tile_height", 64)
        self.assertTrue(oiio.ImageBufAlgo.make_texture(oiio.MakeTxTexture, big,
                                                       self.path("big.tx"), config),
                        oiio.geterror())
        del big
        self.scene("base_color_map=big.tx metallic=0")
        # 512 x 512, 4 samples: a footprint of 4 texels, MIP level 2 (1024^2 x 3 = 3 MB of
        # 8-bit texels) and its neighbours, more than a 1 MB cache holds
        p = self.render("--texture-cache", "1", "--width", "512", "--height", "512", "--spp",
                        "4", "--stats", "--no-preview")
        self.assertEqual(p.returncode, 0, p.stderr)
        m = STATS.search(p.stdout)
        self.assertIsNotNone(m, p.stdout)
        files, bound, peak, now, tiles, lookups, read = m.groups()
        self.assertEqual(int(files), 1)
        self.assertEqual(float(bound), 1.0)
        self.assertLessEqual(float(peak), 1.0)
        self.assertLessEqual(int(now), 1 << 20)
        self.assertEqual(int(lookups), 512 * 512 * 4)
        self.assertGreater(int(read), 3 << 20, "the render read no more than the cache holds")
        self.assertTrue(os.path.exists(self.path("out.exr")))

    def test_explain_states_the_cache(self):
        write_image(self.path("r.png"), np.full((4, 4, 3), 128, np.uint8), "uint8")
        self.scene("roughness_map=r.png")
        p = self.render("--explain", "--no-preview", "--spp", "1")
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("tile cache bounded by 256 MB (--texture-cache, default 256)", p.stdout)
        p = self.render("--explain", "--no-preview", "--spp", "1", "--texture-cache", "7")
        self.assertIn("tile cache bounded by 7 MB", p.stdout)
        self.assertIn("textures: 1 files, cache bound 7 MB", p.stdout)

    def test_bad_textures_one_line_nothing_written(self):
        write_image(self.path("grey.png"), np.full((4, 4, 1), 100, np.uint8), "uint8")
        write_image(self.path("rgb.png"), np.full((8, 8, 3), 100, np.uint8), "uint8")
        with open(self.path("junk.png"), "w") as f:
            f.write("not an image\n")
        write_image(self.path("rgb.exr"), np.full((64, 64, 3), 0.5, np.float32), "half")
        with open(self.path("rgb.exr"), "rb") as f:
            exr = f.read()
        with open(self.path("cut.exr"), "wb") as f:  # the header whole, the pixels cut
            f.write(exr[: len(exr) * 3 // 4])
        with open(self.path("nouv.obj"), "w") as f:
            f.write("v -1 -1 0\nv 1 -1 0\nv 1 1 0\nf 1 2 3\n")
        cases = [
            ("roughness_map=junk.png", None, "junk.png: "),
            ("metallic_map=grey.png metallic_channel=2", None,
             "grey.png: no channel 2 (it has 1) for metallic_channel of material 'm' (line 4)"),
            ("normal_map=grey.png", None, "grey.png: a normal map needs 3 channels (it has 1)"),
            ("base_color_map=rgb.png", "sphere material=m radius=0.5",
             "material 'm' (line 4) has textures, but the sphere at line 5 has no texture "
             "coordinates"),
            ("base_color_map=rgb.png", "mesh file=nouv.obj material=m",
             "but the mesh at line 5 has no texture coordinates"),
            ("base_color_map=cut.exr", None, "cut.exr: "),
            # the budget's shading points read the normal map first: its pass stops there
            ("normal_map=cut.exr budget=slight", None,
             "the shading points of the budget: " + self.path("cut.exr") + ": "),
        ]
        for material, obj, want in cases:
            with self.subTest(material=material, obj=obj):
                self.scene(material, obj or "mesh file=quad.obj material=m")
                p = self.render("--spp", "1")
                self.assertNotEqual(p.returncode, 0)
                self.assertEqual(len(p.stderr.splitlines()), 1, p.stderr)
                self.assertIn(want, p.stderr)
                self.assertTrue(p.stderr.startswith("abrdf render: "), p.stderr)
                self.assertFalse(os.path.exists(self.path("out.exr")))
                self.assertFalse(os.path.exists(self.path("out.png")))
        for bad in ("0", "x", "65537"):
            self.scene("roughness_map=rgb.png")
            p = self.render("--texture-cache", bad)
            self.assertNotEqual(p.returncode, 0)
            self.assertEqual(len(p.stderr.splitlines()), 1, p.stderr)
            self.assertIn("--texture-cache", p.stderr)


if __name__ == "__main__":
    ABRDF = sys.argv.pop(1)
    unittest.main()
