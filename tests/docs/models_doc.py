"""models_doc.py TEST_INVARIANTS TEST_STABILITY SRC - docs/MODELS.md quotes what the generic
suites print now: the stability counts (verbatim), and from test_invariants the reciprocity
asymmetries, the float-vs-double errors, the frame-invariance differences, every albedo table
and inline albedo of the model sections, and the summary tables (each figure to its own last
digit)."""
import os
import re

from doc_check import (NUM, DocError, fail, guarded, line_of, main_args, parse_table, read, require_number, run,
                       section)

invariants, stability, src = main_args("TEST_INVARIANTS TEST_STABILITY SRC", 3)
DOC = "docs/MODELS.md"
os.environ["CK_FORK"] = "no"


def suite_output():
    """test_invariants' figures: {model: value string} per property, albedo rows per model."""
    out = run([invariants])
    recip, fvd, frame, albedo, max_albedo = {}, {}, {}, {}, {}
    for line in out.splitlines():
        if m := re.match(r"reciprocity (\w+) +\d+ sets: max relative asymmetry (\S+)$", line):
            recip[m[1]] = m[2]
        elif m := re.match(r"reciprocity (\w+) +NOT reciprocal", line):
            recip[m[1]] = "NOT"
        # the portable baseline level, the same on every CPU (the doc quotes it)
        elif m := re.match(r"float (?:\(baseline\) )?vs double (\w+) +\d+ sets: max relative error (\S+) ", line):
            fvd[m[1]] = m[2]
        elif m := re.match(r"frame invariance (\w+) +max relative difference (\S+) ", line):
            frame[m[1]] = m[2]
        elif m := re.match(r"  (\w+) +(?:EC|-) +\[([^]]*)\] ((?:\S+ ){3}\S+)(?:.*bound (\S+))?", line):
            albedo.setdefault(m[1], {})[m[2]] = (m[3].split(), m[4])
        elif m := re.match(r"  (\w+) +max albedo ([^ ;]+)", line):
            max_albedo[m[1]] = m[2]
    if not (recip and fvd and frame and albedo):
        raise DocError(f"test_invariants printed no figures:\n{out[-2000:]}")
    return recip, fvd, frame, albedo, max_albedo


def sections(doc):
    """`#### models — ...` sections of "The models": [(model names, first line, text)] (the
    special-surface sections further down have #### headings of their own)."""
    lines, out = section(doc, "The models").splitlines(), []
    heads = [i for i, l in enumerate(lines) if l.startswith("#### ")]
    for k, i in enumerate(heads):
        end = heads[k + 1] if k + 1 < len(heads) else next(
            (j for j in range(i + 1, len(lines)) if lines[j].startswith("## ")), len(lines))
        names = [n.strip() for n in lines[i][5:].split(" — ")[0].split(",")]
        out.append((names, i, lines[i:end]))
    return out


def label(first_cell, header, model):
    """A table row's parameters as test_invariants labels its albedo rows."""
    keys = [k.strip() for k in header.split(",")]
    vals = [v.strip() for v in first_cell.split(",")]
    if keys[0] == "model":
        model, keys, vals = vals[0], keys[1:], vals[1:]
    names = {"σ": "sigma"}
    values = {"π/2": "1.5708"}
    return model, " ".join(f"{names.get(k, k)}={values.get(v, v)}" for k, v in zip(keys, vals))


def albedo_tables(doc, albedo):
    checked = 0
    for names, first, lines in sections(doc):
        i = 0
        while i < len(lines):
            if not (lines[i].startswith("|") and "0°" in lines[i]):
                i += 1
                continue
            head, rows, i = parse_table(lines, i)
            for row in rows:
                model, lab = label(row[0], head[0], names[0])
                got = albedo.get(model, {}).get(lab)
                if got is None:
                    fail(f"{DOC}:{first + 1}: test_invariants prints no albedo row {model} [{lab}]")
                    continue
                values, bound = got
                for h, cell in zip(head[1:], row[1:]):
                    if h == "bound":
                        require_number(DOC, doc, cell, bound, f"{model} [{lab}] furnace bound")
                        continue
                    angle = ["0°", "45°", "80°", "89°"].index(h)
                    # "a / b": light in the T-N plane / the B-N plane (phi_i = 90)
                    for quoted, lab2 in zip(cell.split(" / "), (lab, lab + " phi_i=90")):
                        require_number(DOC, doc, quoted, albedo[model][lab2][0][angle],
                                       f"{model} [{lab2}] albedo at {h}")
                        checked += 1
        for line in lines:
            for m in re.finditer(r"[Aa]lbedo(?: (n) = (\d+)|, F0 = 0|)?: (%s) / (%s) / (%s)" % (NUM, NUM, NUM), line):
                lab = f"n={m[2]}" if m[1] else "defaults"
                for angle, quoted in enumerate(m.groups()[2:]):
                    require_number(DOC, doc, quoted, albedo[names[0]][lab][0][angle], f"{names[0]} [{lab}] albedo")
                    checked += 1
        text = " ".join(lines)
        for m in re.finditer(r"albedo (%s) / (%s) / (%s) at gloss (\d+)" % (NUM, NUM, NUM), text):
            lab = f"clearcoat_gloss={m[4]}"
            for angle, quoted in enumerate(m.groups()[:3]):
                require_number(DOC, doc, quoted, albedo[names[0]][lab][0][angle], f"{names[0]} [{lab}] albedo")
                checked += 1
    if checked < 100:
        fail(f"{DOC}: only {checked} albedo figures found in the model sections; the tables moved?")


def general_models(doc):
    return [n for names, _, _ in sections(doc) for n in names]


def prose(doc, recip, frame):
    m = re.search(r"Measured: 0 for every model\.", doc)
    if not m:
        raise DocError(f"{DOC}: the reciprocity sentence is not where it was")
    for model in general_models(doc):
        if recip.get(model) != "0":
            fail(f"{DOC}:{line_of(doc, m[0])}: {model}'s reciprocity asymmetry is {recip.get(model)}, not 0")
    for model in general_models(doc):
        if frame.get(model) != "0":
            fail(f"{DOC}: 'Measured: 0 difference for every model of The models', but frame invariance "
                 f"of {model} is {frame.get(model)}")


def float_vs_double(doc, fvd):
    lines = doc.splitlines()
    start = next(i for i, l in enumerate(lines) if l.startswith("| model | max rel. error |"))
    _, rows, _ = parse_table(lines, start)
    for row in rows:
        for models, values in ((row[0], row[1]), (row[2], row[3])):
            models = [m.strip() for m in models.split(",")]
            values = [v.strip() for v in values.split(",")]
            for k, model in enumerate(models):
                require_number(DOC, doc, values[min(k, len(values) - 1)], fvd[model],
                               f"{model} float vs double", sig=3)


def furnace_figure(cell):
    m = re.search(r"(?:max |EC, |not EC \()(%s)(?![\wπ])" % NUM, cell)
    return m[1] if m else None


def summary_tables(doc, recip, fvd, frame, max_albedo):
    """'Special-surface models in the generic suites' and 'Test status'."""
    lines = doc.splitlines()
    starts = [i for i, l in enumerate(lines) if l.startswith("| model | reciprocal |")
              or l.startswith("| model | closed form | reciprocal |")]
    if len(starts) != 2:
        raise DocError(f"{DOC}: expected the two summary tables, found {len(starts)}")
    for start in starts:
        head, rows, _ = parse_table(lines, start)
        for row in rows:
            for model in (m.strip() for m in row[0].split(",")):
                for h, cell in zip(head[1:], row[1:]):
                    what = f"{model}, {h}"
                    if h == "reciprocal":
                        if cell.startswith("yes, "):
                            require_number(DOC, doc, cell[5:], recip[model], what, sig=3)
                        elif recip[model] != "NOT":
                            fail(f"{DOC}:{start + 1}: {what}: the page says '{cell}', the suite measures {recip[model]}")
                    elif h.startswith("furnace") and furnace_figure(cell):
                        require_number(DOC, doc, furnace_figure(cell), max_albedo[model], what)
                    elif h == "float == double" and re.fullmatch(NUM, cell):
                        require_number(DOC, doc, cell, fvd[model], what, sig=3)
                    elif h == "frame invariance":
                        lead = re.match(NUM, cell)
                        if not lead:
                            fail(f"{DOC}:{start + 1}: {what}: '{cell}' gives no figure")
                        else:
                            require_number(DOC, doc, lead[0], frame[model], what, sig=3)


def body():
    doc = read(os.path.join(src, DOC))
    m = re.search(r"`build/bin/test_stability` prints\n\n((?:    .*\n)+)", doc)
    if not m:
        raise DocError(f"{DOC}: the quoted output of test_stability is not where it was")
    printed = run([stability]).splitlines()
    for line in m[1].splitlines():
        if line[4:] not in printed:
            fail(f"{DOC}:{line_of(doc, line)}: test_stability no longer prints\n  {line[4:]}")
    recip, fvd, frame, albedo, max_albedo = suite_output()
    albedo_tables(doc, albedo)
    prose(doc, recip, frame)
    float_vs_double(doc, fvd)
    summary_tables(doc, recip, fvd, frame, max_albedo)


guarded("models_doc", body)
