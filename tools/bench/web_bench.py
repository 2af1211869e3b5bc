#!/usr/bin/env python3
"""What the browser explorer costs (docs/EXPLORER.md, "Speed"), measured in Debian's chromium,
headless, on build/web served from loopback:

  load     navigation start -> explorer.ready (the module loaded and the first sphere
           complete), a fresh page each time, median of --rounds;
  sphere   a full 256x256 sphere in the worker, the step-1 pass only (explorer.timings.sphereMs,
           timed in the worker), for every closed-form model at its defaults, median of
           --rounds renders (the light moved between them);
  whole    the whole progressive render of that change (explorer.timings.renderMs: steps 8,
           4, 2 and 1, the transfers from the worker and the drawing), the same renders;
  polar    the plane-of-incidence curve of model A (explorer.timings.polarMs: api.plane, 181
           angles, on the page's thread), median of the same renders.

With --screenshot FILE it instead writes the README's picture of the whole page (1400 wide): a
material chosen (--material, default terracotta), the budget mode (slight) run, A = its choice
and B = the photoreal reference, the advisor's result and front.

usage: .venv-python/bin/python tools/bench/web_bench.py [BUILD/web] [--rounds 5]
                                                         [--screenshot docs/explorer.png
                                                          [--material NAME]]
"""
import argparse
import os
import statistics
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "tests", "web"))
import webtest  # noqa: E402

# Records when explorer.ready resolves, on the page's clock (0 = navigation start).
READY_HOOK = """
Object.defineProperty(window, 'explorer', {configurable: true, set(v) {
    Object.defineProperty(window, 'explorer', {value: v, writable: true, configurable: true});
    v.ready.then(() => { window.__readyAt = performance.now(); });
}});
"""

TARGETS = {"sphere": 50.0, "polar": 5.0, "load": 1000.0}  # ms (docs/EXPLORER.md)


def open_page(browser, url):
    page = browser.page()
    page.add_init_script(READY_HOOK)
    page.goto(url + "index.html")
    page.evaluate("() => explorer.ready")
    page.wait_for_function("() => window.__readyAt !== undefined")
    page.evaluate("() => explorer.idle()")
    return page


def bench(browser, url, rounds):
    loads = []
    for _ in range(rounds):
        page = open_page(browser, url)
        loads.append(page.evaluate("window.__readyAt"))
        page.close()
    page = open_page(browser, url)
    models = page.evaluate("explorer.api.models().filter((m) => m.closedForm).map((m) => m.name)")
    page.select_option("#model-b", "none")
    rows = []
    for name in models:
        page.select_option("#model-a", name)
        page.evaluate("() => explorer.idle()")
        sphere, whole, polar = [], [], []
        for k in range(rounds):
            page.evaluate("(t) => explorer.setLight(t, 0)", 30 + 5 * k)
            page.evaluate("() => explorer.idle()")
            t = page.evaluate("explorer.timings")
            sphere.append(t["sphereMs"][name])
            whole.append(t["renderMs"])
            polar.append(t["polarMs"])
        rows.append((name, statistics.median(sphere), statistics.median(whole),
                     statistics.median(polar)))
    page.close()
    return statistics.median(loads), rows


def report(load, rows, rounds, chromium):
    print("abrdf explorer speed: %s, headless, median of %d (ms)" % (chromium, rounds))
    print("%-24s %9s %9s %9s" % ("model", "sphere", "whole", "polar"))
    for name, s, w, p in rows:
        marks = "".join(" " + k for k, v in (("sphere>50", s > TARGETS["sphere"]),
                                             ("polar>5", p > TARGETS["polar"])) if v)
        print("%-24s %9.1f %9.1f %9.2f%s" % (name, s, w, p, marks))
    sph = [s for _, s, _, _ in rows]
    who = [w for _, _, w, _ in rows]
    pol = [p for _, _, _, p in rows]
    print("sphere 256x256 (step 1, worker): median %.1f, max %.1f; %d of %d models over %g"
          % (statistics.median(sph), max(sph), sum(s > TARGETS["sphere"] for s in sph),
             len(sph), TARGETS["sphere"]))
    print("whole progressive render (steps 8, 4, 2, 1, transfers, drawing): median %.1f, "
          "max %.1f" % (statistics.median(who), max(who)))
    print("polar (page thread): median %.2f, max %.2f; %d of %d models over %g"
          % (statistics.median(pol), max(pol), sum(p > TARGETS["polar"] for p in pol),
             len(pol), TARGETS["polar"]))
    print("load (navigation start -> explorer.ready): %.0f (target < %g)"
          % (load, TARGETS["load"]))


def screenshot(browser, url, path, material):
    """The page at 1400x1000: the material chosen (photoreal), the budget mode (slight) run,
    then its result's button: A = the budget's choice, B = the photoreal reference."""
    page = open_page(browser, url)
    page.select_option("#goal", "photoreal")
    page.select_option("#material", material)
    page.evaluate("() => explorer.idle()")
    page.select_option("#advise-mode", "budget")
    page.fill("#advise-budget", "slight")
    page.click("#advise-run")
    page.wait_for_function("() => explorer.last.advise !== null", timeout=120000)
    page.evaluate("() => explorer.idle()")
    page.locator("#advise-result button").click()
    page.evaluate("() => explorer.idle()")
    page.screenshot(path=path, full_page=True)
    print("wrote %s: %s, A %s, B %s, NMSE %s (%s)"
          % (path, material, *page.evaluate("explorer.state.models"),
             page.inner_text("#nmse"), page.inner_text("#nmse-class")))
    page.close()


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("web", nargs="?", default=os.path.join(root, "build", "web"))
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--screenshot", metavar="PNG")
    ap.add_argument("--material", default="terracotta", help="for --screenshot")
    a = ap.parse_args()
    os.environ.setdefault("WEB_DIR", a.web)
    os.environ.setdefault("ABRDF", os.path.join(os.path.dirname(a.web), "bin", "abrdf"))
    _, web, chromium, _ = webtest.config("web_bench", webtest.MODULE_FILES + ("index.html",))
    with webtest.Server(web) as server, webtest.Browser(chromium) as browser:
        if a.screenshot:
            screenshot(browser, server.url, a.screenshot, a.material)
        else:
            load, rows = bench(browser, server.url, a.rounds)
            report(load, rows, a.rounds, chromium)
        for e in browser.errors:
            print("web_bench: %s" % e)
    sys.exit(1 if browser.errors else 0)


if __name__ == "__main__":
    main()
