"""Several lights with shadows in POV-Ray, exactly: the robot under three lights
(scenes/robot_lights.scene: two directional, one point) exported once by `abrdf export --pov`,
rendered by the real povray once per light (Declare=Abrdf_Pass=k), the passes summed and the
2 x 2 blocks averaged by oiiotool, compared by `abrdf compare` with `abrdf render --spp 4`:
the commands of docs/POVRAY.md ("Several lights") and README.md, as a user types them.

It also checks that the comparison sees the shadows (the same file rendered without
Abrdf_Pass, every light in the pigment and no shadows, fails the bar), that every pass counts
(the sum without the last one fails), and that a pass that is not a light stops the parse.

usage: test_pov_lights.py ABRDF POVRAY OIIOTOOL INCLUDE_DIR SCENE WORK_DIR"""
import os
import re
import subprocess
import sys
import unittest

ABRDF, POVRAY, OIIOTOOL, INCLUDE, SCENE, WORK = (None,) * 6
SIZE, K, LIGHTS = 32, 2, 3


def path(name):
    return os.path.join(WORK, name)


def run(*cmd):
    return subprocess.run(list(cmd), capture_output=True, text=True, cwd=WORK)


def povray(out, *declare):
    """povray on the exported file at K times the size, no antialiasing, one thread."""
    return run(POVRAY, "-D", "+WT1", "+I" + path("robot.pov"), "+O" + out, "+FE",
               "+W%d" % (K * SIZE), "+H%d" % (K * SIZE), "-A", "+L" + INCLUDE, *declare)


def nmse(text):
    m = re.search(r"^NMSE\s+(\S+)", text, re.M)
    return float(m.group(1)) if m else None


class PovLights(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        for name in os.listdir(WORK):
            os.remove(path(name))
        r = run(ABRDF, "render", SCENE, "-o", path("ref.exr"), "--width", str(SIZE), "--height",
                str(SIZE), "--spp", str(K * K), "--threads", "1", "--precision", "double",
                "--no-preview")
        assert r.returncode == 0, r.stderr
        r = run(ABRDF, "export", "--pov", SCENE, "-o", path("robot.pov"), "--width", str(SIZE),
                "--height", str(SIZE))
        assert r.returncode == 0, r.stderr
        for k in range(LIGHTS):
            r = povray(path("pass_%d.exr" % k), "Declare=Abrdf_Pass=%d" % k)
            assert r.returncode == 0 and os.path.exists(path("pass_%d.exr" % k)), r.stderr

    def sum_and_compare(self, passes, out):
        """oiiotool sums the passes and averages K x K blocks; abrdf compare against ref."""
        cmd = [OIIOTOOL, path("pass_0.exr")]
        for k in range(1, passes):
            cmd += [path("pass_%d.exr" % k), "--add"]
        r = run(*cmd, "--resize:filter=box", "%dx%d" % (SIZE, SIZE), "-o", path(out))
        self.assertEqual(r.returncode, 0, r.stderr)
        return run(ABRDF, "compare", path("ref.exr"), path(out))

    def test_passes_sum_to_the_render(self):
        r = self.sum_and_compare(LIGHTS, "sum.exr")
        print("\nthree lights, shadows on, %d passes summed: NMSE %.3e (bar 1e-4)"
              % (LIGHTS, nmse(r.stdout)), file=sys.stderr)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertLess(nmse(r.stdout), 1e-4)

    def test_every_pass_counts(self):
        r = self.sum_and_compare(LIGHTS - 1, "sum_short.exr")
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertGreater(nmse(r.stdout), 1e-3)

    def test_the_comparison_sees_shadows(self):
        # The same file without Abrdf_Pass: every light in the pigment, no shadows.
        r = povray(path("emissive.exr"))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("no Abrdf_Pass: every light without shadows", " ".join(r.stderr.split()))
        r = run(OIIOTOOL, path("emissive.exr"), "--resize:filter=box", "%dx%d" % (SIZE, SIZE),
                "-o", path("emissive_small.exr"))
        self.assertEqual(r.returncode, 0, r.stderr)
        r = run(ABRDF, "compare", path("ref.exr"), path("emissive_small.exr"))
        print("\nthe same file without passes (no shadows): NMSE %.3e" % nmse(r.stdout),
              file=sys.stderr)
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertGreater(nmse(r.stdout), 1e-3)

    def test_a_pass_that_is_no_light_stops(self):
        for bad in ("3", "-1", "0.5"):
            out = path("bad.exr")
            r = povray(out, "Declare=Abrdf_Pass=" + bad)
            self.assertNotEqual(r.returncode, 0, bad)
            self.assertIn("is not a light: render with Declare=Abrdf_Pass=k, k = 0 .. 2",
                          " ".join(r.stderr.split()), bad)  # povray wraps lines
            self.assertFalse(os.path.exists(out), bad)


if __name__ == "__main__":
    if len(sys.argv) != 7:
        sys.exit(__doc__)
    ABRDF, POVRAY, OIIOTOOL, INCLUDE, SCENE, WORK = sys.argv[1:7]
    os.makedirs(WORK, exist_ok=True)
    unittest.main(argv=sys.argv[:1], verbosity=2)
