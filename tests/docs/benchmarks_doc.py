"""benchmarks_doc.py ABRDF SRC - docs/BENCHMARKS.md: the accuracy half of `abrdf bench` is
deterministic and is held to the page (section 1's reference, robot NMSE, n, Table 2 and
Table 3 columns; section 2's image and per-material NMSE and classes). The cost ratios and
render times are timings: the page marks them as one-off measurements, and they are not
compared. `--reps 1` keeps the timing part short; it does not change the accuracy."""
import json
import os

from doc_check import DocError, fail, guarded, main_args, parse_table, read, require_number, run

abrdf, src = main_args("ABRDF SRC", 2)
DOC = "docs/BENCHMARKS.md"


def table8_class(nmse):
    """The paper's Table-8 class (tools/image/metrics.c)."""
    return "none" if nmse < 1e-4 else "slight" if nmse < 2.5e-4 else "noticeable" if nmse < 1e-3 else "significant"


def table_at(lines, header_start):
    i = next((i for i, l in enumerate(lines) if l.startswith(header_start)), None)
    if i is None:
        raise DocError(f"{DOC}: no table starting '{header_start}'")
    return parse_table(lines, i)


def accuracy_columns(doc, lines):
    models = {m["name"]: m for m in json.loads(run([abrdf, "bench", "--json", "--reps", "1"]))["models"]}
    head, rows, _ = table_at(lines, "| model | float | speedup | double |")
    col = {h: k for k, h in enumerate(head)}
    for row in rows:
        m = models.get(row[0])
        if m is None:
            fail(f"{DOC}: `abrdf bench` has no model {row[0]}")
            continue
        if row[col["reference"]] != (m["reference"] or ""):
            fail(f"{DOC}: {row[0]}: reference '{row[col['reference']]}', the tool says {m['reference']}")
        for h, key in (("robot NMSE", "robot_nmse"), ("n", "best_n"), ("Table 2 %", "table2_max_rel_pct"),
                       ("Table 3", "table3_max_abs")):
            quoted, value = row[col[h]], m[key]
            if value is None or quoted == "":
                if (value is None) != (quoted == ""):
                    fail(f"{DOC}: {row[0]}, {h}: the page says '{quoted}', the tool gives {value}")
                continue
            require_number(DOC, doc, quoted, str(value), f"{row[0]}, {h}", sig=6)
    if len(rows) != len(models):
        fail(f"{DOC}: the table has {len(rows)} models, `abrdf bench` {len(models)}")


def render_variants(doc, lines):
    out = json.loads(run([abrdf, "bench", "--render", "--json", "--reps", "1"]))
    variants = {v["name"]: v for v in out["variants"]}
    order = ["full_disney", "adaptive_photoreal", "adaptive_performance", "performance_exact_bp"]
    _, rows, _ = table_at(lines, "| variant | models")
    for row, name in zip(rows, order):
        v = variants[name]
        require_number(DOC, doc, row[3], str(v["image_nmse"]), f"{row[0]}, image NMSE", sig=6)
        if name != "full_disney" and row[4] != table8_class(v["image_nmse"]):
            fail(f"{DOC}: {row[0]}: class '{row[4]}', NMSE {v['image_nmse']} is {table8_class(v['image_nmse'])}")
        models = {m["models"] for m in v["materials"]}
        if len(models) == 1 and not row[1].startswith(models.pop()):
            fail(f"{DOC}: {row[0]}: models '{row[1]}', the tool uses {[m['models'] for m in v['materials']]}")
    _, rows, _ = table_at(lines, "| material | (c) vs (a)")
    per = {name: {m["material"]: m["nmse"] for m in variants[name]["materials"]} for name in order}
    own = {m["material"]: m["nmse"] for m in out["performance_vs_exact_bp"]["materials"]}
    for row in rows:
        mat = row[0].split()[0]
        if mat == "image":
            got = (variants["adaptive_performance"]["image_nmse"], variants["performance_exact_bp"]["image_nmse"],
                   out["performance_vs_exact_bp"]["image_nmse"])
        else:
            got = (per["adaptive_performance"][mat], per["performance_exact_bp"][mat], own[mat])
        for quoted, value, what in zip(row[1:], got, ("(c) vs (a)", "(d) vs (a)", "(c) vs (d)")):
            require_number(DOC, doc, quoted, str(value), f"{mat}, {what}", sig=6)


def body():
    doc = read(os.path.join(src, DOC))
    lines = doc.splitlines()
    accuracy_columns(doc, lines)
    render_variants(doc, lines)


guarded("benchmarks_doc", body)
