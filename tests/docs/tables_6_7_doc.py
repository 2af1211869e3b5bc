"""tables_6_7_doc.py ABRDF SRC - docs/TABLES.md, "Tables 6 and 7", quotes what `abrdf tables 6|7`
print now: the two outputs (every line), the sensitivity table (each column re-run with the options its
header names, `abrdf tables 6 --csv [options]`), and the figures the discussion takes from
them (published/computed ratios, the plateaus at n = 1000, the cells in the same class)."""
import csv
import io
import os
import re
import statistics

from doc_check import (DocError, fail, guarded, line_of, main_args, parse_table, quoted, read, require_lines,
                       require_number, round_sig, run, section)

abrdf, src = main_args("ABRDF SRC", 2)
DOC = "docs/TABLES.md"
SECTION = "Tables 6 and 7"

def csv_table(table, options=()):
    """{alpha_g label: computed row}, {alpha_g label: published row}, model names."""
    rows = list(csv.DictReader(io.StringIO(run([abrdf, "tables", table, "--csv", *options]))))
    comp = {r["alpha_g"]: r for r in rows if r["kind"] == "computed"}
    pub = {r["alpha_g"]: r for r in rows if r["kind"] == "published"}
    models = [k for k in rows[0] if k not in ("alpha_g", "kind", "alpha") and not k.endswith("_n")]
    return comp, pub, models


def sensitivity(doc):
    """The f_2e column under each set-up its header names: one run per column."""
    lines = doc.splitlines()
    start = next((i for i, l in enumerate(lines) if l.startswith("| α_g | default")), None)
    if start is None:
        raise DocError(f"{DOC}: no sensitivity table (header '| α_g | default ...')")
    head, rows, _ = parse_table(lines, start)
    columns = []
    for h in head[1:-1]:
        m = re.search(r"`([^`]*)`", h)
        columns.append(csv_table("6", m.group(1).split() if m else ())[0])
    _, pub, _ = csv_table("6")
    for label in columns[0]:
        cells = ["%.1e [%s]" % (float(c[label]["f_2e"]), c[label]["f_2e_n"]) for c in columns]
        row = "| %s | %s | %s |" % (label, " | ".join(cells), pub[label]["f_2e"])
        if not quoted(doc, row):
            fail(f"{DOC}:{start + 1}: the sensitivity table lacks this row (`abrdf tables 6 --csv "
                 f"[option]`, f_2e):\n  {row}")


def discussion(doc, t6, t7):
    # Published/computed ratios over alpha_g >= 0.1.
    m = re.search(r"median of (\S+) \(range (\S+)–(\S+)\) in Table 6 and\s+(\S+) \(range (\S+)–(\S+)\) "
                  r"in Table 7", doc)
    if not m:
        raise DocError(f"{DOC}: the published/computed ratio sentence is not where it was")
    for k, (comp, pub, models) in enumerate((t6, t7)):
        ratios = [float(pub[a][mo]) / float(comp[a][mo]) for a in comp if float(a) >= 0.1 for mo in models]
        for quoted, value, what in zip(m.groups()[3 * k:3 * k + 3],
                                       (statistics.median(ratios), min(ratios), max(ratios)),
                                       ("median", "smallest", "largest")):
            if float(quoted) != round_sig(value, 2):
                fail(f"{DOC}:{line_of(doc, m[0])}: Table {6 + k}: the {what} published/computed ratio is "
                     f"{value:.3g}, the page says {quoted}")
    # Cells in the same Table-8 class (the tool prints "Same class in N of 72 cells.").
    m = re.search(r"only (\d+) of 72 \(Table 6\) and (\d+) of 72 \(Table 7\)", doc)
    if not m:
        raise DocError(f"{DOC}: the same-class sentence is not where it was")
    for quoted, table in zip(m.groups(), ("6", "7")):
        if f"Same class in {quoted} of 72 cells." not in run([abrdf, "tables", table]):
            fail(f"{DOC}:{line_of(doc, m.group(0))}: Table {table} does not have {quoted} cells in the same class")
    # The plateaus of the unbounded lobes at the n = 1000 end (the smallest alpha_g).
    m = re.search(r"flattens at the n = 1000 end of the search: (.*?)\. The", doc, re.S)
    if not m:
        raise DocError(f"{DOC}: the plateau sentence is not where it was")
    last = {}
    for comp, _, models in (t6, t7):
        smallest = min(comp, key=float)
        last.update({mo: comp[smallest][mo] for mo in models})
    found = re.findall(r"(f_\w+) (\d\.\de-\d+)", m.group(1))
    if len(found) < 4:
        fail(f"{DOC}:{line_of(doc, m.group(1))}: expected four plateau values, found {found}")
    for model, quoted in found:
        require_number(DOC, doc, quoted, last[model], f"{model} at the smallest alpha_g")


def body():
    doc = section(read(os.path.join(src, DOC)), SECTION)
    for t in ("6", "7"):
        require_lines(DOC, doc, run([abrdf, "tables", t]), f"`abrdf tables {t}`")
    sensitivity(doc)
    discussion(doc, csv_table("6"), csv_table("7"))


guarded("tables_6_7_doc", body)
