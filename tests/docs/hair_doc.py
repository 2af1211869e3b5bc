"""hair_doc.py BIN SRC - docs/MODELS.md, "Hair models", quotes what its programs print now
(BIN holds test_hair_marschner, test_hair_huang, test_invariants, measure_hair, gen_hair_tables,
hair_convergence): the fibre albedos, lobes and reciprocity, Huang's convergence (what a
converged reference costs, and the tabulated huang at its default sizes), white furnace and R
limit, the surface albedos, the continuity and stability figures, the table convergence. The
costs are one-off timings, marked so on the page."""
import os
import re

from doc_check import NUM, DocError, fail, guarded, main_args, parse_table, read, require_number, run
from doc_check import section as page_section

bin_dir, src = main_args("BIN SRC", 2)
DOC = "docs/MODELS.md"
SECTION = "Hair models"
os.environ["CK_FORK"] = "no"


def prog(name, *args):
    return run([os.path.join(bin_dir, name), *args])


def grab(pattern, text, what):
    m = re.search(pattern, text)
    if not m:
        raise DocError(f"{what}: no match for {pattern!r}")
    return m


def section(doc, start, end):
    i = doc.index(start)
    j = doc.index(end, i) if end else len(doc)
    return doc[i:j]


def triple(doc, text, label, values, what):
    """The value cell of the row whose label starts with `label`: 'a / b / c ...'."""
    m = grab(r"\| %s[^|]*\| (%s(?: / %s)*)" % (re.escape(label), NUM, NUM), text, f"{DOC}: row '{label}'")
    quoted = m[1].split(" / ")
    if len(quoted) != len(values):
        fail(f"{DOC}: row '{label}' has {len(quoted)} figures, the program {len(values)}")
    for q, v in zip(quoted, values):
        require_number(DOC, doc, q, v, what)


def surface(doc, text, model, grid):
    for label, sets in (("surface albedo ∫f_r cos, defaults", []), ("surface albedo, melanin 0", ["--set", "melanin=0"])):
        out = prog("measure_hair", model, "--grid", grid, "--evals", "1", *sets)
        triple(doc, text, label, re.findall(r"albedo\(\s*\d+ deg\) = (\S+)", out), f"{model} {label}")


def body():
    doc = page_section(read(os.path.join(src, DOC)), SECTION)
    flat = lambda t: re.sub(r"\s+", " ", t)
    mar_text = section(doc, "\n### `marschner`", "\n### `huang`")
    hu_text = section(doc, "\n### `huang`", "\n### Stability grid")
    mar = prog("test_hair_marschner")
    hu = prog("test_hair_huang")
    inv = prog("test_invariants")

    # Marschner.
    furnace = [grab(r"theta_o=%2d: (\S+) \(N\)" % d, mar, "test_hair_marschner")[1] for d in (0, 45, 60, 80)]
    triple(doc, mar_text, "fibre albedo ∫S dω_i", furnace, "marschner fibre albedo")
    lobes = grab(r"by lobe: R (\S+), TT (\S+), TRT (\S+)", mar, "test_hair_marschner")
    triple(doc, mar_text, "of which at θ_o = 0", lobes.groups(), "marschner lobes")
    require_number(DOC, doc, grab(r"max relative error (%s) \(200 pairs\)" % NUM, mar_text, DOC)[1],
                   grab(r"of S_M: max relative error (\S+)", mar, "test_hair_marschner")[1], "S_M reciprocity", sig=3)
    surface(doc, mar_text, "marschner", "60,240")
    for model, text in (("marschner", mar_text), ("huang", hu_text)):
        q = grab(r"max relative asymmetry (%s) on the `test_invariants` grid|on the `test_invariants` grid: (%s)"
                 % (NUM, NUM), text, f"{DOC}: {model}'s f_r asymmetry")
        got = grab(r"reciprocity %s +NOT reciprocal \(max asymmetry (\S+)\)" % model, inv, "test_invariants")[1]
        require_number(DOC, doc, q[1] or q[2], got, f"{model} f_r asymmetry", sig=3)

    # Huang: convergence, R limit, white furnace, surface albedos, continuity.
    conv = grab(r"S (\S+), Simpson x2 (\S+), VNDF grids x2 (\S+)", hu, "test_hair_huang")
    conv2 = grab(r"Simpson x4 (\S+), Simpson x8 (\S+), VNDF grids x4 (\S+)", hu, "test_hair_huang")
    ft = flat(hu_text)
    for quoted, got in zip(grab(r"×1 / ×2 / ×4 / ×8: S = (%s) / (%s) / (%s) / (%s)" % ((NUM,) * 4), ft, DOC).groups(),
                           (conv[1], conv[2], conv2[1], conv2[2])):
        require_number(DOC, doc, quoted, got, "Simpson refinement", sig=6)
    for quoted, got in zip(grab(r"\(24, 12\): S = (%s) / (%s) / (%s)" % ((NUM,) * 3), ft, DOC).groups(),
                           (conv[1], conv[3], conv2[3])):
        require_number(DOC, doc, quoted, got, "VNDF grids", sig=6)
    pairs = grab(r"over (\d+) pairs: RMS relative error (\S+), largest (\S+)", hu, "test_hair_huang")
    q = grab(r"[Oo]ver (\d+) direction pairs the default's RMS relative error is (%s) and the largest (%s)" % (NUM, NUM), ft, DOC)
    for quoted, got in zip(q.groups(), pairs.groups()):
        require_number(DOC, doc, quoted, got, "convergence over direction pairs", sig=3)
    r = grab(r"alpha 0.05: (\S+) \(90 x 180\), (\S+) \(180 x 360\), Fresnel h-average (\S+)", hu, "test_hair_huang")
    q = grab(r"(%s) \(90 × 180 grid\) / (%s) \(180 × 360\), against its smooth limit, the Fresnel h-average (%s)"
             % (NUM, NUM, NUM), hu_text, DOC)
    for quoted, got in zip(q.groups(), r.groups()):
        require_number(DOC, doc, quoted, got, "R lobe of a nearly smooth fibre")
    lines = hu_text.splitlines()
    _, rows, _ = parse_table(lines, next(i for i, l in enumerate(lines) if l.startswith("| b | θ_view")))
    for b, view, e, t, total, comp in rows:
        key = "b=%.2f theta_o=%s" % (float(b), view.rstrip("°"))
        if e:
            m = grab(r"no compensation, %s: R\+TT\+TRT (\S+), TRRT\+ (\S+), total (\S+)" % key, hu, key)
            for quoted, got in zip((e, t, total), m.groups()):
                require_number(DOC, doc, quoted, got, f"uncompensated white furnace {key}")
        else:
            require_number(DOC, doc, total, grab(r"no compensation, %s: total (\S+)" % key, hu, key)[1],
                           f"uncompensated white furnace {key}")
        require_number(DOC, doc, comp, grab(r"compensated, %s: total (\S+)" % key, hu, key)[1],
                       f"compensated white furnace {key}")
    surface(doc, hu_text, "huang", "16,64")
    _, rows, _ = parse_table(lines, next(i for i, l in enumerate(lines) if l.startswith("| grids (n1, n2)")))
    if len(rows) != len(re.findall(r"image grids ", hu)):
        fail(f"{DOC}: the image convergence table has {len(rows)} rows, test_hair_huang prints "
             f"{len(re.findall(r'image grids ', hu))}")
    for grid, vs_def, vs_ref, work in rows:
        n1, n2, refine = (int(v) for v in re.findall(r"\d+", grid)[:3])
        m = grab(r"image grids %d,%d, Simpson x%d: NMSE vs the default (\S+), vs the reference (\S+), work (\S+)"
                 % (n1, n2, refine), hu, grid)
        for quoted, got in zip((vs_def, vs_ref, work), m.groups()):
            require_number(DOC, doc, quoted, got, f"image convergence ({n1}, {n2}, x{refine})")
    conv_out = prog("hair_convergence")
    _, rows, _ = parse_table(lines, next(i for i, l in enumerate(lines) if l.startswith("| grids (n1, n2), Simpson | work")))
    if len(rows) != len(re.findall(r"^grids ", conv_out, re.M)):
        fail(f"{DOC}: the converged-reference table has {len(rows)} rows, hair_convergence prints "
             f"{len(re.findall(r'^grids ', conv_out, re.M))}")
    for grid, work, nmse in rows:
        n1, n2, refine = (int(v) for v in re.findall(r"\d+", grid)[:3])
        m = grab(r"grids \(%d, %d\), Simpson x%d: work (\S+), NMSE vs the reference (\S+)" % (n1, n2, refine),
                 conv_out, grid)
        for quoted, got in zip((work, nmse), m.groups()):
            require_number(DOC, doc, quoted, got, f"converged reference ({n1}, {n2}, x{refine})")
    # One set of shifts is one draw: each grid over the model's set and seven rotations of it.
    i = next(i for i, l in enumerate(lines) if l.strip().startswith("| grids (n1, n2), Simpson | work | set 0"))
    _, rows, _ = parse_table([l.strip() for l in lines], i)
    grids = [",".join(re.findall(r"\d+", row[0])[:3]) for row in rows]
    if len(rows) != 6:
        fail(f"{DOC}: the shift-set table has {len(rows)} rows, not 6")
    sets = prog("hair_convergence", "--shifts", "8", *grids)
    for (grid, work, set0, mean, span, of_mean), g in zip(rows, grids):
        n1, n2, refine = (int(v) for v in g.split(","))
        m = grab(r"grids \(%d, %d\), Simpson x%d: work (\S+), NMSE vs the reference (\S+)\n"
                 r"  over 8 shift sets: mean (\S+), from (\S+) to (\S+) \([^)]*\); their mean image ([^;\s]+)"
                 % (n1, n2, refine), sets, grid)
        lo, hi = (v.strip() for v in span.split("–"))
        for quoted, got in zip((work, set0, mean, lo, hi, of_mean), m.groups()):
            require_number(DOC, doc, quoted, got.rstrip(","), f"shift sets ({n1}, {n2}, x{refine})")
        if (n1, n2, refine) == (6, 3, 1) and not re.search(
                r"grids \(6, 3\), Simpson x1: .*\n  over 8 shift sets: .*; nearest: set 0\n", sets):
            fail(f"{DOC}: the default's own shifts are no longer the nearest of eight on the cylinder")
    back_out = prog("hair_convergence", "--backlit", "--lobes", "6,3,1")
    back = grab(r"R (\S+) \(\d+ %\), TT (\S+) \((\d+) %\), TRT (\S+) \(\d+ %\), TRRT\+ (\S+)", back_out,
                "hair_convergence --backlit --lobes")
    q = grab(r"TT makes (\d+) %% of the reference's squared sum. The default is (%s) from \(16, 8, ×4\) there"
             % NUM, ft, DOC)
    if q[1] != back[3]:
        fail(f"{DOC}: TT's share of the backlit image is {q[1]} % on the page, {back[3]} % now")
    require_number(DOC, doc, q[2], grab(r"grids \(6, 3\), Simpson x1: work \S+, NMSE vs the reference (\S+)",
                                        back_out, "backlit")[1], "the backlit default's error")
    q = grab(r"6,3,1`\): R (%s), TT (%s), TRT (%s), TRRT\+ (%s) \(the parts" % (NUM, NUM, NUM, NUM), ft, DOC)
    for quoted, got in zip(q.groups(), (back[1], back[2], back[4], back[5])):
        require_number(DOC, doc, quoted, got, "the backlit default's error by lobe")
    sets = prog("hair_convergence", "--backlit", "--shifts", "8", "6,3,1", "12,6,2")
    q = grab(r"the default (%s) with its own shifts \(\S+\),\s+(%s) on average, \S+ and "
             r"\(12, 6, ×2\) (%s) on average" % (NUM, NUM, NUM), ft, DOC)
    got = (grab(r"grids \(6, 3\), Simpson x1: work \S+, NMSE vs the reference (\S+)", sets, "backlit")[1],
           grab(r"grids \(6, 3\).*\n  over 8 shift sets: mean (\S+),", sets, "backlit")[1].rstrip(","),
           grab(r"grids \(12, 6\).*\n  over 8 shift sets: mean (\S+),", sets, "backlit")[1].rstrip(","))
    for quoted, g in zip(q.groups(), got):
        require_number(DOC, doc, quoted, g, "the backlit image over shift sets")
    if not re.search(r"grids \(6, 3\), Simpson x1: .*\n  over 8 shift sets: .*; nearest: set 0\n", sets):
        fail(f"{DOC}: on the backlit image the default's own shifts are no longer the nearest of eight")
    q = grab(r"over its own set and seven rotations of it the same rule is (%s) from the reference on average"
             % NUM, ft, DOC)
    require_number(DOC, doc, q[1], grab(r"huang shift sets: .* mean of 8 sets (\S+),", hu, "test_hair_huang")[1],
                   "the default's mean over shift sets")
    i = next(i for i, l in enumerate(lines) if l.strip().startswith("| r | default (6, 3) |"))
    _, rows, _ = parse_table([l.strip() for l in lines], i)
    if len(rows) < 3:
        fail(f"{DOC}: the roughness table has {len(rows)} rows")
    for r, dflt, dense, denser in rows:
        out = prog("hair_convergence", "--r", r, "6,3,1", "16,6,1", "16,7,1")
        for quoted, grid in ((dflt, "6, 3"), (dense, "16, 6"), (denser, "16, 7")):
            got = grab(r"grids \(%s\), Simpson x1: work \S+, NMSE vs the reference (\S+)" % grid, out, f"r {r}")[1]
            require_number(DOC, doc, quoted, got, f"convergence at r {r}, grids ({grid})")
    # A tabulated huang: the row of the default sizes (abrdf.h, ABRDF_HUANG_TABLE_SIZES), on the
    # cylinder and the backlit cylinder; the other rows are one-off figures.
    i = next(i for i, l in enumerate(lines) if l.strip().startswith("| table (NT, NV, NP), sets |"))
    _, rows, _ = parse_table([l.strip() for l in lines], i)
    row = next((r for r in rows if "default" in r[0]), None)
    if not row:
        fail(f"{DOC}: the tabulated huang's table has no row of the default sizes")
    sizes = tuple(re.findall(r"\d+", row[0])[:4])
    hdr = read(os.path.join(src, "libabrdf/include/abrdf.h"))
    want = grab(r"#define ABRDF_HUANG_TABLE_SIZES \{(\d+), (\d+), (\d+), (\d+)\}", hdr, "abrdf.h").groups()
    if sizes != want:
        fail(f"{DOC}: the tabulated huang's default row is {sizes}, abrdf.h's sizes {want}")
    # Against the mean of eight shift sets of (16, 8, x4), with the quadrature (6, 3, x1) and
    # set 0 of (16, 8, x4) beside the table on the same reference.
    quad = grab(r"The quadrature it replaces, on the same images: (%s) with its own shifts on the cylinder"
                r"\s+\(\S+ on average over rotations of them\), (%s) backlit" % (NUM, NUM), ft, DOC)
    own = grab(r"Its set 0, the reference of the other figures of these sections, is (%s)\s+from the mean "
               r"of its sets 0 to 7 on the cylinder and (%s) backlit" % (NUM, NUM), ft, DOC)
    for col, extra in ((3, []), (4, ["--backlit", "--parts"])):
        out = prog("hair_convergence", *extra, "--reference-sets", "8", "--table", ",".join(sizes),
                   "6,3,1", "16,8,4")
        m = grab(r"table \(\d+, \d+, \d+\), \d+ shift sets of grids \(6, 3\): NMSE vs the reference (\S+); "
                 r"built in \S+ s \((\d+) values\)", out, "hair_convergence --table")
        require_number(DOC, doc, row[col], m[1], f"the tabulated huang {sizes} {' '.join(extra)}")
        if int(row[1].replace(" ", "")) != int(m[2]):
            fail(f"{DOC}: the tabulated huang {sizes} has {row[1]} values on the page, {m[2]} now")
        image = "backlit" if extra else "cylinder"
        for q, (n1, n2, k) in ((quad[col - 2], (6, 3, 1)), (own[col - 2], (16, 8, 4))):
            got = grab(r"grids \(%d, %d\), Simpson x%d: work \S+, NMSE vs the reference (\S+)" % (n1, n2, k),
                       out, "hair_convergence --reference-sets 8")[1]
            require_number(DOC, doc, q, got, f"against the mean of eight sets, {image}, grids ({n1}, {n2}, x{k})")
    # The backlit table's error in parts (--parts, the last run): its nodes' rule at the
    # image's own directions, and each axis read alone between its nodes.
    node = grab(r"own directions: NMSE vs the reference (\S+)", out, "hair_convergence --parts")[1]
    require_number(DOC, doc, grab(r"evaluated at the image's own directions\s+\(no table\), is already (%s)" % NUM,
                                  ft, DOC)[1], node, "the backlit table's nodes' rule")
    axes = grab(r"theta_v along the ridge (\S+), theta_v \+ theta_l (\S+), phi_v (\S+), d (\S+)", out,
                "hair_convergence --parts")
    quoted = grab(r"three exact: θ_view \+ θ_light, across the ridge, (%s); the light's relative azimuth d (%s); "
                  r"the view's azimuth (%s); θ_view along the ridge (%s)\." % (NUM, NUM, NUM, NUM), ft, DOC)
    for q, g, name in zip(quoted.groups(), (axes[2], axes[4], axes[3], axes[1]),
                          ("theta_v + theta_l", "d", "phi_v", "theta_v along the ridge")):
        require_number(DOC, doc, q, g, f"the backlit table's interpolation along {name}")
    lob = grab(r"R (\S+) \(\d+ %\), TT \S+ \(\d+ %\), TRT (\S+) \(\d+ %\), TRRT\+ (\S+)",
               prog("hair_convergence", "--lobes", "6,3,1"), "hair_convergence --lobes")
    q = grab(r"against \(16, 8, ×4\): R (%s), TRT (%s), TRRT\+ (%s)\)" % (NUM, NUM, NUM), ft, DOC)
    for quoted, got in zip(q.groups(), lob.groups()):
        require_number(DOC, doc, quoted, got, "the default's error by lobe")
    cop = grab(r"largest relative change (\S+)", hu, "test_hair_huang")[1]
    require_number(DOC, doc, grab(r"The largest relative change is (%s)" % NUM, ft, DOC)[1], cop, "coplanar continuity", sig=3)
    require_number(DOC, doc, grab(r"The example now gives f_r = (%s)" % NUM, ft, DOC)[1],
                   grab(r"phi 180/180: f (\S+)", hu, "test_hair_huang")[1], "coplanar example")
    ecomp = grab(r"largest change against 128 × 128 is (%s)" % NUM, ft, DOC)[1]
    require_number(DOC, doc, ecomp, grab(r"nodes per dimension: (\S+)", prog("gen_hair_tables", "--convergence"),
                                         "gen_hair_tables --convergence")[1], "energy table convergence", sig=3)

    # Stability counts of both suites.
    q = grab(r"Marschner ([\d ]+) values and Huang ([\d ]+) values", flat(doc), DOC)
    for quoted, out, name in ((q[1], mar, "marschner"), (q[2], hu, "huang")):
        got = grab(r"%s stability grid: (\d+) values" % name, out, name)[1]
        if int(quoted.replace(" ", "")) != int(got):
            fail(f"{DOC}: {name} stability grid: the page says {quoted}, the suite prints {got}")


guarded("hair_doc", body)
