"""gltf_doc.py ABRDF SRC - docs/GLTF.md, its section "The mapping", quotes what
`abrdf tables gltf` prints now (every line), and its prose's figures are that table's: the
largest albedo error and NMSE of the rows whose only approximation is the masking (the
metallic-0.5 and coloured-specular rows among them: their diffuse is exact), and the classes
it names."""
import csv
import io
import os
import re

from doc_check import NUM, DocError, fail, guarded, main_args, read, require_lines, require_number, run, section

abrdf, src = main_args("ABRDF SRC", 2)
DOC = "docs/GLTF.md"
MASKING_ONLY = ("dielectric, rough", "dielectric, smooth", "metal", "metallic 0.5",
                "coloured specular", "ior 2", "anisotropy 0.5", "transmission 0.5")


def body():
    doc = section(read(os.path.join(src, DOC)), "The mapping")
    require_lines(DOC, doc, run([abrdf, "tables", "gltf"]), "`abrdf tables gltf`")
    rows = {r["mapping"]: r for r in csv.DictReader(io.StringIO(run([abrdf, "tables", "gltf", "--csv"])))}
    flat = re.sub(r"\s+", " ", doc)
    m = re.search(r"at most (%s) of albedo \(anisotropy, 75 degrees\) and an NMSE of at most (%s)" % (NUM, NUM), flat)
    if not m:
        raise DocError(f"{DOC}: the masking summary ('at most ... of albedo ... NMSE of at most ...') is not where it was")
    worst = max(MASKING_ONLY, key=lambda r: float(rows[r]["albedo_max_abs"]))
    if worst != "anisotropy 0.5" or abs(float(rows[worst]["albedo_err_75"])) != float(rows[worst]["albedo_max_abs"]):
        fail(f"{DOC}: the largest masking-only albedo error is now {worst}'s, not anisotropy's at 75 degrees")
    require_number(DOC, doc, m[1], rows[worst]["albedo_max_abs"], "largest masking-only albedo error")
    require_number(DOC, doc, m[2], max(float(rows[r]["nmse"]) for r in MASKING_ONLY),
                   "largest masking-only NMSE")
    if any(rows[r]["class"] != "none" for r in MASKING_ONLY):
        fail(f"{DOC}: says masking alone is within 'none'; the table says otherwise")
    for row, cls in (("specular 0.5", "noticeable"), ("clearcoat 1", "significant"),
                     ("sheen", "significant")):
        if rows[row]["class"] != cls:
            fail(f"{DOC}: names {row} '{cls}'; the table says '{rows[row]['class']}'")


guarded("gltf_doc", body)
