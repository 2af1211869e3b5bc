"""cloth_layered_doc.py BIN SRC - docs/MODELS.md, "Cloth and layered models", quotes what its
programs print now (BIN holds measure_cloth_layered, gen_belcour_tables, test_cloth,
test_layered):
  - each model's defaults table: albedo 0 / 45 / 80 deg (order 256) and reciprocity error;
  - the Weidlich-Wilkie white-furnace table, each row run with the `--set`s its label names;
  - every figure triple "a / b / c" followed by a `measure_cloth_layered ...` command;
  - "reciprocal (measured X)" in each model's section;
  - the Belcour table convergence of orders 8 vs 16 and 16 vs 32 (gen_belcour_tables --check);
  - the FGD interpolation error and the stability counts the unit suites print.
The costs are timings, marked one-off on the page and not compared."""
import os
import re
import shlex

from doc_check import (NUM, DocError, fail, guarded, line_of, main_args, parse_table, read, require_number, run,
                       section)

bin_dir, src = main_args("BIN SRC", 2)
DOC = "docs/MODELS.md"
SECTION = "Cloth and layered models"
os.environ["CK_FORK"] = "no"


def measure(model, sets=()):
    """(albedo strings at 0, 45, 80 deg (order 256), reciprocity string) of one configuration."""
    args = [os.path.join(bin_dir, "measure_cloth_layered"), model, "--evals", "1000"]
    for s in sets:
        args += ["--set", s]
    out = run(args)
    albedo = re.findall(r"albedo\( ?\d+ deg\) = (\S+) \(order 256\)", out)
    recip = re.search(r"over 1e5 random pairs = (\S+)", out)
    if len(albedo) != 3 or not recip:
        raise DocError(f"`{' '.join(args)}` printed no albedo/reciprocity:\n{out}")
    return albedo, recip[1]


def model_sections(doc):
    """{code name: section text}: the top table maps each model's title to its name."""
    lines = doc.splitlines()
    _, rows, _ = parse_table(lines, next(i for i, l in enumerate(lines) if l.startswith("| model | name |")))
    heads = [i for i, l in enumerate(lines) if l.startswith("### ")]
    out = {}
    for title, name, *_ in rows:
        i = next((h for h in heads if lines[h][4:].startswith(title)), None)
        if i is None:
            raise DocError(f"{DOC}: no section '### {title} ...'")
        end = next((h for h in heads if h > i), len(lines))
        out[name.strip("`")] = "\n".join(lines[i:end])
    return out


def defaults_tables(doc, sections):
    for model, text in sections.items():
        albedo, recip = measure(model)
        lines = text.splitlines()
        starts = [i for i, l in enumerate(lines) if l.startswith("| defaults")]
        if len(starts) != 1:
            fail(f"{DOC}: the {model} section should have one '| defaults ... | value |' table")
            continue
        _, rows, _ = parse_table(lines, starts[0])
        for key, value in rows:
            if key.startswith("albedo"):
                for quoted, got in zip(value.split(" / "), albedo):
                    require_number(DOC, doc, quoted, got, f"{model} defaults, albedo")
            elif key.startswith("reciprocity"):
                require_number(DOC, doc, re.match(NUM, value)[0], recip, f"{model} defaults, reciprocity", sig=3)
        for m in re.finditer(r"reciprocal\s+\(measured (%s)\)|[Rr]eciprocal[^.]*: measured error (%s)" % (NUM, NUM), text):
            require_number(DOC, doc, m[1] or m[2], recip, f"{model}: reciprocity in the text", sig=3)


def furnace_table(doc):
    lines = doc.splitlines()
    start = next((i for i, l in enumerate(lines) if l.startswith("| kd = 1, one coat")), None)
    if start is None:
        raise DocError(f"{DOC}: the Weidlich-Wilkie white-furnace table is not where it was")
    _, rows, _ = parse_table(lines, start)
    for row in rows:
        m = re.fullmatch(r"eta (%s), r (%s)" % (NUM, NUM), row[0])
        albedo, _ = measure("weidlich_wilkie", ["kd=1", f"layer0_eta={m[1]}", f"layer0_r={m[2]}"])
        for quoted, got in zip(row[1:], albedo):
            require_number(DOC, doc, quoted, got, f"weidlich_wilkie kd = 1, {row[0]}")


def commands_in_text(doc):
    flat = re.sub(r"\s+", " ", doc)
    found = 0
    for m in re.finditer(r"(%s) / (%s) / (%s)[^`]{0,120}?\(`(measure_cloth_layered [^`]*)`" % (NUM, NUM, NUM), flat):
        args = shlex.split(m[4])
        sets = [args[i + 1] for i, a in enumerate(args) if a == "--set"]
        albedo, _ = measure(args[1], sets)
        for quoted, got in zip(m.groups()[:3], albedo):
            require_number(DOC, doc, quoted, got, f"`{m[4]}`")
        found += 1
    if found < 3:
        fail(f"{DOC}: expected at least 3 figures with their measure_cloth_layered command, found {found}")


def belcour_convergence(doc):
    flat = re.sub(r"\s+", " ", doc)
    for order, low in ((8, None), (16, "16 vs 32")):
        out = run([os.path.join(bin_dir, "gen_belcour_tables"), "--check", "--order", str(order), "--tol", "1"])
        m = re.search(r"max \|dFGD\| = (\S+), max \|dTIR\| = (\S+)", out)
        if not m:
            raise DocError(f"gen_belcour_tables --check --order {order} printed:\n{out}")
        if low:
            q = re.search(r"order %s: (%s) \(FGD\), (%s) \(TIR\)" % (low, NUM, NUM), flat)
            if not q:
                fail(f"{DOC}: no 'order {low}: X (FGD), Y (TIR)'")
                continue
            require_number(DOC, doc, q[1], m[1], f"FGD order {low}", sig=3)
            require_number(DOC, doc, q[2], m[2], f"TIR order {low}", sig=3)
        else:
            q = re.search(r"orders 8 vs 16 to agree to 1e-2 \(measured (%s)\)" % NUM, flat)
            worst = max(m[1], m[2], key=float)
            if not q:
                fail(f"{DOC}: no 'orders 8 vs 16 ... (measured X)'")
            else:
                require_number(DOC, doc, q[1], worst, "orders 8 vs 16", sig=3)


def unit_suites(doc):
    flat = re.sub(r"\s+", " ", doc)
    layered = run([os.path.join(bin_dir, "test_layered")])
    cloth = run([os.path.join(bin_dir, "test_cloth")])
    m = re.search(r"max \|error\| = (\S+)", layered)
    q = re.search(r"off-node points \(alpha >= 0.15\): max \|error\| (%s)" % NUM, flat)
    if not (m and q):
        fail(f"{DOC}: the FGD interpolation error is not where it was, or test_layered no longer prints it")
    else:
        require_number(DOC, doc, q[1], m[1], "FGD table vs direct quadrature")
    counts = {int(v) for v in re.findall(r"stability \w+: scalar (\d+) values", cloth)}
    batch = {int(v) for v in re.findall(r"batch (\d+) \(", cloth)}
    layer = {int(v) for v in re.findall(r"stability \w+: (\d+) values", layered)}
    q = re.search(r"Measured: ([\d,]+) scalar and ([\d,]+) batch values per model", flat)
    q2 = re.search(r"Measured: ([\d,]+) values per model, 0 NaN", flat)
    for quoted, printed, what in ((q and q[1], counts, "cloth scalar"), (q and q[2], batch, "cloth batch"),
                                  (q2 and q2[1], layer, "layered")):
        if not quoted or printed != {int(quoted.replace(",", ""))}:
            fail(f"{DOC}:{line_of(doc, quoted or 'Measured:')}: {what} stability count: the page says "
                 f"{quoted}, the suites print {sorted(printed)}")


def body():
    doc = section(read(os.path.join(src, DOC)), SECTION)
    defaults_tables(doc, model_sections(doc))
    furnace_table(doc)
    commands_in_text(doc)
    belcour_convergence(doc)
    unit_suites(doc)


guarded("cloth_layered_doc", body)
