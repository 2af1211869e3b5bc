"""tables_doc.py ABRDF SRC - docs/TABLES.md, its section on Tables 2, 3 and 4, quotes what its
programs print now:
`abrdf tables 2` and `abrdf tables 3` (every line), `tools/measure/zone_candidates.py` (every
line), and `abrdf tables 4 --costs costs.txt` run on the cost file the page quotes (every
line: the cost file itself is a one-off calibration, the table computed from it is not)."""
import os
import re
import sys
import tempfile

from doc_check import NUM, DocError, guarded, main_args, read, require_lines, require_number, run, section

abrdf, src = main_args("ABRDF SRC", 2)
DOC = "docs/TABLES.md"
SECTION = "The paper's Tables 2, 3 and 4"


def body():
    doc = section(read(os.path.join(src, DOC)), SECTION)
    for t in ("2", "3"):
        require_lines(DOC, doc, run([abrdf, "tables", t]), f"`abrdf tables {t}`")
    zone = os.path.join(src, "tools", "measure", "zone_candidates.py")
    candidates = run([sys.executable, zone])
    require_lines(DOC, doc, candidates, "`python3 tools/measure/zone_candidates.py`")
    # The prose's summaries of those outputs.
    flat = re.sub(r"\s+", " ", doc)
    chosen = re.search(r"CHOSEN:.*?(%s) +(%s)$" % (NUM, NUM), candidates, re.M)
    said = re.search(r"matches every column: mean deviation (%s) points, largest (%s)" % (NUM, NUM), flat)
    mads = [re.search(r"Mean absolute deviation .*?: (%s) " % NUM, run([abrdf, "tables", t])) for t in ("2", "3")]
    result = re.search(r"Result: \*\*(%s) points and (%s)\*\*" % (NUM, NUM), flat)
    if not (chosen and said and all(mads) and result):
        raise DocError(f"{DOC}: the summaries of the zone candidates and of the deviations are not where they were")
    for quoted, value, what in ((said[1], chosen[1], "chosen zone, mean deviation"),
                                (said[2], chosen[2], "chosen zone, largest deviation"),
                                (result[1], mads[0][1], "Table 2 mean absolute deviation"),
                                (result[2], mads[1][1], "Table 3 mean absolute deviation")):
        require_number(DOC, doc, quoted, value, what)
    m = re.search(r"```\n(# abrdf [^\n]*cost file.*?)```", doc, re.S)
    if not m:
        raise DocError(f"{DOC}: no quoted cost file (a block starting '# abrdf ... cost file')")
    with tempfile.TemporaryDirectory(prefix="tables_doc_") as work:
        with open(os.path.join(work, "costs.txt"), "w") as f:
            f.write(m.group(1))
        out = run([abrdf, "tables", "4", "--costs", "costs.txt"], cwd=work)
    require_lines(DOC, doc, out, "`abrdf tables 4 --costs costs.txt` (on the quoted cost file)")


guarded("tables_doc", body)
