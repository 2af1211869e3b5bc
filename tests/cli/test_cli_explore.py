"""CLI tests of `abrdf explore` (run by CTest with the path of the abrdf binary): the folder it
finds, serving it over HTTP (the WebAssembly module with its MIME type), and the errors (a
folder without the explorer, a port in use, a bad port), each one line and a non-zero exit.
The page itself is tested in a browser by tests/web."""
import os
import socket
import subprocess
import sys
import time
import unittest
import urllib.request

from clitest import TempDirCase, checked_stderr

ABRDF = None


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class ExploreTest(TempDirCase):
    def setUp(self):
        super().setUp()
        self.web = os.path.join(self.dir, "web")
        os.mkdir(self.web)
        self.put("web/index.html", "<!doctype html><title>explorer</title>\n")
        self.put("web/abrdf_wasm.wasm", b"\0asm\1\0\0\0")
        self.env = dict(os.environ, ABRDF_WEB_DIR=self.web, ABRDF_PYTHON=sys.executable)

    def run_explore(self, *args, env=None, code=0):
        p = subprocess.run([ABRDF, "explore", *args], capture_output=True, timeout=30,
                           env=env or self.env)
        err = checked_stderr(p)
        self.assertEqual(p.returncode, code, err)
        return p.stdout.decode(), err

    def test_dir(self):
        out, _ = self.run_explore("--dir")
        self.assertEqual(out.strip(), self.web)

    def test_serves_the_folder(self):
        port = free_port()
        p = subprocess.Popen([ABRDF, "explore", "--port", str(port)], env=self.env,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        try:
            url = f"http://127.0.0.1:{port}/"
            for _ in range(100):
                try:
                    with urllib.request.urlopen(url + "index.html", timeout=2) as r:
                        page = r.read().decode()
                    break
                except OSError:
                    time.sleep(0.1)
            else:
                self.fail("abrdf explore did not answer on " + url)
            self.assertIn("<title>explorer</title>", page)
            with urllib.request.urlopen(url + "abrdf_wasm.wasm", timeout=2) as r:
                self.assertEqual(r.headers.get_content_type(), "application/wasm")
                self.assertEqual(r.read(), b"\0asm\1\0\0\0")
        finally:
            p.terminate()
            out, _ = p.communicate(timeout=10)
        self.assertIn(f"http://127.0.0.1:{port}/", out.decode())

    def test_port_in_use(self):
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            s.listen(1)
            port = s.getsockname()[1]
            _, err = self.run_explore("--port", str(port), code=1)
        self.assertEqual(len(err.strip().splitlines()), 1, err)
        self.assertIn(f"127.0.0.1:{port}", err)
        self.assertIn("--port", err)

    def test_bad_arguments(self):
        for args, words in ((["--port", "0"], "--port 0"), (["--port", "http"], "--port http"),
                            (["--port"], "--port needs"), (["--serve"], "unknown argument")):
            _, err = self.run_explore(*args, code=2)
            self.assertEqual(len(err.strip().splitlines()), 1, err)
            self.assertIn(words, err)

    def test_folder_without_the_explorer(self):
        os.remove(os.path.join(self.web, "abrdf_wasm.wasm"))
        _, err = self.run_explore("--dir", code=1)
        self.assertEqual(len(err.strip().splitlines()), 1, err)
        self.assertIn(self.web, err)


if __name__ == "__main__":
    ABRDF = sys.argv.pop(1)
    unittest.main()
