"""Clear errors, every time: every line-based reader takes lines of any length (a long comment
is a comment, never data); a message keeps its reason whatever the length of the path; inputs
must be regular files (a FIFO is refused at once, never waited on); subnormal numbers are
finite; help texts state the ranges that are enforced; JSON output stays UTF-8; an empty result
is an error where it means nothing was measured; zero tangents are refused like zero normals.

Run by CTest with ABRDF (the command), SCENES and SRC (the source tree) in the environment."""
import json
import os
import re
import resource
import socket
import struct
import subprocess
import unittest

from clitest import TempDirCase, checked_stderr, read_text

ABRDF = os.environ["ABRDF"]
SCENES = os.environ["SCENES"]
SRC = os.environ["SRC"]
SPHERE = os.path.join(SCENES, "sphere.scene")


def run(*args, timeout=120):
    p = subprocess.run([ABRDF, *args], capture_output=True, timeout=timeout)
    return p.returncode, p.stdout, checked_stderr(p)


class Base(TempDirCase):
    def fails(self, rc_expected, args, *needles):
        rc, out, err = run(*args)
        self.assertEqual(rc, rc_expected, (args, err))
        self.assertEqual(err.count("\n"), 1, err)
        for n in needles:
            self.assertIn(n, err)
        return err


class LongLines(Base):
    """A 512-byte reader parsed the rest of a long comment as data; 2 KiB readers refused."""

    LONG = "x" * 1500 + " f8 -1 nan"  # what a cut line would read as an entry

    def test_cost_file(self):
        costs = self.put("c.txt", "# " + self.LONG + "\nf8 1.5  # " + self.LONG + "\n"
                         "f16 2.5\nlambert 0.5\n")
        rc, out, err = run("advise", "--n", "300", "--goal", "performance", "--costs", costs,
                           "--json")
        self.assertEqual(rc, 0, err)
        self.assertEqual(json.loads(out)["cost"]["unit"], "ns/eval (measured, abrdf calibrate)")

    def test_material_table(self):
        mats = read_text(os.path.join(SRC, "data", "materials.csv"))
        mats = "# " + self.LONG + "\n" + mats + "# " + self.LONG + "\n"
        path = self.put("m.csv", mats)
        rc, out, err = run("advise", "gold", "--materials", path)
        self.assertEqual(rc, 0, err)
        self.assertIn(path + ":", out.decode())

    def test_paper_data(self):
        data = read_text(os.path.join(SRC, "data", "paper_tables.csv"))
        path = self.put("p.csv", "# " + self.LONG + "\n" + data)
        rc, out, err = run("tables", "2", "--paper", path)
        self.assertEqual(rc, 0, err)
        rc0, out0, _ = run("tables", "2")
        self.assertEqual(out.decode().split("Published values")[0],
                         out0.decode().split("Published values")[0])

    def test_scene(self):
        text = read_text(SPHERE).replace("\n", "  # " + "c" * 5000 + "\n", 1)
        path = self.put("long.scene", text)
        rc, out, err = run("render", path, "-o", os.path.join(self.dir, "x.exr"), "--width",
                           "8", "--height", "8", "--no-preview")
        self.assertEqual(rc, 0, err)
        # A word still has a bound, and the message quotes it shortened, whole otherwise.
        path = self.put("word.scene", read_text(SPHERE) + "sphere material=" + "m" * 300 + "\n")
        self.fails(1, ["render", path, "-o", os.path.join(self.dir, "y.exr")],
                   "word.scene:", "a word of 309 characters", "words have at most 256")


class ReasonsAreKept(Base):
    def deep_dir(self):
        """A directory whose path is about 3500 bytes long."""
        d = self.dir
        while len(d) < 3500:
            d = os.path.join(d, "a-rather-long-directory-name-" + "d" * 40)
        os.makedirs(d)
        return d

    def test_long_paths_keep_the_reason(self):
        d = self.deep_dir()
        self.fails(1, ["render", os.path.join(d, "missing.scene"), "-o", "x.exr"],
                   "missing.scene: cannot open: No such file or directory")
        bad = os.path.join(d, "bad.scene")
        with open(bad, "w") as f:
            f.write("camera position=0,0,4 look_at=0,0,0\nteapot size=1\n")
        err = self.fails(1, ["render", bad, "-o", os.path.join(self.dir, "x.exr")],
                         "bad.scene:2: unknown directive 'teapot'; directives: camera, ambient, "
                         "light, material, sphere, cylinder, capsule, box")
        self.assertIn("...", err)  # the path was shortened, the reason was not
        self.fails(1, ["export", "--pov", SPHERE, "-o", os.path.join(d, "no", "x.pov")],
                   "x.pov: cannot create a file beside it: No such file or directory")
        self.fails(2, ["advise", "gold", "--costs", os.path.join(d, "costs.txt")],
                   "costs.txt: cannot open: No such file or directory")
        self.fails(2, ["advise", "gold", "--materials", os.path.join(d, "m.csv")],
                   "m.csv: cannot open: No such file or directory")
        self.fails(2, ["compare", os.path.join(d, "a.exr"), os.path.join(d, "b.exr")],
                   "a.exr: cannot open: No such file or directory")

    def test_no_empty_reasons(self):
        exr = os.path.join(self.dir, "a.exr")
        self.assertEqual(run("render", SPHERE, "-o", exr, "--width", "8", "--height", "8")[0], 0)
        err = self.fails(2, ["compare", exr, exr, "--diff", os.path.join(self.dir, "h.xyz")],
                         "h.xyz: not an 8-bit display format")
        self.fails(1, ["export", "--pov", SPHERE, "-o", self.dir], "is a directory, not a file")
        self.fails(1, ["render", self.dir, "-o", exr], "is a directory, not a file")
        self.fails(1, ["tables", "2", "--paper", self.dir], "is a directory, not a file")


class RegularFilesOnly(Base):
    def test_fifos_are_refused_at_once(self):
        fifo = os.path.join(self.dir, "fifo")
        os.mkfifo(fifo)
        out = os.path.join(self.dir, "x.exr")
        for rc, args in ((1, ["render", fifo, "-o", out]),
                         (1, ["export", "--pov", fifo, "-o", out + ".pov"]),
                         (2, ["advise", "gold", "--costs", fifo]),
                         (2, ["advise", "gold", "--materials", fifo]),
                         (1, ["render", SPHERE, "--materials", fifo, "-o", out]),
                         (1, ["tables", "2", "--paper", fifo]),
                         (1, ["tables", "4", "--costs", fifo]),
                         (2, ["compare", fifo, fifo])):
            rc_got, _, err = run(*args, timeout=30)  # a blocked open would time out
            self.assertEqual(rc_got, rc, (args, err))
            self.assertIn("not a regular file", err)


class Numbers(Base):
    def test_subnormals_are_finite(self):
        rc, out, err = run("eval", "lambert", "--wi", "1e-310,0,1", "--wo", "0,0,1")
        self.assertEqual(rc, 0, err)
        self.assertIn(b"f_r = 0.3183098862", out)
        rc, out, err = run("advise", "--n", "1e-310", "--goal", "performance")
        self.assertEqual(rc, 0, err)
        scene = self.put("s.scene", read_text(SPHERE) + "ambient 1e-310\n")
        rc, out, err = run("render", scene, "-o", os.path.join(self.dir, "x.exr"), "--width", "8",
                           "--height", "8", "--no-preview")
        self.assertEqual(rc, 0, err)
        self.fails(2, ["eval", "lambert", "--wi", "1e400,0,1", "--wo", "0,0,1"], "--wi")

    def test_zero_tangent_is_refused_like_a_zero_normal(self):
        base = ["eval", "kajiya_kay", "--wi", "0,0,1", "--wo", "0,0,1"]
        self.fails(2, base + ["--normal", "0,0,0"], "--normal")
        self.fails(2, base + ["--tangent", "0,0,0"], "--tangent 0,0,0 has zero length")
        self.fails(2, base + ["--tangent", "-0,0,-0"], "--tangent")
        rc, _, err = run(*base, "--tangent", "1,0,0")
        self.assertEqual(rc, 0, err)


class HelpStatesTheEnforcedRanges(Base):
    def test_photoreal_hair_roughness(self):
        models = json.loads(run("models", "--json")[1])["models"]
        huang = next(m for m in models if m["name"] == "huang")
        r = next(p for p in huang["params"] if p["name"] == "r")
        lo, hi = r["min"], r["max"]
        self.assertGreater(lo, 0)  # narrower than the [0, 1] --r takes otherwise
        rc, out, _ = run("advise", "--help")
        m = re.search(r"photoreal hair \(huang\): r in \[([0-9.e+-]+), ([0-9.e+-]+)\], so n <= "
                      r"(\d+)", out.decode())
        self.assertIsNotNone(m, out)
        self.assertEqual((float(m.group(1)), float(m.group(2))), (lo, hi))
        n_max = int(m.group(3))
        # What the help says is what is enforced, on both sides of each bound.
        self.fails(2, ["advise", "--type", "hair", "--r", "0.03", "--goal", "photoreal"],
                   "--r 0.03 is outside [%g, %g]: photoreal hair uses huang" % (lo, hi))
        for args in (["--r", repr(lo)], ["--r", repr(hi)], ["--n", str(n_max)]):
            rc, _, err = run("advise", "--type", "hair", "--goal", "photoreal", *args)
            self.assertEqual(rc, 0, (args, err))
        self.fails(2, ["advise", "--type", "hair", "--n", str(n_max + 1)],
                   "give n <= %d" % n_max)
        rc, _, err = run("advise", "--type", "hair", "--r", "0.03", "--goal", "performance")
        self.assertEqual(rc, 0, err)


class JsonIsUtf8(Base):
    def test_compare_json_with_a_path_that_is_not_utf8(self):
        d = os.fsencode(self.dir)
        a = d + b"/caf\xe9-latin1.exr"  # Latin-1, not UTF-8
        b = d + b"/\xc3\xa9t\xc3\xa9.exr"  # UTF-8
        for p in (a, b):
            r = subprocess.run([ABRDF, "render", SPHERE, "-o", p, "--width", "8", "--height",
                                "8", "--no-preview"], capture_output=True, timeout=120)
            self.assertEqual(r.returncode, 0, r.stderr)
        r = subprocess.run([os.fsencode(ABRDF), b"compare", a, b, b"--json"], capture_output=True,
                           timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        doc = json.loads(r.stdout.decode("utf-8"))  # strict: raises on invalid UTF-8
        self.assertTrue(doc["reference"].endswith("caf\ufffd-latin1.exr"), doc["reference"])
        self.assertTrue(doc["test"].endswith("/\u00e9t\u00e9.exr"), doc["test"])

    def test_advise_json_with_a_source_that_is_not_utf8(self):
        mats = read_text(os.path.join(SRC, "data", "materials.csv")).encode()
        mats += b"weird,general,,0.4,0.5,0.5,0.5,1,1,1,,,,1.5,,,,,,,,,,,,caf\xe9 \xff\xfe\n"
        path = self.put("m.csv", mats)
        r = subprocess.run([ABRDF, "advise", "weird", "--materials", path, "--json"],
                           capture_output=True, timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(json.loads(r.stdout.decode("utf-8"))["source"], "caf\ufffd \ufffd\ufffd")


class NothingMeasuredIsAnError(Base):
    def test_tables_6_on_a_black_scene(self):
        scene = self.put("black.scene", "camera position=0,0,4 look_at=0,0,0\n"
                         "light directional direction=0,0,-1\nmaterial m model=lambert\n"
                         "sphere material=m radius=1\n")  # lit from behind: all black
        rc, out, err = run("tables", "6", "--scene", scene, "--width", "8", "--height", "8")
        self.assertEqual(rc, 1, err)
        self.assertEqual(out, b"")
        self.assertIn("every reference image is black", err)


def exr_header_only(width, height, channels):
    """A scanline EXR that declares width x height x channels (half, ZIP) and holds its header
    and line-offset table only: no pixels (a 4.6 KB file for 8192 x 8192)."""
    def attr(name, kind, data):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data
    names = sorted("C%02d" % i for i in range(channels))
    chlist = b"".join(n.encode() + b"\0" + struct.pack("<iB3xii", 1, 0, 1, 1) for n in names)
    box = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    head = (struct.pack("<ii", 20000630, 2) + attr("channels", "chlist", chlist + b"\0")
            + attr("compression", "compression", b"\x03") + attr("dataWindow", "box2i", box)
            + attr("displayWindow", "box2i", box) + attr("lineOrder", "lineOrder", b"\0")
            + attr("pixelAspectRatio", "float", struct.pack("<f", 1))
            + attr("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0))
            + attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    blocks = (height + 15) // 16  # ZIP: 16 lines a block
    table = b"".join(struct.pack("<Q", len(head) + 8 * blocks + 100 * i) for i in range(blocks))
    return head + table


def run_measured(*args, timeout=120):
    """run(), with the peak resident memory of the command in bytes."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    rc, out, err = run(*args, timeout=timeout)
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    return rc, err, 1024 * peak if peak > before else 0


class FilesASceneNames(Base):
    """Meshes and environment maps are inputs like the scene: regular files only, refused at
    once; headers cannot ask for memory they do not hold; UTF-8 paths."""

    def scene(self, line, name="s.scene"):
        return self.put(name, read_text(SPHERE) + line + "\n")

    def render(self, scene, *extra):
        return run("render", scene, "-o", self.path("x.exr"), "--width", "8", "--height", "8",
                   "--no-preview", *extra)

    def test_mesh_and_map_that_are_not_regular_files(self):
        fifo = self.path("fifo")
        os.mkfifo(fifo)
        os.mkdir(self.path("dir"))
        for target, kind in ((fifo, "is a FIFO, not a regular file"),
                             (self.path("dir"), "is a directory, not a file"),
                             ("/dev/zero", "is a character device, not a regular file")):
            for line in ("mesh file=%s material=plastic" % target,
                         "light environment file=%s" % target):
                scene = self.scene(line)
                for args in (["render", scene, "-o", self.path("x.exr")],
                             ["export", "--cycles", scene, "--mode", "closure", "-o",
                              self.path("x.py")]):
                    rc, _, err = run(*args, timeout=30)  # a blocked open would time out
                    self.assertEqual(rc, 1, (args, err))
                    self.assertIn(kind, err)
                    self.assertEqual(err.count("\n"), 1, err)
        self.assertFalse(os.path.exists(self.path("x.exr")) or os.path.exists(self.path("x.py")))

    def test_an_image_header_cannot_ask_for_memory(self):
        """8192 x 8192 x 12 channels over 4.6 KB: only the 3 channels used are read, in strips,
        so the read fails at the first missing rows (it allocated 3.3 GB before); a header over
        the reader's 1 GiB limit is refused before any read."""
        self.put("big.exr", exr_header_only(8192, 8192, 12))
        self.put("huge.exr", exr_header_only(16384, 16384, 3))
        scene = self.scene("light environment file=big.exr")
        for args in (["compare", self.path("big.exr"), self.path("big.exr")],
                     ["render", scene, "-o", self.path("x.exr"), "--no-preview"]):
            rc, err, peak = run_measured(*args)
            self.assertNotEqual(rc, 0, err)
            self.assertIn("big.exr", err)
            self.assertEqual(err.count("\n"), 1, err)
            self.assertLess(peak, 1 << 30, "%s: peak memory %d bytes" % (args[0], peak))
        self.fails(2, ["compare", self.path("huge.exr"), self.path("huge.exr")],
                   "huge.exr: 16384x16384 pixels x 3 channels as 32-bit floats need 3221225472 "
                   "bytes, over the image reader's limit of 1073741824 bytes")

    def test_utf8_paths_and_obj_details(self):
        obj = "v 0 0 0\nv 1 0 0\nv 0 1e-310 1\nf 1 2 3\n"
        self.put("t\u00e9.obj", "\ufeff" + obj)  # a byte-order mark, a subnormal
        scene = self.scene("mesh file=t\u00e9.obj material=plastic")
        rc, _, err = self.render(scene)
        self.assertEqual(rc, 0, err)
        rc, out, err = run("export", "--cycles", scene, "-o", self.path("x.py"))
        self.assertEqual(rc, 0, err)
        self.assertIn("t\\u00e9.obj", read_text(self.path("x.py")))  # an ASCII literal of the name
        self.put("long.obj", "v 0 0 0." + "0" * 300 + "\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        self.fails(1, ["render", self.scene("mesh file=long.obj material=plastic"), "-o",
                       self.path("x.exr")], "long.obj:1: v: a number of 302 characters "
                   "(at most 255)")
        bad = self.put("bad.scene", (read_text(SPHERE) + "mesh file=t\xe9.obj material=plastic\n")
                       .encode("latin-1"))
        self.fails(1, ["render", bad, "-o", self.path("x.exr")], "bad.scene:9: file= holds byte "
                   "0xe9: a path is UTF-8 text without control characters")

    def test_messages_state_the_rule(self):
        self.fails(1, ["render", self.scene("light point position=2e6,0,0"), "-o",
                       self.path("x.exr")], "position needs X,Y,Z (three finite numbers, |x| <= 1e+06)")
        self.fails(1, ["render", self.scene("light sphere center=0,0,3 radius=2e6"), "-o",
                       self.path("x.exr")], "radius needs a finite number with |x| <= 1e+06, got '2e6'")
        self.fails(1, ["render", self.scene("light rect center=0,3,0 u=1e-12,0,0 v=0,0,1"),
                       "-o", self.path("x.exr")], "rect light edges u and v must each be longer "
                   "than 1e-9")
        rc, out, err = run("sample", "lambert", "--wo", "1e308,0,1e308", "-n", "2")
        self.assertEqual(rc, 0, err)
        rc, out, err = run("eval", "lambert", "--wi", "1e308,0,1e308", "--wo", "0,0,1e-300")
        self.assertIn(b"f_r = 0.3183098862", out)
        for args in (["eval", "lambert", "--wi", "0,0,1", "--wo", "0,0,1", "--wi", "1,0,1"],
                     ["render", SPHERE, "-o", "a.exr", "-o", "b.exr"],
                     ["advise", "gold", "--goal", "photoreal", "--goal", "performance"]):
            self.fails(2, args, "is given twice (only --set and --materials repeat")
        self.fails(2, ["eval", "lambert", "--wi", "0,0,1", "--wo", "0,0,1", "--set", "kd=0.5",
                       "--set", "kd=0.4"], "kd=0.4 is given twice")
        rc, _, err = run("eval", "lambert_fresnel", "--wi", "0,0,1", "--wo", "0,0,1", "--set",
                         "kd=0.5", "--set", "f0=0.4")
        self.assertEqual(rc, 0, err)

    def test_sockets_controls_and_truncated_pixels(self):
        sock = socket.socket(socket.AF_UNIX)
        sock.bind(self.path("sock"))
        try:
            for line in ("mesh file=sock material=plastic", "light environment file=sock"):
                self.fails(1, ["render", self.scene(line), "-o", self.path("x.exr")],
                           "is a socket, not a regular file")
        finally:
            sock.close()
        self.fails(1, ["render", self.scene("mesh file=a\u0085.obj material=plastic"), "-o",
                       self.path("x.exr")], "a path is UTF-8 text without control characters")
        # a TIFF cut in its pixels: the reader fills what it could not read and says so only
        # in its error state
        rc, _, err = run("render", SPHERE, "-o", self.path("full.tif"), "--width", "16",
                         "--height", "16", "--no-preview")
        self.assertEqual(rc, 0, err)  # a TIFF is written (libtiff's Exif directory is not)
        with open(self.path("full.tif"), "rb") as f:
            data = f.read()
        self.put("cut.tif", data[:len(data) // 2])
        self.fails(2, ["compare", self.path("full.tif"), self.path("cut.tif")], "cut.tif: ")


if __name__ == "__main__":
    unittest.main()
