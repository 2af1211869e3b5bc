#!/usr/bin/env python3
"""What WebAssembly SIMD128 pays in the browser explorer (docs/EXPLORER.md, "Speed"): the
256 x 256 lit sphere of every closed-form model, and f_r of 65536 direction pairs through the
float batch path (aw_eval on pairs already in the module's memory), computed by the module
built with -msimd128
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
  const n = 1 << 16, mod = a.m;
  const pi = mod._malloc(12 * n), po = mod._malloc(12 * n), pf = mod._malloc(12 * n);
  for (let k = 0; k < n; ++k) {  // fixed pairs over the upper hemisphere
    const t1 = Math.acos(1 - (k % 97) / 97), p1 = 2 * Math.PI * (k % 89) / 89;
    const t2 = Math.acos(1 - (k % 83) / 83), p2 = 2 * Math.PI * (k % 79) / 79;
    const i = (pi >> 2) + 3 * k, o = (po >> 2) + 3 * k;
    mod.HEAPF32[i] = Math.sin(t1) * Math.cos(p1); mod.HEAPF32[i + 1] = Math.sin(t1) * Math.sin(p1);
    mod.HEAPF32[i + 2] = Math.cos(t1);
    mod.HEAPF32[o] = Math.sin(t2) * Math.cos(p2); mod.HEAPF32[o + 1] = Math.sin(t2) * Math.sin(p2);
    mod.HEAPF32[o + 2] = Math.cos(t2);
  }
  const fastest = (runs, f) => {
    let best = Infinity;
    for (let k = 0; k < runs; ++k) {
      const t = performance.now();
      f();
      best = Math.min(best, performance.now() - t);
    }
    return best;
  };
  const out = {};
  for (let pass = 0; pass < 2; ++pass) {
    for (const m of a.models()) {
      if (!m.closedForm || !a.setModel(0, m.name, {}).ok) continue;
      const r = pass ? runs : 1;
      out[m.name] = [fastest(r, () => a.sphereRows(0, 256, light, 0, 256, 1)),
                     fastest(r, () => mod._aw_eval(0, pi, po, n, pf)) / n * 1e6];
    }
  }
  [pi, po, pf].forEach((p) => mod._free(p));
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
    print(f"# fastest of {args.runs} runs, Chromium {version}: the 256x256 lit sphere (ms) and "
          f"f_r of 65536 direction pairs (aw_eval, ns per pair)")
    # the command, less the scratch directory (where the second module was built)
    print(f"# tools/bench/web_simd.py {args.web} --runs {args.runs}")
    print(f"{'model':24s} {'sphere simd128':>14s} {'scalar':>7s} {'ratio':>6s}   "
          f"{'eval simd128':>12s} {'scalar':>7s} {'ratio':>6s}")
    for m, (ts, es) in times["simd128"].items():
        tc, ec = times["scalar"][m]
        print(f"{m:24s} {ts:14.2f} {tc:7.2f} {tc / ts:6.2f}   {es:12.2f} {ec:7.2f} "
              f"{ec / es:6.2f}")
    if tmp:
        tmp.cleanup()


if __name__ == "__main__":
    main()
