"""Nothing the user had is lost (tools/common/out_file.h): every program that writes a file
writes it whole or not at all, never over one of its inputs, and says why when it cannot.

- inputs as outputs: the same path, ./x, a symbolic link, a hard link, a derived name (the
  preview of -o x.exr) are refused with exit 2 and one line; the input is unchanged;
- a full disk, simulated without root: the file-size limit (RLIMIT_FSIZE, as `ulimit -f`) with
  SIGXFSZ ignored, for every program that writes a file, and /dev/full for every command that
  writes to standard output: exit 1, one line with the reason, the old file untouched, no
  temporary file left;
- a failed second output after a good first one (the render's EXR after its preview): both old
  files untouched;
- everything that can be refused is refused before the work (preview transform, formats,
  directories), leaving old files untouched;
- racing writers to one target end with one whole file from one of them.

Run by CTest with ABRDF (the command), BIN (the build's programs), SCENES and SRC."""
import fcntl
import os
import resource
import signal
import struct
import subprocess
import sys
import threading
import unittest

from clitest import TempDirCase, checked_stderr, read_text

ABRDF = os.environ["ABRDF"]
BIN = os.environ["BIN"]
SCENES = os.environ["SCENES"]
SRC = os.environ["SRC"]
SANITIZED = os.environ.get("ABRDF_SANITIZE") == "1"
SPHERE = os.path.join(SCENES, "sphere.scene")
SMALL = ["--width", "24", "--height", "16"]


def limited(max_bytes):
    """preexec_fn: files may not grow past max_bytes; SIGXFSZ ignored, so writes fail (EFBIG)
    instead of killing the process (what `ulimit -f` with `trap '' XFSZ` does)."""
    def pre():
        resource.setrlimit(resource.RLIMIT_FSIZE, (max_bytes, max_bytes))
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    return pre


def run(*args, limit=None, stdout=None, timeout=600):
    p = subprocess.run(list(args), stdout=stdout if stdout is not None else subprocess.PIPE,
                       stderr=subprocess.PIPE, preexec_fn=limited(limit) if limit else None,
                       timeout=timeout)
    return p.returncode, checked_stderr(p)


def png_size(path):
    """(width, height) from a PNG's IHDR chunk."""
    with open(path, "rb") as f:
        head = f.read(24)
    return struct.unpack(">II", head[16:24])


def exr_size(path):
    """(width, height) from an EXR header's dataWindow attribute."""
    with open(path, "rb") as f:
        head = f.read(4096)
    at = head.index(b"dataWindow\0box2i\0") + len(b"dataWindow\0box2i\0") + 4
    x0, y0, x1, y1 = struct.unpack("<iiii", head[at:at + 16])
    return x1 - x0 + 1, y1 - y0 + 1


def snapshot(directory):
    """Every file of a directory with its bytes: what must not change."""
    out = {}
    for name in sorted(os.listdir(directory)):
        path = os.path.join(directory, name)
        if os.path.isfile(path) and not os.path.islink(path):
            with open(path, "rb") as f:
                out[name] = f.read()
    return out


class Base(TempDirCase):
    def one_line(self, err, *needles):
        self.assertEqual(err.count("\n"), 1, err)
        for n in needles:
            self.assertIn(n, err)

    def assert_untouched(self, before, *extra_ok):
        after = snapshot(self.dir)
        self.assertEqual(sorted(after), sorted(before) + sorted(extra_ok) if extra_ok else
                         sorted(before), "files appeared or vanished (a temporary file left?)")
        for name, data in before.items():
            self.assertEqual(after[name], data, name + " changed")


class InputsAreNeverOutputs(Base):
    """Every way of naming an input as an output is refused (exit 2, one line)."""

    def aliases(self, target):
        """Names for the file `target` (in self.dir): itself, ./x, absolute, a symlink, a hard
        link."""
        os.symlink(os.path.basename(target), self.path("link"))
        os.link(target, self.path("hard"))
        rel = os.path.relpath(target)
        return [target, os.path.join(os.path.dirname(target), ".", os.path.basename(target)),
                os.path.abspath(target), rel if not rel.startswith("..") else target,
                self.path("link"), self.path("hard")]

    def refused(self, args, needle):
        before = snapshot(self.dir)
        rc, err = run(ABRDF, *args)
        self.assertEqual(rc, 2, (args, err))
        self.one_line(err, needle, "nothing was written")
        self.assert_untouched(before)

    def test_export_over_its_scene(self):
        scene = self.put("s.scene", read_text(SPHERE))
        self.refused(["export", "--cycles", scene, "-o", scene], "the scene")
        for name in self.aliases(scene):
            self.refused(["export", "--pov", scene, "-o", name], "the scene")
        glb = self.path("s.glb")  # a glTF file as the scene
        self.assertEqual(run(ABRDF, "export", "--gltf", SPHERE, "-o", glb)[0], 0)
        self.refused(["export", "--gltf", glb, "-o", glb], "the scene")

    def test_export_over_a_materials_file(self):
        mats = self.put("m.csv", read_text(os.path.join(SRC, "data", "materials.csv")))
        self.refused(["export", "--pov", SPHERE, "--materials", mats, "-o", "./" +
                      os.path.relpath(mats)], "--materials file")

    def test_render_over_its_scene_or_through_its_preview(self):
        scene = self.put("view.png", read_text(SPHERE))  # a scene that happens to end in .png
        self.refused(["render", scene, "-o", self.path("view.exr")] + SMALL, "the preview")
        scene2 = self.put("s.scene", read_text(SPHERE))
        os.symlink("s.scene", self.path("alias.png"))
        self.refused(["render", scene2, "-o", self.path("alias.exr")] + SMALL, "the preview")
        self.refused(["render", scene2, "-o", self.path("s.scene"), "--no-preview"] + SMALL,
                     "scene")

    def test_render_over_its_materials_or_config(self):
        mats = self.put("m.exr", "")  # refused before it is read
        self.refused(["render", SPHERE, "--materials", mats, "-o", mats, "--no-preview"],
                     "--materials file")
        config = self.put("c.png", "")  # the preview of -o c.exr would replace the config
        self.refused(["render", SPHERE, "--config", config, "-o", self.path("c.exr")],
                     "--config file")

    def named_files_scene(self):
        """A scene in self.dir naming a mesh file and an environment map (made by a render)."""
        with open(self.path("tri.obj"), "w") as f:
            f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        rc, err = run(ABRDF, "render", SPHERE, "-o", self.path("sky.exr"), "--width", "8",
                      "--height", "4", "--no-preview")
        self.assertEqual(rc, 0, err)
        text = read_text(SPHERE) + ("light environment file=sky.exr intensity=0.5\n"
                                    "mesh file=tri.obj material=plastic\n")
        return self.put("named.scene", text)

    def test_files_a_scene_names_are_never_outputs(self):
        """Every kind of file a scene names (a mesh, an environment map), under each of its
        names (itself, ./x, absolute, a symbolic link, a hard link), as every output of the
        commands that read the scene: render -o, its preview, export --pov/--cycles -o."""
        scene = self.named_files_scene()
        for name, role in (("tri.obj", "mesh file"), ("sky.exr", "environment map")):
            target = self.path(name)
            for alias in self.aliases(target):
                for fmt in ("--pov", "--cycles"):
                    self.refused(["export", fmt, scene, "-o", alias], role)
                # the render's image and preview through links of the names they must have
                for ext, out in ((".exr", "o.exr"), (".png", "p.exr")):
                    link = self.path(out[:-4] + ext)
                    os.symlink(os.path.abspath(alias), link)
                    extra = ["--no-preview"] if ext == ".exr" else []
                    self.refused(["render", scene, "-o", self.path(out)] + SMALL + extra, role)
                    os.unlink(link)
            os.unlink(self.path("link"))
            os.unlink(self.path("hard"))
            if name.endswith(".exr"):
                self.refused(["render", scene, "-o", target, "--no-preview"] + SMALL, role)

    def test_compare_diff_over_an_image(self):
        self.assertEqual(run(ABRDF, "render", SPHERE, "-o", self.path("a.exr"), *SMALL)[0], 0)
        png = self.path("a.png")  # the preview: an 8-bit image compare reads
        for name in self.aliases(png):
            self.refused(["compare", png, self.path("a.exr"), "--diff", name], "same file")


class FullDisk(Base):
    """A file-size limit makes every write fail: the command says so (exit 1, one line with
    the reason) and the file it would have replaced is untouched, with no temporary file
    left beside it."""

    def fails_whole(self, args, target, limit=64, rc_expected=1, named=None):
        self.put(os.path.basename(target), b"the old content\n")
        before = snapshot(self.dir)
        rc, err = run(*args, limit=limit)
        self.assertEqual(rc, rc_expected, (args, err))
        # The last line (calibrate and bench print progress before it) names the file and
        # the reason.
        last = err.rstrip("\n").split("\n")[-1]
        self.assertIn(named or os.path.basename(target), last, err)
        self.assertIn("File too large", last, err)
        self.assert_untouched(before)

    def test_render(self):
        # The preview is written first: it is the one that fails.
        self.fails_whole([ABRDF, "render", SPHERE, "-o", self.path("x.exr")] + SMALL,
                         self.path("x.exr"), named="x.png")
        self.fails_whole([ABRDF, "render", SPHERE, "-o", self.path("x.exr"), "--no-preview"] +
                         SMALL, self.path("x.exr"))

    def test_compare_diff(self):
        self.assertEqual(run(ABRDF, "render", SPHERE, "-o", self.path("a.exr"), "--no-preview",
                             *SMALL)[0], 0)
        self.fails_whole([ABRDF, "compare", self.path("a.exr"), self.path("a.exr"), "--diff",
                          self.path("heat.png")], self.path("heat.png"), rc_expected=2)

    def test_export_pov_and_cycles(self):
        for fmt, name in (("--pov", "x.pov"), ("--cycles", "x.py"), ("--gltf", "x.gltf"),
                          ("--gltf", "x.glb")):
            self.fails_whole([ABRDF, "export", fmt, SPHERE, "-o", self.path(name)],
                             self.path(name), limit=1000)

    def test_calibrate(self):
        self.fails_whole([ABRDF, "calibrate", "--quick", "--reps", "1", "--pairs", "16", "-o",
                          self.path("costs.txt")], self.path("costs.txt"))

    def test_bench_plot(self):
        self.fails_whole([ABRDF, "bench", "--quick", "--size", "8", "--reps", "1", "--plot",
                          self.path("p.svg")], self.path("p.svg"), limit=1000)

    def test_generators(self):
        self.fails_whole([os.path.join(BIN, "fit_fkub"), self.path("fkub.c")],
                         self.path("fkub.c"), limit=1000)
        self.fails_whole([os.path.join(BIN, "gen_belcour_tables"), "--order", "2",
                          self.path("belcour.c")], self.path("belcour.c"), limit=1000)
        if not SANITIZED:  # minutes under the sanitizers (generated_files_current skips it too)
            self.fails_whole([os.path.join(BIN, "gen_hair_tables"), self.path("hair.c")],
                             self.path("hair.c"), limit=1000)
            self.gen_tables_whole()

    def gen_tables_whole(self):
        """tools/gen/gen_tables.py writes its eleven files whole or not at all: with a 1000-byte
        file limit it fails on the first table, one line naming it, and the tree it was to
        write under (--out) keeps every old file and gains none."""
        rels = ["libabrdf/src/kernels/fkub_table.c", "libabrdf/src/hair/hair_tables.c",
                "libabrdf/src/layered/belcour_tables.c", "scenes/teapot.obj",
                "povray_macros/abrdf_params.inc", "povray_macros/abrdf_belcour_tables.inc",
                "povray_macros/abrdf_huang_tables.inc", "osl/abrdf_meta.h", "osl/abrdf_fkub.h",
                "osl/abrdf_belcour_tables.h", "osl/abrdf_hair_tables.h"]
        tree = self.path("tree")
        for rel in rels:
            os.makedirs(os.path.dirname(os.path.join(tree, rel)), exist_ok=True)
            with open(os.path.join(tree, rel), "w") as f:
                f.write("the old content\n")

        def files():
            return sorted(os.path.relpath(os.path.join(d, n), tree)
                          for d, _, names in os.walk(tree) for n in names)

        before = files()
        gen = os.path.join(SRC, "tools", "gen", "gen_tables.py")
        rc, err = run(sys.executable, "-B", gen, BIN, "--out", tree, limit=1000)
        self.assertEqual(rc, 1, err)
        self.assertEqual(err.count("\n"), 1, err)
        self.assertIn("File too large", err)
        self.assertTrue(any(os.path.basename(r) in err for r in rels), err)
        self.assertEqual(files(), before, "files appeared or vanished")
        for rel in rels:
            with open(os.path.join(tree, rel)) as f:
                self.assertEqual(f.read(), "the old content\n", rel)
        # and without the limit it writes them all, as the tree has them
        rc, err = run(sys.executable, "-B", gen, BIN, "--out", tree)
        self.assertEqual(rc, 0, err)
        for rel in rels:
            with open(os.path.join(tree, rel)) as f, open(os.path.join(SRC, rel)) as g:
                self.assertEqual(f.read(), g.read(), rel)

    def test_standard_output_on_dev_full(self):
        """Every command that prints: a failed write to stdout is an error, with its reason."""
        with open("/dev/full", "wb") as full:
            for args in (["models"], ["models", "--json"],
                         ["eval", "lambert", "--wi", "0,0,1", "--wo", "0,0,1"],
                         ["slice", "lambert", "--csv"], ["advise", "gold"],
                         ["advise", "--list", "--json"], ["tables", "2"],
                         ["calibrate", "--quick", "--reps", "1", "--pairs", "16"]):
                rc, err = run(ABRDF, *args, stdout=full)
                self.assertEqual(rc, 1, (args, err))
                self.assertIn("abrdf %s: standard output: No space left on device" % args[0], err)

    def test_dev_full_as_the_output_file(self):
        """A character device is written in place, every write checked."""
        rc, err = run(ABRDF, "export", "--pov", SPHERE, "-o", "/dev/full")
        self.assertEqual(rc, 1, err)
        self.one_line(err, "/dev/full: write failed: No space left on device")


class WholeOrNothing(Base):
    def test_failed_second_output_leaves_both_old_files(self):
        """The preview is written first and fits under the limit, the EXR does not: neither
        old file is replaced (both are committed together)."""
        rc, _ = run(ABRDF, "render", SPHERE, "-o", self.path("new.exr"), *SMALL)
        self.assertEqual(rc, 0)
        png, exr = os.path.getsize(self.path("new.png")), os.path.getsize(self.path("new.exr"))
        self.assertLess(png, exr)
        os.remove(self.path("new.png"))
        os.remove(self.path("new.exr"))
        self.put("x.exr", b"old exr")
        self.put("x.png", b"old png")
        before = snapshot(self.dir)
        rc, err = run(ABRDF, "render", SPHERE, "-o", self.path("x.exr"), *SMALL,
                      limit=(png + exr) // 2)
        self.assertEqual(rc, 1, err)
        self.one_line(err, "x.exr: write failed: File too large")
        self.assert_untouched(before)

    def test_refused_before_the_work(self):
        self.put("x.exr", b"old exr")
        self.put("x.png", b"old png")
        before = snapshot(self.dir)
        out = self.path("x.exr")
        for args, needle in (
                (["--display", "nosuch"], "no display 'nosuch'"),
                (["--view", "nosuch"], "no view 'nosuch'"),
                (["--config", self.path("none.ocio")], "none.ocio"),
                (["-o", self.path("x.xyz")], "x.xyz"),
                (["-o", self.path("x.png"), "--no-preview"], "scene-linear"),
                (["-o", self.path("x.png")], "leaves no name for the .png preview"),
                (["-o", self.path("x.sgi")], "cannot encode in memory")):
            a = ["render", SPHERE] + ([] if "-o" in args else ["-o", out]) + SMALL + args
            rc, err = run(ABRDF, *a)
            self.assertEqual(rc, 2, (a, err))
            self.one_line(err, needle)
        self.assert_untouched(before)
        rc, err = run(ABRDF, "render", SPHERE, "-o", self.path("no/such/dir/x.exr"), *SMALL)
        self.assertEqual(rc, 1)
        self.one_line(err, "No such file or directory")
        rc, err = run(ABRDF, "compare", out, out, "--diff", self.path("h.xyz"))
        self.assertEqual(rc, 2)
        self.one_line(err, "h.xyz: not an 8-bit display format")

    def test_failed_export_keeps_the_old_file(self):
        """--native with a point light fails after the scene is read: the old file stays."""
        scene = self.put("p.scene", read_text(SPHERE).replace(
            "light directional direction=-1,1,1", "light point position=-3,3,3"))
        self.assertIn("light point", read_text(scene))
        self.put("x.pov", b"the old export\n")
        before = snapshot(self.dir)
        rc, err = run(ABRDF, "export", "--pov", scene, "--native", "-o", self.path("x.pov"))
        self.assertEqual(rc, 1, err)
        self.one_line(err, "--native")
        self.assert_untouched(before)

    def test_output_modes_follow_the_replaced_file(self):
        self.put("x.pov", b"old")
        os.chmod(self.path("x.pov"), 0o640)
        self.assertEqual(run(ABRDF, "export", "--pov", SPHERE, "-o", self.path("x.pov"))[0], 0)
        self.assertEqual(os.stat(self.path("x.pov")).st_mode & 0o777, 0o640)
        os.symlink("x.pov", self.path("link.pov"))  # a link is written through, and stays
        self.assertEqual(run(ABRDF, "export", "--pov", SPHERE, "-o", self.path("link.pov"))[0], 0)
        self.assertTrue(os.path.islink(self.path("link.pov")))

    def test_racing_writers_leave_one_whole_file(self):
        """Renders of two sizes and exports of two models race to one target, repeatedly:
        every run succeeds and the target is always one whole result."""
        out = self.path("race.exr")
        sizes = [("40", "30"), ("30", "40")]
        refs = []
        for w, h in sizes:
            ref = self.path("ref%sx%s.exr" % (w, h))
            self.assertEqual(run(ABRDF, "render", SPHERE, "-o", ref, "--width", w, "--height", h,
                                 "--no-preview")[0], 0)
            refs.append(ref)
        for _ in range(2):
            procs = [subprocess.Popen([ABRDF, "render", SPHERE, "-o", out, "--width", w,
                                       "--height", h, "--threads", "1"],
                                      stderr=subprocess.PIPE) for w, h in sizes * 2]
            for p in procs:
                _, err = p.communicate()
                self.assertEqual(p.returncode, 0, err)
            same = [run(ABRDF, "compare", ref, out, "--fail", "1e-30")[0] for ref in refs]
            self.assertIn(0, same, "the raced file is none of the renders")
        pov = self.path("race.pov")
        texts = {}
        for model in ("lambert", "blinn_phong"):
            self.assertEqual(run(ABRDF, "export", "--pov", SPHERE, "--model", model, "-o",
                                 self.path(model + ".pov"))[0], 0)
            texts[model] = read_text(self.path(model + ".pov"))
        for _ in range(3):
            procs = [subprocess.Popen([ABRDF, "export", "--pov", SPHERE, "--model", m, "-o", pov])
                     for m in ("lambert", "blinn_phong") * 2]
            for p in procs:
                self.assertEqual(p.wait(), 0)
            self.assertIn(read_text(pov), texts.values())
        self.assertEqual(sorted(f for f in os.listdir(self.dir) if f.startswith(".")), [])

    def test_image_and_preview_are_committed_under_the_directory_lock(self):
        """The EXR and its PNG preview are renamed over their targets under an exclusive lock
        on their directory (flock), which every abrdf command takes the same way: while
        another holder has it, a finished render waits, both targets still absent."""
        out, png = self.path("pair.exr"), self.path("pair.png")
        fd = os.open(self.dir, os.O_RDONLY)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX)
            p = subprocess.Popen([ABRDF, "render", SPHERE, "-o", out] + SMALL,
                                 stderr=subprocess.PIPE)
            with self.assertRaises(subprocess.TimeoutExpired):
                p.wait(timeout=20 if SANITIZED else 5)  # the render itself takes < 1 s
            self.assertFalse(os.path.exists(out) or os.path.exists(png))
        finally:
            os.close(fd)  # releases the lock
        _, err = p.communicate(timeout=60)
        self.assertEqual(p.returncode, 0, err)
        self.assertEqual(exr_size(out), png_size(png))

    def test_racing_renders_leave_an_image_and_preview_of_one_render(self):
        """Renders of two sizes race to one -o: the EXR and its preview always come from the
        same render."""
        out, png = self.path("pair.exr"), self.path("pair.png")
        for _ in range(8):
            procs = [subprocess.Popen([ABRDF, "render", SPHERE, "-o", out, "--width", w,
                                       "--height", h, "--threads", "1"],
                                      stderr=subprocess.PIPE) for w, h in (("40", "30"),
                                                                           ("30", "40")) * 2]
            for p in procs:
                _, err = p.communicate()
                self.assertEqual(p.returncode, 0, err)
            self.assertEqual(exr_size(out), png_size(png))

    def interrupt(self, args, ready, tries, step, message, env=None):
        """`abrdf render ARGS` sent SIGTERM once a file of the directory is `ready` (polled
        `tries` times, `step` seconds apart): it dies of the signal and leaves the directory
        as it was."""
        before = snapshot(self.dir)
        p = subprocess.Popen([ABRDF, "render"] + args, stderr=subprocess.DEVNULL, env=env)
        for _ in range(tries):
            if any(ready(n) for n in os.listdir(self.dir)) or p.poll() is not None:
                break
            threading.Event().wait(step)
        self.assertIsNone(p.poll(), message)
        p.send_signal(signal.SIGTERM)
        p.wait()
        self.assertEqual(p.returncode, -signal.SIGTERM)
        self.assert_untouched(before)

    def test_interrupted_render_leaves_no_temporary_file(self):
        self.put("x.exr", b"old")
        # The temporary files exist from before the render starts.
        self.interrupt([os.path.join(SCENES, "robot.scene"), "-o", self.path("x.exr"), "--spp",
                        "64", "--threads", "1"], lambda n: n.startswith(".x."), 600, 0.05,
                       "the render ended before it could be interrupted")

    def test_a_signal_while_a_temporary_file_is_created_leaves_none(self):
        """The preview's temporary file is held at its creation (slow_create); SIGTERM comes
        then, and may be handled on any thread (OpenImageIO's and Embree's pools exist by
        then): the file is removed all the same."""
        env = dict(os.environ, LD_PRELOAD=os.environ["SLOW_CREATE"], SLOW_CREATE_PREFIX=".x.",
                   SLOW_CREATE_SUFFIX=".png", SLOW_CREATE_SECONDS="1.5")
        if SANITIZED:  # the preload comes before the sanitizer's runtime
            env["ASAN_OPTIONS"] = env.get("ASAN_OPTIONS", "") + ":verify_asan_link_order=0"
        for _ in range(3):
            self.interrupt([SPHERE, "-o", self.path("x.exr"), "--threads", "1"] + SMALL,
                           lambda n: n.startswith(".x.") and n.endswith(".png"), 1200, 0.01,
                           "the render ended before its preview file was created", env)


if __name__ == "__main__":
    unittest.main()
