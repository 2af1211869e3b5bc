"""What the browser tests share (imported from the tests' own directory, which Python puts
first on the module path when CTest runs a test script): the prerequisites checked in one
line each, build/web served on a free loopback port from a thread, and Debian's chromium
driven headless by Playwright, with every console error and page error kept.

Configuration comes from the environment CTest sets (tests/web/CMakeLists.txt):
    ABRDF     the built `abrdf` command
    WEB_DIR   the CMake target `web`'s output directory (build/web)
    CHROMIUM  the browser (default /usr/bin/chromium)
    OUT_DIR   where screenshots go (the test's build directory)"""
import functools
import http.server
import json
import os
import subprocess
import sys
import threading

# The files the explorer's contract puts in build/web (tools/web/static/abrdf_api.js).
MODULE_FILES = ("abrdf_wasm.js", "abrdf_wasm.wasm", "abrdf_api.js")

# A page of the test's own, served beside the module: the module alone, without the
# explorer's page (for the numbers).
MODULE_PAGE = (b"<!doctype html><meta charset=utf-8><title>abrdf module</title>"
               b"<link rel=icon href='data:,'>"
               b"<script src=abrdf_wasm.js></script><script src=abrdf_api.js></script>")


def fail(test, message):
    """One clear line and a failing exit: a missing prerequisite fails, it never skips."""
    print("%s: FAIL: %s" % (test, message), flush=True)
    sys.exit(1)


def config(test, pages=MODULE_FILES):
    """(abrdf, web_dir, chromium, out_dir) once every prerequisite is there; else fail()."""
    abrdf = os.environ.get("ABRDF", "")
    web = os.environ.get("WEB_DIR", "")
    chromium = os.environ.get("CHROMIUM", "/usr/bin/chromium")
    out = os.environ.get("OUT_DIR", os.getcwd())
    if not os.access(abrdf, os.X_OK):
        fail(test, "the abrdf command '%s' is not there (set ABRDF; build the abrdf_cli target)"
             % abrdf)
    for name in pages:
        if not os.path.isfile(os.path.join(web, name)):
            fail(test, "%s is missing (build the CMake target web: cmake --build build "
                 "--target web)" % os.path.join(web, name))
    if not os.access(chromium, os.X_OK):
        fail(test, "no browser at %s (Debian's chromium: scripts/setup.sh installs it)"
             % chromium)
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError as e:
        fail(test, "Playwright is not importable from %s (%s; scripts/setup_python.sh "
             "installs it into .venv-python)" % (sys.executable, e))
    return abrdf, web, chromium, out


class _Handler(http.server.SimpleHTTPRequestHandler):
    extensions_map = dict(http.server.SimpleHTTPRequestHandler.extensions_map,
                          **{".wasm": "application/wasm", ".js": "text/javascript"})
    extra = {}  # path -> bytes served from memory (the test's own pages)

    def do_GET(self):
        body = self.extra.get(self.path.split("?")[0])
        if body is None:
            return super().do_GET()
        self.send_response(200)
        self.send_header("Content-Type", "text/html; charset=utf-8")
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)

    def end_headers(self):
        self.send_header("Cache-Control", "no-store")
        super().end_headers()

    def log_message(self, *args):  # quiet: the test prints what matters
        pass


class Server:
    """build/web served on 127.0.0.1, a free port, from a daemon thread; extra pages from
    memory. Use as a context manager; .url is the root URL ending in '/'."""

    def __init__(self, root, extra=None):
        handler = type("Handler", (_Handler,), {"extra": dict(extra or {})})
        self.httpd = http.server.ThreadingHTTPServer(
            ("127.0.0.1", 0), functools.partial(handler, directory=root))
        self.url = "http://127.0.0.1:%d/" % self.httpd.server_address[1]
        self.thread = threading.Thread(target=self.httpd.serve_forever, daemon=True)

    def __enter__(self):
        self.thread.start()
        return self

    def __exit__(self, *exc):
        self.httpd.shutdown()
        self.httpd.server_close()
        self.thread.join()


class Browser:
    """Debian's chromium, headless, by Playwright; .page() opens a page whose console errors
    and page errors are collected in .errors (a test fails on any)."""

    def __init__(self, chromium):
        self.chromium = chromium
        self.errors = []

    def __enter__(self):
        from playwright.sync_api import sync_playwright
        self.pw = sync_playwright().start()
        self.browser = self.pw.chromium.launch(executable_path=self.chromium,
                                               args=["--no-sandbox"], headless=True)
        return self

    def page(self, width=1400, height=1000):
        page = self.browser.new_page(viewport={"width": width, "height": height})
        page.on("console", lambda m: m.type == "error" and self.errors.append(
            "console error: %s" % m.text))
        page.on("pageerror", lambda e: self.errors.append("page error: %s" % e))
        page.set_default_timeout(60000)
        return page

    def __exit__(self, *exc):
        self.browser.close()
        self.pw.stop()


def run_abrdf(abrdf, *args, stdin=None):
    """(returncode, stdout, stderr) of one `abrdf` run."""
    p = subprocess.run([abrdf] + [str(a) for a in args], input=stdin, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, timeout=600)
    return p.returncode, p.stdout.decode(), p.stderr.decode()


def abrdf_json(abrdf, *args):
    rc, out, err = run_abrdf(abrdf, *args)
    assert rc == 0, "abrdf %s: exit %d: %s" % (" ".join(map(str, args)), rc, err.strip())
    return json.loads(out)
