"""tables_doc.py ABRDF SRC - docs/TABLES.md quotes what its programs print now:
`abrdf tables 2` and `abrdf tables 3` (every line), `tools/measure/zone_candidates.py` (every
line), and `abrdf tables 4 --costs costs.txt` run on the cost file the page quotes (every
line: the cost file itself is a one-off calibration, the table computed from it is not)."""
import os
import re
import sys
import tempfile

from doc_check import DocError, guarded, main_args, read, require_lines, run

abrdf, src = main_args("ABRDF SRC", 2)
DOC = "docs/TABLES.md"


def body():
    doc = read(os.path.join(src, DOC))
    for t in ("2", "3"):
        require_lines(DOC, doc, run([abrdf, "tables", t]), f"`abrdf tables {t}`")
    zone = os.path.join(src, "tools", "measure", "zone_candidates.py")
    require_lines(DOC, doc, run([sys.executable, zone]), "`python3 tools/measure/zone_candidates.py`")
    m = re.search(r"```\n(# abrdf [^\n]*cost file.*?)```", doc, re.S)
    if not m:
        raise DocError(f"{DOC}: no quoted cost file (a block starting '# abrdf ... cost file')")
    with tempfile.TemporaryDirectory(prefix="tables_doc_") as work:
        with open(os.path.join(work, "costs.txt"), "w") as f:
            f.write(m.group(1))
        out = run([abrdf, "tables", "4", "--costs", "costs.txt"], cwd=work)
    require_lines(DOC, doc, out, "`abrdf tables 4 --costs costs.txt` (on the quoted cost file)")


guarded("tables_doc", body)
