#!/usr/bin/env python3
"""test_cli_eval_pairs.py - `abrdf eval MODEL --pairs FILE|-`: many direction pairs in one run
give exactly the one-pair answers (text and JSON), with the normal, tangent and --set of a
one-pair run; a bad line is one `abrdf eval: FILE:LINE: problem` line, exit 1 and nothing on
stdout.

    python3 test_cli_eval_pairs.py PATH/TO/abrdf        (CTest passes the built binary)

Python 3 standard library only."""
import json
import os
import random
import subprocess
import sys
import unittest

from clitest import TempDirCase, checked_stderr

ABRDF = None  # set from argv in main

# (model, extra options): isotropic and anisotropic lobes, a tangent-dependent hair model,
# a layered model, each with a frame or parameters a one-pair run takes the same way.
CASES = [
    ("lambert", []),
    ("disney_specular", ["--set", "r=0.3"]),
    ("disney_specular_aniso", ["--normal", "0.1,0.2,1", "--tangent", "1,1,0", "--set", "r=0.4",
                               "--set", "anisotropic=0.8", "--set", "f0=0.9,0.6,0.3"]),
    ("kajiya_kay", ["--tangent", "1,0.5,0", "--set", "n=20"]),
    ("belcour", []),
]


def run(args, stdin=None):
    p = subprocess.run([ABRDF] + [str(a) for a in args], input=stdin, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, timeout=120)
    return p.returncode, p.stdout.decode(), checked_stderr(p)


def random_pairs(rng, count):
    """count pairs in the upper hemisphere of z, some of them grazing, not unit length."""
    pairs = []
    for k in range(count):
        v = []
        for _ in range(2):
            z = 1e-3 if k % 5 == 0 else rng.uniform(0.05, 1.0)
            v += [rng.uniform(-1, 1), rng.uniform(-1, 1), z * rng.uniform(0.5, 3.0)]
        pairs.append(v)
    return pairs


def one_pair(model, extra, pair):
    rc, out, err = run(["eval", model, "--wi", ",".join(repr(x) for x in pair[:3]),
                        "--wo", ",".join(repr(x) for x in pair[3:])] + extra + ["--json"])
    assert rc == 0, err
    return json.loads(out)["f_r"]


class PairsEqualOnePair(TempDirCase):
    def test_every_case_text_and_json(self):
        rng = random.Random(7)
        for model, extra in CASES:
            with self.subTest(model=model):
                pairs = random_pairs(rng, 12)
                lines = ["# wix wiy wiz wox woy woz", ""]
                lines += [" ".join(repr(x) for x in p) + ("  # trailing" if i == 3 else "")
                          for i, p in enumerate(pairs)]
                path = self.put(model + ".txt", "\n".join(lines) + "\n")
                expect = [one_pair(model, extra, p) for p in pairs]
                rc, out, err = run(["eval", model, "--pairs", path] + extra)
                self.assertEqual((rc, err), (0, ""))
                got = [l.split() for l in out.splitlines()]
                self.assertEqual(got, [["%.9g" % c for c in f] for f in expect])
                rc, out, err = run(["eval", model, "--pairs", path, "--json"] + extra)
                self.assertEqual((rc, err), (0, ""))
                self.assertEqual(json.loads(out), expect)

    def test_stdin_and_crlf(self):
        data = b"0.3 0 1 -0.2 0.1 1\r\n\r\n  -0.5\t0 1  0.5 0 1  \r\n"
        rc, out, err = run(["eval", "disney_specular", "--pairs", "-", "--set", "r=0.3"], data)
        self.assertEqual((rc, err), (0, ""))
        self.assertEqual(out.splitlines()[0].split(),
                         ["%.9g" % c for c in one_pair("disney_specular", ["--set", "r=0.3"],
                                                       [0.3, 0, 1, -0.2, 0.1, 1])])
        self.assertEqual(len(out.splitlines()), 2)

    def test_no_pairs(self):
        path = self.put("empty.txt", "# nothing\n\n")
        self.assertEqual(run(["eval", "lambert", "--pairs", path]), (0, "", ""))
        rc, out, err = run(["eval", "lambert", "--pairs", path, "--json"])
        self.assertEqual((rc, json.loads(out), err), (0, [], ""))


class BadLines(TempDirCase):
    BAD = [
        ("0 0 1 0 0", "5 numbers, expected six"),
        ("0 0 1 0 0 1 2", "more than six numbers"),
        ("0 0 1 0 abc 1", "'abc' is not a finite number (number 5 of six)"),
        ("0 0 nan 0 0 1", "'nan' is not a finite number"),
        ("0 0 1 0 0 1e999", "'1e999' is not a finite number"),
        ("0 0 0 0 0 1", "wi 0,0,0 has zero length"),
        ("0 0 1 0 0 0", "wo 0,0,0 has zero length"),
        ("0,0,1,0,0,1", "is not a finite number (number 1 of six)"),
    ]

    def test_bad_line_names_file_and_line(self):
        for line, why in self.BAD:
            with self.subTest(line=line):
                # good lines before the bad one: nothing of them may reach stdout
                path = self.put("bad.txt", "0 0 1 0 0 1\n# c\n\n0.1 0 1 0 0 1\n" + line + "\n")
                rc, out, err = run(["eval", "lambert", "--pairs", path])
                self.assertEqual((rc, out), (1, ""))
                self.assertEqual(err.count("\n"), 1, err)
                self.assertTrue(err.startswith("abrdf eval: %s:5: " % path), err)
                self.assertIn(why, err)

    def test_bad_line_on_stdin(self):
        rc, out, err = run(["eval", "lambert", "--pairs", "-", "--json"], b"0 0 1 0 0 1\n1 2\n")
        self.assertEqual((rc, out), (1, ""))
        self.assertEqual(err, "abrdf eval: stdin:2: 2 numbers, expected six: "
                              "wix wiy wiz wox woy woz\n")

    def test_nul_byte(self):
        path = self.put("nul.txt", b"0 0 1 0 0 1\x00\n")
        rc, out, err = run(["eval", "lambert", "--pairs", path])
        self.assertEqual((rc, out, err), (1, "", "abrdf eval: %s:1: a NUL byte\n" % path))

    def test_missing_file_and_directory(self):
        for path in (self.path("missing.txt"), self.dir):
            rc, out, err = run(["eval", "lambert", "--pairs", path])
            self.assertEqual((rc, out), (1, ""))
            self.assertTrue(err.startswith("abrdf eval: %s: " % path), err)
            self.assertEqual(err.count("\n"), 1, err)

    def check_pair_limit(self):
        """One pair past the limit (2^24) is refused on its line before more memory is taken;
        the stream arrives through a pipe, in chunks, so the test holds only one chunk. The
        Release build runs it (tests/cli/CMakeLists.txt): 0.9 GB of pairs take a minute under
        the sanitizers, for a comparison and a message."""
        limit = 1 << 24
        p = subprocess.Popen([ABRDF, "eval", "lambert", "--pairs", "-"], stdin=subprocess.PIPE,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        chunk = b"0 0 1 0 0 1\n" * (1 << 16)
        try:
            for _ in range(limit // (1 << 16)):
                p.stdin.write(chunk)
            p.stdin.write(b"0 0 1 0 0 1\n")
            p.stdin.close()
        except BrokenPipeError:
            pass
        out, err = p.stdout.read(), p.stderr.read().decode()  # written only at its end
        p.wait(timeout=300)
        p.stdout.close()
        p.stderr.close()
        self.assertEqual(p.returncode, 1, err)
        self.assertEqual(out, b"")
        self.assertIn(f"stdin:{limit + 1}: more than {limit} direction pairs", err)

    if os.environ.get("ABRDF_SANITIZE") != "1":
        test_pair_limit = check_pair_limit

    def test_usage_errors(self):
        path = self.put("ok.txt", "0 0 1 0 0 1\n")
        for args, why in [
            (["--pairs", path, "--wi", "0,0,1"], "--pairs and --wi"),
            (["--pairs"], "--pairs needs a file"),
            (["--pairs", path, "--set", "r=7"], "'r'"),
        ]:
            with self.subTest(args=args):
                rc, out, err = run(["eval", "disney_specular"] + args)
                self.assertEqual((rc, out), (2, ""))
                self.assertIn(why, err)


def main():
    global ABRDF
    if len(sys.argv) < 2 or not os.access(sys.argv[1], os.X_OK):
        sys.exit("usage: test_cli_eval_pairs.py PATH/TO/abrdf")
    ABRDF = sys.argv.pop(1)
    unittest.main(verbosity=2)


if __name__ == "__main__":
    main()
