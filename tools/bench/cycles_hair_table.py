"""cycles_hair_table.py - what huang's table buys in Cycles (docs/OSL.md, "huang from a table").

    python cycles_hair_table.py ABRDF [SCENE] [--width 96] [--height 96] [--threads 2]
                                [--reps 3] [--hair-table-cache DIR]
                                [--hair-table-sizes NT,NV,NP,SETS]

The scene (default tools/bench/hair_robot.scene: three hair materials under four lights) is
exported by `abrdf export --cycles` in evaluation mode (one sample per pixel) in three forms:
huang integrated per call; huang read from its tables (--hair-table; built first, or read
from --hair-table-cache, else into a cache of its own, once); and, for scale, every material
as lambert. Each form is rendered at the size given and at twice it in each dimension, all
in this one process: each built once, rendered once untimed, then --reps times, timed (the
wall time of bpy.ops.render.render; a line "cycles_hair_table FORM WxH render_seconds S" per
render). A render's fixed costs
(the scene's sync, the shader's JIT compilation, which Cycles repeats per render) are the
same at both sizes, so the shading's cost is the difference of the two sizes' fastest
renders; per evaluation, that time on all threads over the difference of the lobe
evaluations `abrdf render --stats` counts for the two images (the shader evaluates the same
pixel-centre rays), an estimate that takes the threads as fully busy. Each image is compared
with `abrdf render --spp 1 --precision double` of the same form (the OSL port's exactness,
NMSE), and the two hair forms with each other (what the table changes).
"""
import argparse
import json
import os
import re
import runpy
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.dirname(os.path.dirname(HERE))
OSL_DIR = os.path.join(SRC, "osl")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("abrdf")
    ap.add_argument("scene", nargs="?", default=os.path.join(HERE, "hair_robot.scene"))
    ap.add_argument("--width", type=int, default=96)
    ap.add_argument("--height", type=int, default=96)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--hair-table-cache")
    ap.add_argument("--hair-table-sizes")
    a = ap.parse_args()
    sys.path.insert(0, OSL_DIR)
    import abrdf_cycles  # bpy with it

    sizes = [(a.width, a.height), (2 * a.width, 2 * a.height)]

    def abrdf(*args):
        r = subprocess.run([a.abrdf, *args], capture_output=True, text=True)
        if r.returncode not in (0, 1) or (r.returncode and args[0] != "compare"):
            sys.exit("cycles_hair_table: abrdf %s: %s" % (args[0], r.stderr.strip()))
        return r.stdout + r.stderr

    best, evals, nmse = {}, {}, {}
    with tempfile.TemporaryDirectory(prefix="abrdf_hair_table_") as d:
        # without a cache of the caller's, one here: each table built once for the four uses
        cache = a.hair_table_cache or os.path.join(d, "cache")
        os.makedirs(cache, exist_ok=True)
        table = ["--hair-table-cache", cache] + (
            ["--hair-table-sizes", a.hair_table_sizes] if a.hair_table_sizes else [])
        forms = {"per_call": [], "table": table, "lambert": ["--model", "lambert"]}
        for form, extra in forms.items():
            for w, h in sizes:
                key, tag = (form, w), "%s_%dx%d" % (form, w, h)
                size = ["--width", str(w), "--height", str(h)]
                c, test = (os.path.join(d, tag + n) for n in ("_c.exr", "_cycles.exr"))
                out = abrdf("render", a.scene, "-o", c, "--spp", "1", "--precision", "double",
                            "--no-preview", "--stats", *size, *extra)
                evals[key] = int(re.search(r"brdf evals\s+(\d+)", out).group(1))
                script = os.path.join(d, tag + ".py")
                abrdf("export", "--cycles", a.scene, "-o", script, "--osl-dir", OSL_DIR,
                      "--spp", "1", *size, *extra)
                s = runpy.run_path(script, run_name="abrdf_scene")["SCENE"]
                sc = abrdf_cycles.build(s, "eval", os.path.join(d, tag + "_osl"), OSL_DIR)
                sc.render.threads_mode = "FIXED"
                sc.render.threads = a.threads
                abrdf_cycles.render(sc, test)  # untimed
                best[key] = float("inf")
                for _ in range(a.reps):
                    t0 = time.perf_counter()
                    abrdf_cycles.render(sc, test)
                    best[key] = min(best[key], time.perf_counter() - t0)
                    print("cycles_hair_table %s %dx%d render_seconds %.3f" % (
                        form, w, h, time.perf_counter() - t0), flush=True)
                nmse[key] = json.loads(abrdf("compare", c, test, "--json"))["nmse"]
                print("cycles_hair_table %s %dx%d nmse_vs_c %.2e" % (form, w, h, nmse[key]))
        w2, h2 = sizes[1]
        big = lambda form: os.path.join(d, "%s_%dx%d_cycles.exr" % (form, w2, h2))
        between = json.loads(abrdf("compare", big("per_call"), big("table"), "--json"))["nmse"]
    print("cycles_hair_table table_vs_per_call %dx%d nmse %.2e" % (w2, h2, between))
    shade = {f: best[(f, sizes[1][0])] - best[(f, sizes[0][0])] for f in forms}
    for f in forms:
        n = evals[(f, sizes[1][0])] - evals[(f, sizes[0][0])]
        print("cycles_hair_table %s shading %.3f s for %d evaluations: about %.1f us each on "
              "%d threads" % (f, shade[f], n, 1e6 * shade[f] * a.threads / max(n, 1),
                              a.threads))
    hair = {f: shade[f] - shade["lambert"] for f in ("per_call", "table")}
    print("cycles_hair_table speedup of the hair's shading %.1fx (over lambert's: per call "
          "%.3f s, with tables %.3f s; %s, %dx%d less %dx%d, %d threads)" % (
              hair["per_call"] / hair["table"] if hair["table"] > 0 else float("nan"),
              hair["per_call"], hair["table"], os.path.basename(a.scene), w2, h2, a.width,
              a.height, a.threads))


if __name__ == "__main__":
    main()
