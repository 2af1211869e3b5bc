#!/usr/bin/env python3
"""test_web_page.py - the explorer page (build/web/index.html) in Debian's chromium, driven
as a user drives it, through its ids and window.explorer (docs/EXPLORER.md, "Using the page"):

  - it loads and draws its first complete sphere (explorer.ready) with no console or page
    error, every model in #model-a/#model-b, every material in #material;
  - choosing a material sets model A to the flowchart's choice (`abrdf advise MAT --goal G
    --json`) and lists the trace of both goals;
  - switching models A and B, moving a slider (typing into its field; dragging its range) and
    dragging the light on #light with the mouse: explorer.last.plane equals api.plane for the
    state, and #nmse equals the NMSE of the spheres recomputed from api.sphereRows of both
    slots;
  - bad values (r = 7, r = abc) show a visible .field-error naming the value and the range,
    and the spheres keep their pixels;
  - the advisor (budget slight) names the models `abrdf advise MAT --budget slight --json`
    chooses;
  - a screenshot, web_page.png, goes to the test's build directory.

    ABRDF=build/bin/abrdf WEB_DIR=build/web .venv-python/bin/python test_web_page.py

Missing chromium, Playwright or build/web fail the test with one line (webtest.py)."""
import math
import os
import sys
import time
import traceback

import webtest

TEST = "web_page"
PAGES = webtest.MODULE_FILES + ("index.html", "app.js", "worker.js", "style.css")


class Steps:
    """Prints each step's name with the seconds the one before took (what a slow run spent)."""

    def __init__(self):
        self.name, self.t0 = None, time.monotonic()

    def __call__(self, name):
        now = time.monotonic()
        if self.name:
            print("%-40s %6.1f s" % (self.name, now - self.t0), flush=True)
        self.name, self.t0 = name, now


def check(cond, message):
    if not cond:
        raise AssertionError(message)


def wait_idle(page):
    page.evaluate("() => explorer.idle()")


def plane_matches(page):
    """explorer.last.plane equals api.plane(0, theta_i, count) for the page's state (both from
    the same module: exactly equal)."""
    r = page.evaluate("""() => {
        const last = explorer.last.plane, n = last.thetaO.length;
        const ref = explorer.api.plane(0, explorer.state.light.theta, n);
        let worst = 0;
        for (let k = 0; k < n; k++) worst = Math.max(worst, Math.abs(last.thetaO[k] - ref.thetaO[k]));
        for (let k = 0; k < 3 * n; k++) worst = Math.max(worst, Math.abs(last.f[k] - ref.f[k]));
        return {n, worst, finite: Array.from(last.f).every(Number.isFinite)};
    }""")
    check(r["n"] > 1 and r["finite"], "explorer.last.plane: %r" % r)
    check(r["worst"] == 0, "explorer.last.plane differs from api.plane by %g" % r["worst"])


def nmse_matches(page):
    """#nmse and explorer.last.nmse against the NMSE of api.sphereRows of slots 0 and 1."""
    r = page.evaluate("""() => {
        const s = explorer.state, api = explorer.api;
        const t = s.light.theta * Math.PI / 180, f = s.light.phi * Math.PI / 180;
        const light = [Math.sin(t) * Math.cos(f), Math.sin(t) * Math.sin(f), Math.cos(t)];
        const a = api.sphereRows(0, 256, light, 0, 256, 1);
        const b = api.sphereRows(1, 256, light, 0, 256, 1);
        let num = 0, den = 0;
        for (let i = 0; i < a.length; i++) { num += (a[i] - b[i]) ** 2; den += b[i] ** 2; }
        return {nmse: num / den, api: api.nmse(a, b), last: explorer.last.nmse,
                cls: explorer.last.cls, text: document.getElementById('nmse').textContent,
                clsText: document.getElementById('nmse-class').textContent};
    }""")
    ref = r["nmse"]
    check(math.isfinite(ref), "NMSE from sphereRows: %r" % r)
    check(abs(r["last"] - ref) <= 1e-6 * ref + 1e-12,
          "explorer.last.nmse %r, NMSE of sphereRows %r" % (r["last"], ref))
    check(abs(r["api"]["nmse"] - ref) <= 1e-6 * ref + 1e-12, "api.nmse %r vs %r" % (r["api"], ref))
    shown = float(r["text"])
    check(abs(shown - ref) <= 5e-3 * ref + 1e-12, "#nmse shows %r, NMSE %r" % (r["text"], ref))
    check(r["clsText"] == r["api"]["cls"] == r["cls"],
          "#nmse-class %r, api.nmse class %r" % (r["clsText"], r["api"]["cls"]))
    return ref


def keep_sphere_pixels(page):
    """Keeps the pixels of #sphere-a and #sphere-b in the page (window.__kept)."""
    page.evaluate("""() => { window.__kept = ['sphere-a', 'sphere-b'].map((id) => {
        const c = document.getElementById(id);
        return c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    }); }""")


def changed_sphere_pixels(page):
    """How many bytes of the spheres' pixels differ from the kept ones."""
    return page.evaluate("""() => ['sphere-a', 'sphere-b'].reduce((n, id, s) => {
        const c = document.getElementById(id);
        const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        for (let i = 0; i < d.length; i++) n += d[i] !== window.__kept[s][i];
        return n;
    }, 0)""")


def field(page, slot, name, comp=None):
    sel = '#params-%s input.num[data-param="%s"]' % ("ab"[slot], name)
    if comp is not None:
        sel += '[data-comp="%d"]' % comp
    return page.locator(sel)


def type_value(page, slot, name, text):
    """Fills a parameter's text field and commits it as a user does (Enter: change)."""
    f = field(page, slot, name)
    f.fill(text)
    f.dispatch_event("input")
    f.dispatch_event("change")


def field_error(page, slot, name):
    el = page.locator('#params-%s .field-error[data-param="%s"]' % ("ab"[slot], name))
    return el.inner_text().strip() if el.is_visible() else ""


def run(page, url, abrdf, out_dir):
    step = Steps()
    step("load, explorer.ready, idle")
    page.goto(url + "index.html")
    page.evaluate("() => explorer.ready")
    wait_idle(page)
    api_models = page.evaluate("explorer.api.models().map((m) => m.name)")
    options_a = page.eval_on_selector_all("#model-a option", "os => os.map((o) => o.value)")
    options_b = page.eval_on_selector_all("#model-b option", "os => os.map((o) => o.value)")
    check(options_a == api_models, "#model-a lists %r, the module %r" % (options_a, api_models))
    check(options_b == ["none"] + api_models, "#model-b's options: %r" % options_b)
    mats = page.eval_on_selector_all("#material option", "os => os.map((o) => o.value)")
    check(len(mats) == 65 and "gold" in mats, "#material: %d options" % len(mats))

    step("material gold, photoreal")
    # A material: model A is the flowchart's choice for the goal; the traces of both goals.
    page.select_option("#goal", "photoreal")
    page.select_option("#material", "gold")
    wait_idle(page)
    for goal in ("performance", "photoreal"):
        cli = webtest.abrdf_json(abrdf, "advise", "gold", "--goal", goal, "--json")
        items = page.locator("#trace-%s li" % goal).all_inner_texts()
        texts = [s["text"] for s in cli["trace"]]
        check(items[:len(texts)] == texts, "#trace-%s %r, the command's %r" % (goal, items, texts))
    cli = webtest.abrdf_json(abrdf, "advise", "gold", "--goal", "photoreal", "--json")
    state = page.evaluate("explorer.state")
    check(state["models"][0] == cli["specular"],
          "model A %r after choosing gold, the flowchart's %r" % (state["models"][0],
                                                                   cli["specular"]))
    check(page.locator("#model-a").input_value() == cli["specular"], "#model-a not updated")
    r_text = field(page, 0, "r").input_value()
    check(float(r_text) == cli["params"]["r"], "A's r field %r, the material's %r"
          % (r_text, cli["params"]["r"]))
    plane_matches(page)
    # The other goal re-runs the flowchart: A is the performance choice's specular lobe.
    page.select_option("#goal", "performance")
    wait_idle(page)
    cli = webtest.abrdf_json(abrdf, "advise", "gold", "--goal", "performance", "--json")
    model_a = page.evaluate("explorer.state.models[0]")
    check(model_a == (cli["specular"] or cli["diffuse"]),
          "model A %r for gold, performance; the flowchart's %r + %r"
          % (model_a, cli["diffuse"], cli["specular"]))
    page.select_option("#goal", "photoreal")
    wait_idle(page)
    plane_matches(page)

    step("models A and B")
    # Models A and B switched by their selects.
    page.select_option("#model-a", "disney_specular")
    page.select_option("#model-b", "cook_torrance")
    wait_idle(page)
    state = page.evaluate("explorer.state")
    check(state["models"] == ["disney_specular", "cook_torrance"], "models %r" % state["models"])
    plane_matches(page)
    nmse0 = nmse_matches(page)

    step("slider r: typed, dragged")
    # A slider by its text field, then by dragging its range.
    type_value(page, 0, "r", "0.35")
    wait_idle(page)
    check(page.evaluate("explorer.state.params[0].r") == 0.35, "typing r = 0.35 did not set it")
    check(field_error(page, 0, "r") == "", "a .field-error after a valid value")
    plane_matches(page)
    nmse1 = nmse_matches(page)
    check(nmse1 != nmse0, "the NMSE did not change with r")
    rng = page.locator('#params-a input[type="range"][data-param="r"]')
    box = rng.bounding_box()
    page.mouse.move(box["x"] + 2, box["y"] + box["height"] / 2)
    page.mouse.down()
    page.mouse.move(box["x"] + 0.7 * box["width"], box["y"] + box["height"] / 2, steps=5)
    page.mouse.up()
    wait_idle(page)
    r_dragged = page.evaluate("explorer.state.params[0].r")
    check(abs(r_dragged - 0.7) < 0.1, "dragging r's range to 70%% set r = %r" % r_dragged)
    check(float(field(page, 0, "r").input_value()) == r_dragged, "r's field not updated")
    plane_matches(page)
    nmse_matches(page)

    step("light dragged, setLight")
    # The light dragged on #light: theta_i follows, and #theta-i mirrors it.
    light = page.locator("#light").bounding_box()
    cx, cy = light["x"] + light["width"] / 2, light["y"] + light["height"] / 2
    page.mouse.move(cx, cy)
    page.mouse.down()
    page.mouse.move(cx + 0.3 * light["width"], cy - 0.1 * light["height"], steps=6)
    page.mouse.up()
    wait_idle(page)
    st = page.evaluate("explorer.state.light")
    check(20 < st["theta"] < 89 and 0 < st["phi"] < 90, "the light after the drag: %r" % st)
    check(int(page.locator("#theta-i").input_value()) == round(st["theta"]),
          "#theta-i %r, theta %r" % (page.locator("#theta-i").input_value(), st["theta"]))
    plane_matches(page)
    nmse_matches(page)
    page.evaluate("explorer.setLight(30, 0)")
    wait_idle(page)
    check(page.evaluate("explorer.state.light") == {"theta": 30, "phi": 0}, "setLight(30, 0)")
    plane_matches(page)
    nmse_matches(page)

    step("bad values")
    # Bad values: a visible error naming the value and the range; the spheres keep their pixels.
    keep_sphere_pixels(page)
    params_before = page.evaluate("explorer.state.params")
    for text in ("7", "abc", "-0.1", "nan"):
        type_value(page, 0, "r", text)
        wait_idle(page)
        err = field_error(page, 0, "r")
        check(err and text in err and "0" in err and "1" in err,
              "r = %s: the .field-error says %r" % (text, err))
        check(page.evaluate("explorer.state.params") == params_before,
              "r = %s changed the parameters" % text)
        n = changed_sphere_pixels(page)
        check(n == 0, "r = %s changed %d bytes of the spheres' pixels" % (text, n))
    type_value(page, 0, "r", "0.3")
    wait_idle(page)
    check(field_error(page, 0, "r") == "", "the .field-error stays after a good value")
    nmse_matches(page)

    step("advisor, budget slight")
    # The advisor, budget slight, in the worker.
    page.select_option("#advise-mode", "budget")
    page.fill("#advise-budget", "slight")
    page.click("#advise-run")
    page.wait_for_function("() => explorer.last.advise !== null", timeout=120000)
    wait_idle(page)
    cli = webtest.abrdf_json(abrdf, "advise", "gold", "--budget", "slight", "--json")
    adv = page.evaluate("explorer.last.advise")
    shown = page.locator("#advise-result").inner_text()
    chosen = " + ".join(m for m in (cli["diffuse"], cli["specular"]) if m)
    check((adv["diffuse"], adv["specular"]) == (cli["diffuse"], cli["specular"]),
          "the advisor chose %r + %r, the command %r + %r"
          % (adv["diffuse"], adv["specular"], cli["diffuse"], cli["specular"]))
    check(chosen in shown, "#advise-result does not name %r: %r" % (chosen, shown))

    step("screenshot")
    path = os.path.join(out_dir, "web_page.png")
    page.screenshot(path=path, full_page=True)
    step(None)
    print("screenshot: %s" % path)


def main():
    abrdf, web, chromium, out = webtest.config(TEST, PAGES)
    with webtest.Server(web) as server, webtest.Browser(chromium) as browser:
        page = browser.page()
        try:
            run(page, server.url, abrdf, out)
        except Exception as e:  # the traceback, one FAIL line, then what the page logged
            traceback.print_exc()
            print("%s: FAIL: %s" % (TEST, str(e).splitlines()[0] if str(e) else repr(e)))
            for err in browser.errors:
                print("%s: %s" % (TEST, err))
            sys.exit(1)
        if browser.errors:
            for err in browser.errors:
                print("%s: FAIL: %s" % (TEST, err))
            sys.exit(1)
    print("%s: the page did everything the test asked, with no console or page error" % TEST)


if __name__ == "__main__":
    main()
