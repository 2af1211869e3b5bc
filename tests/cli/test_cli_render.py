"""CLI tests of `abrdf render`: outputs, determinism across threads, errors with file:line,
usage errors, and the effect plan printed by --explain. Run by CTest with ABRDF (the binary)
and SCENES (the scenes directory) in the environment."""
import os
import re
import subprocess
import unittest

from clitest import TempDirCase

ABRDF = os.environ["ABRDF"]
SCENES = os.environ["SCENES"]


def run(*args, preview=False, cwd=None):
    """abrdf render ARGS; the PNG preview only when a test looks at it (it costs time)."""
    extra = [] if preview else ["--no-preview"]
    return subprocess.run([ABRDF, "render", *args, *extra], capture_output=True, text=True, cwd=cwd)


def same_pixels(a, b):
    """idiff of two images with zero tolerance (their DateTime headers differ; the pixels are
    compared): the finished process, returncode 0 when every pixel is the same."""
    return subprocess.run(["idiff", "-fail", "0", "-failpercent", "0", "-warn", "0", a, b],
                          capture_output=True, text=True)


# Two huang materials side by side, lit from one direction (the tests of --hair-table).
HAIR_SCENE = ("camera position=0,0,6 look_at=0,0,0 up=0,1,0 fov=30 resolution=24,24\n"
              "light directional direction=-0.45,0.75,0.55 color=1,1,1 intensity=2.5\n"
              "material brown table=hair_brown\nmaterial blond table=hair_blond\n"
              "capsule material=brown radius=0.6 height=1.4 tangent=v translate=-0.7,0,0\n"
              "sphere material=blond radius=0.6 tangent=v translate=0.8,0,0\n")


def counter(out, name):
    m = re.search(r"^\s+%s\s+(\d+)" % re.escape(name), out, re.M)
    if not m:
        raise AssertionError("no counter %r in:\n%s" % (name, out))
    return int(m.group(1))


class Render(TempDirCase):
    def test_writes_exr_and_png_preview(self):
        r = run(os.path.join(SCENES, "sphere.scene"), "-o", self.path("s.exr"), "--width", "32", "--height", "24",
                preview=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(self.path("s.exr"), "rb") as f:
            self.assertEqual(f.read(4), b"\x76\x2f\x31\x01")  # OpenEXR magic
        with open(self.path("s.png"), "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")

    def test_same_image_for_one_and_two_threads(self):
        robot = os.path.join(SCENES, "robot.scene")
        outs = []
        for t in ("1", "2"):
            r = run(robot, "-o", self.path("r%s.exr" % t), "--width", "48", "--height", "48",
                    "--threads", t, "--stats")
            self.assertEqual(r.returncode, 0, r.stderr)
            outs.append(r.stdout)
            self.assertFalse(os.path.exists(self.path("r%s.png" % t)))
        d = same_pixels(self.path("r1.exr"), self.path("r2.exr"))
        self.assertEqual(d.returncode, 0, d.stdout + d.stderr)
        self.assertEqual(outs[0], outs[1])

    def test_hair_table_cache(self):
        """--hair-table: the hair read from tables (small ones here: the default takes about a minute),
        not the per-call image; the same image for one and two threads; --hair-table-cache keeps
        a table per material and reads it back (the same image, the files not rewritten); a file there
        of another material or cut short is replaced; bad sizes or a missing directory are one
        line and exit 2, before any output."""
        hair = self.path("hair.scene")
        with open(hair, "w") as f:
            f.write(HAIR_SCENE)
        sizes = ["--hair-table-sizes", "6,3,8,1"]
        base = ["--stats", "--precision", "double"]
        r = run(hair, "-o", self.path("q.exr"), *base)
        self.assertEqual(r.returncode, 0, r.stderr)
        for t in ("1", "2"):
            r = run(hair, "-o", self.path("t%s.exr" % t), "--threads", t, *sizes, *base)
            self.assertEqual(r.returncode, 0, r.stderr)
        same = lambda a, b: same_pixels(self.path(a), self.path(b))
        self.assertEqual(same("t1.exr", "t2.exr").returncode, 0)
        self.assertNotEqual(same("q.exr", "t1.exr").returncode, 0)  # the table is not the quadrature
        cache = self.path("cache")
        os.mkdir(cache)
        r = run(hair, "-o", self.path("c1.exr"), *sizes, "--hair-table-cache", cache, *base)
        self.assertEqual(r.returncode, 0, r.stderr)
        files = sorted(os.listdir(cache))
        self.assertEqual(len(files), 2, files)  # brown and blond
        for name in files:
            self.assertRegex(name, r"^huang-[0-9a-f]{16}-6x3x8x1\.table$")
            self.assertEqual(os.path.getsize(os.path.join(cache, name)), 8 * (8 + 3 * 6 * 3 * 6 * 8))
        self.assertEqual(same("t1.exr", "c1.exr").returncode, 0)
        # read back: the same image, the files not written again (a write renames a new file
        # over the old one: another inode); then one file cut short and the other replaced by
        # the first's bytes (another material's table under this one's name): both rebuilt,
        # the same image
        ino = {n: os.stat(os.path.join(cache, n)).st_ino for n in files}
        r = run(hair, "-o", self.path("c2.exr"), *sizes, "--hair-table-cache", cache, *base)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(same("t1.exr", "c2.exr").returncode, 0)
        self.assertEqual(ino, {n: os.stat(os.path.join(cache, n)).st_ino for n in files})
        a, b = (os.path.join(cache, n) for n in files)
        with open(a, "rb") as f:
            first = f.read()
        with open(a, "wb") as f:
            f.write(first[:1000])
        with open(b, "wb") as f:
            f.write(first)
        r = run(hair, "-o", self.path("c3.exr"), *sizes, "--hair-table-cache", cache, *base)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(same("t1.exr", "c3.exr").returncode, 0)
        self.assertEqual(os.path.getsize(a), len(first))
        with open(b, "rb") as f:
            self.assertNotEqual(f.read(), first)
        # an output in a directory that does not exist: refused before any table is built
        fresh = self.path("fresh")
        os.mkdir(fresh)
        r = run(hair, "-o", self.path(os.path.join("none", "x.exr")), *sizes,
                "--hair-table-cache", fresh)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
        self.assertIn(os.path.join("none", "x.exr"), r.stderr)
        self.assertEqual(os.listdir(fresh), [])
        # bad input: one line, exit 2, nothing written
        for args, msg in ((["--hair-table-sizes", "6,3,8"], "is not NT,NV,NP,SETS"),
                          (["--hair-table-sizes", "6,3,8,1x"], "is not NT,NV,NP,SETS"),
                          (["--hair-table-sizes", "0,3,8,1"], "theta nodes NT is 0, not in [4, 256]"),
                          (["--hair-table-sizes", "6,3,8,99999999999"], "shift sets SETS is 99999999999"),
                          (["--hair-table-sizes", "+6,3,8,1"], "is not NT,NV,NP,SETS"),
                          (["--hair-table-sizes", "256,256,256,1"], "more than 2^28"),
                          (["--hair-table-cache", self.path("none")], "not a directory")):
            r = run(hair, "-o", self.path("x.exr"), *args)
            self.assertEqual(r.returncode, 2, r.stderr)
            self.assertIn(msg, r.stderr)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
            self.assertFalse(os.path.exists(self.path("x.exr")))
        r = run(hair, "-o", self.path("x.exr"), "--hair-table-sizes", "6,1,8,1")
        self.assertEqual(r.returncode, 1, r.stderr)  # the scene's material refuses the sizes
        self.assertIn("material 'brown' (line 3): huang table 6,1,8,1: ", r.stderr)
        self.assertFalse(os.path.exists(self.path("x.exr")))

    def test_budget_against_hair_table(self):
        """--adaptive --budget with --hair-table: each huang material's budget is predicted
        against its table (the trace says so), the table wins (its cost is a fraction of any
        quadrature's, its error 0) and renders from the table the prediction used, built once:
        the image is --goal photoreal's with the same tables. --explain says what the render
        reads from a table."""
        hair = self.path("hair.scene")
        with open(hair, "w") as f:
            f.write(HAIR_SCENE)
        sizes = ["--hair-table-sizes", "6,3,8,1", "--precision", "double", "--stats"]
        r = run(hair, "-o", self.path("b.exr"), "--adaptive", "--budget", "slight", "--explain",
                *sizes)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stdout.count("(the photoreal choice, as the caller prepared it)"), 2,
                         r.stdout)
        chosen = re.findall(r"^\s+\d+\. huang: the cheapest within .*predicted NMSE 0 \(none\)$",
                            r.stdout, re.M)
        self.assertEqual(len(chosen), 2, r.stdout)
        costs = [float(c) for c in re.findall(r"(\S+) ns/eval: ", r.stdout)]
        ref = [float(c) for c in re.findall(r"huang \(reference\): .* (\S+) ns/eval", r.stdout)]
        self.assertEqual(len(ref), 2, r.stdout)
        quad = [float(c) for c in re.findall(r"entry_grid [2-5], .* (\S+) ns/eval", r.stdout)]
        self.assertEqual(len(quad), 8, r.stdout)
        self.assertLess(max(ref), min(quad))  # any quadrature costs more than a table
        self.assertTrue(all(c > 0 for c in costs))
        self.assertEqual(r.stdout.count("TT, TRT and TRRT+ read from its table (6 theta, 3 view "
                                        "azimuth and 8 light azimuth nodes, 1 shift sets)"), 2)
        self.assertRegex(r.stderr, r"huang tables 6,3,8,1: 2 built in [0-9.]+ s wall, 0 read "
                                   r"from the cache \(none given\)")
        r = run(hair, "-o", self.path("p.exr"), "--adaptive", "--goal", "photoreal", *sizes)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(same_pixels(self.path("b.exr"), self.path("p.exr")).returncode, 0)
        # A material no object shows builds no table; one whose line sets a parameter of
        # huang's that its table entry does not describe (cuticle_tilt) renders other
        # parameters than the photoreal choice's: its budget is predicted against the per-call
        # quadrature, as without tables, and the render tabulates what it renders.
        with open(hair, "w") as f:
            f.write(HAIR_SCENE.replace("material blond table=hair_blond",
                                       "material blond table=hair_blond cuticle_tilt=3\n"
                                       "material spare table=hair_red"))
        r = run(hair, "-o", self.path("u.exr"), "--adaptive", "--budget", "slight", "--explain",
                *sizes)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stdout.count("(the photoreal choice, as the caller prepared it)"), 1,
                         r.stdout)
        self.assertEqual(r.stdout.count("(the photoreal choice),"), 2, r.stdout)  # blond, spare
        self.assertRegex(r.stderr, r"huang tables 6,3,8,1: 2 built in")  # brown, blond

    def test_parse_error_names_file_and_line(self):
        bad = self.path("bad.scene")
        with open(bad, "w") as f:
            f.write("camera position=0,0,5 look_at=0,0,0\nsphere radius=1 material=none\n")
        r = run(bad, "-o", self.path("x.exr"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("%s:2: material 'none' is not defined" % bad, r.stderr)
        self.assertFalse(os.path.exists(self.path("x.exr")))

    def test_usage_errors(self):
        sphere = os.path.join(SCENES, "sphere.scene")
        for args, msg in ((["--spp", "3"], "not a square"), (["--threads", "0"], "--threads"),
                          (["--bogus"], "unknown option"), (["--set", "r=0.2"], "--set needs --model"),
                          (["--adaptive"], "--goal"), (["--model", "lambrt"], "did you mean")):
            r = run(sphere, "-o", self.path("x.exr"), *args)
            self.assertEqual(r.returncode, 2, args)
            self.assertIn(msg, r.stderr, args)
        r = run()
        self.assertEqual(r.returncode, 2)
        self.assertIn("missing SCENE", r.stderr)

    def test_default_output_next_to_the_working_directory(self):
        # without -o: NAME.exr and NAME.png in the current directory for .../NAME.scene
        r = run(os.path.join(SCENES, "sphere.scene"), "--width", "16", "--height", "16", preview=True,
                cwd=self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(sorted(os.listdir(self.dir)), ["sphere.exr", "sphere.png"])

    def test_model_override(self):
        r = run(os.path.join(SCENES, "sphere.scene"), "-o", self.path("m.exr"), "--width", "16", "--height", "16",
                "--model", "blinn_phong", "--set", "n=50", "--explain")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("plastic (line 7): blinn_phong", r.stdout)
        self.assertEqual(counter(r.stdout, "fresnel evals"), 0)

    def test_explain_single_sphere_plans_no_shadow_rays(self):
        r = run(os.path.join(SCENES, "sphere.scene"), "-o", self.path("e.exr"), "--width", "32", "--height", "32",
                "--explain")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("no shadow rays - no object can block it", r.stdout)
        self.assertIn("tangent frames: no", r.stdout)
        self.assertEqual(counter(r.stdout, "shadow rays"), 0)
        self.assertGreater(counter(r.stdout, "shadow rays skipped"), 0)
        self.assertEqual(counter(r.stdout, "tangent frames"), 0)

    def test_explain_robot_plans_shadow_rays(self):
        r = run(os.path.join(SCENES, "robot.scene"), "-o", self.path("e.exr"), "--width", "32", "--height", "32",
                "--explain")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertRegex(r.stdout, r"shadow rays for \d+ of 35 receivers")
        self.assertGreater(counter(r.stdout, "shadow rays"), 0)

    def test_adaptive_robot(self):
        for goal, specular in (("photoreal", "disney_specular"), ("performance", "lambert + f")):
            r = run(os.path.join(SCENES, "robot.scene"), "--adaptive", "--goal", goal, "-o", self.path("a.exr"),
                    "--width", "32", "--height", "32", "--explain", preview=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            m = re.search(r"selection: material 'shell' \(line 11\), goal %s: (.*)" % goal, r.stdout)
            self.assertIsNotNone(m, r.stdout)
            self.assertIn(specular, m.group(1))
            self.assertIn("shell (line 11): %s\n" % m.group(1), r.stdout)  # the plan renders the choice
            self.assertTrue(os.path.exists(self.path("a.png")))

    def test_material_table_entries(self):
        scene = self.path("t.scene")
        with open(scene, "w") as f:
            f.write("camera position=0,0,4 look_at=0,0,0 resolution=16,16\n"
                    "light directional direction=0,1,1 intensity=3\n"
                    "material g table=gold\n"
                    "material s adaptive goal=photoreal r=0.01 kd=0.2\n"
                    "sphere material=g radius=1 translate=-1,0,0\n"
                    "sphere material=s radius=0.5 translate=1,0,0\n")
        r = run(scene, "-o", self.path("t.exr"), "--explain")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("material 'g' (line 3), goal photoreal, table entry gold: disney_diffuse + disney_specular",
                      r.stdout)
        # The paper's smooth branch: alpha <= 0.03 -> Lambert (1 - F) + f_2E.
        self.assertIn("material 's' (line 4), goal photoreal: lambert_fresnel + f_2e", r.stdout)
        with open(scene, "a") as f:
            f.write("material bad table=gld\n")
        r = run(scene, "-o", self.path("t.exr"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("%s:7: material 'bad': no entry 'gld' in the material table; did you mean: gold" % scene,
                      r.stderr)


if __name__ == "__main__":
    unittest.main(verbosity=2)
