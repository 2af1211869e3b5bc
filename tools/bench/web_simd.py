#!/usr/bin/env python3
"""What WebAssembly SIMD128 pays in the browser explorer (docs/EXPLORER.md, "Speed"): the
256 x 256 lit sphere of every closed-form model rendered by the module built with -msimd128
(the build's web/) and by the same sources built without it (configured and built here in a
scratch directory, -DABRDF_WEB_SIMD=OFF), side by side in one headless Chromium run.

    .venv-python/bin/python tools/bench/web_simd.py build/web [--scratch DIR] [--runs N]

Each time is the fastest of N full renders (the least disturbed by other work on the machine) (sphereRows on the page's main thread, step 1)
after one warm-up pass over every model, so both modules run in the optimising tier. Needs
Debian's chromium and Playwright (scripts/setup_python.sh)."""
import argparse
import functools
import http.server
import os
import subprocess
import sys
import tempfile
import threading

BENCH_PAGE = """<!doctype html><meta charset="utf-8"><title>simd bench</title>
<script src="abrdf_wasm.js"></script><script src="abrdf_api.js"></script>"""

BENCH_JS = """async (runs) => {
  const a = await AbrdfApi.load();
  const light = [0.3, 0.5, 1.0];
  const out = {};
  for (let pass = 0; pass < 2; ++pass) {
    for (const m of a.models()) {
      if (!m.closedForm || !a.setModel(0, m.name, {}).ok) continue;
      const ts = [];
      for (let k = 0; k < (pass ? runs : 1); ++k) {
        const t = performance.now();
        a.sphereRows(0, 256, light, 0, 256, 1);
        ts.push(performance.now() - t);
      }
      ts.sort((x, y) => x - y);
      out[m.name] = ts[0];
    }
  }
  return out;
}"""


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


def serve(directory):
    handler = functools.partial(QuietHandler, directory=directory)
    srv = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=srv.serve_forever, daemon=True).start()
    return srv


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("web", help="the build's web/ folder (built with SIMD128, the default)")
    ap.add_argument("--scratch", help="where to build the module without SIMD128 "
                    "(default: a temporary directory)")
    ap.add_argument("--runs", type=int, default=15)
    args = ap.parse_args()
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        sys.exit("web_simd: Playwright is missing (scripts/setup_python.sh installs it)")
    src = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    tmp = None
    scratch = args.scratch
    if not scratch:
        tmp = tempfile.TemporaryDirectory()
        scratch = tmp.name
    subprocess.run(["cmake", "-S", src, "-B", scratch, "-DCMAKE_BUILD_TYPE=Release",
                    "-DABRDF_WEB_SIMD=OFF", "-DABRDF_BUILD_TESTS=OFF"], check=True,
                   stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", scratch, "--target", "web"], check=True,
                   stdout=subprocess.DEVNULL)
    dirs = {"simd128": os.path.abspath(args.web), "scalar": os.path.join(scratch, "web")}
    times = {}
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium",
                                    args=["--no-sandbox"])
        for name, d in dirs.items():
            srv = serve(d)
            page = browser.new_page()
            page.route("**/bench.html", lambda r: r.fulfill(body=BENCH_PAGE,
                                                            content_type="text/html"))
            page.goto(f"http://127.0.0.1:{srv.server_address[1]}/bench.html")
            times[name] = page.evaluate(BENCH_JS, args.runs)
            srv.shutdown()
        version = browser.version
        browser.close()
    print(f"# 256x256 lit sphere, ms (fastest of {args.runs}), Chromium {version}")
    print(f"# {' '.join(['tools/bench/web_simd.py'] + sys.argv[1:])}")
    print(f"{'model':24s} {'simd128':>8s} {'scalar':>8s} {'scalar/simd':>11s}")
    for m, t in times["simd128"].items():
        s = times["scalar"].get(m)
        print(f"{m:24s} {t:8.2f} {s:8.2f} {s / t if t > 0 else float('nan'):11.2f}")
    if tmp:
        tmp.cleanup()


if __name__ == "__main__":
    main()
