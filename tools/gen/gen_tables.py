#!/usr/bin/env python3
"""gen_tables.py - the one generator of every generated file in the tree, and its check.

    python3 tools/gen/gen_tables.py BIN_DIR            rewrite them (whole or not at all)
    python3 tools/gen/gen_tables.py BIN_DIR --check    compare, write nothing (CTest
                                                       generated_files_current)
    python3 tools/gen/gen_tables.py BIN_DIR --out DIR  write the same tree under DIR

BIN_DIR is a build's bin/ (build/bin): the C generators there compute the tables, and
`abrdf` there gives the registry and the selection rules. The files, and what makes them:

    libabrdf/src/kernels/fkub_table.c        fit_fkub            (tools/gen/fit_fkub.c)
    libabrdf/src/hair/hair_tables.c          gen_hair_tables     (tools/gen/gen_hair_tables.c)
    libabrdf/src/layered/belcour_tables.c    gen_belcour_tables  (tools/gen/gen_belcour_tables.c)
    scenes/teapot.obj                        gen_teapot          (tools/gen/gen_teapot.c)
    povray_macros/abrdf_params.inc           pov_includes.py, from `abrdf` and fkub_table.c
    povray_macros/abrdf_belcour_tables.inc   pov_includes.py, from belcour_tables.c
    povray_macros/abrdf_huang_tables.inc     pov_includes.py, from hair_tables.c
    osl/abrdf_meta.h                         osl_headers.py, from `abrdf`
    osl/abrdf_fkub.h                         osl_headers.py, from fkub_table.c
    osl/abrdf_belcour_tables.h               osl_headers.py, from belcour_tables.c
    osl/abrdf_hair_tables.h                  osl_headers.py, from hair_tables.c

The ports' copies are made from the C tables of this same run, so one run leaves the three
consistent. `abrdf` is built from the committed C tables: after a C table changes, rebuild
and run again (--check then passes). Why the files are committed at all: README, "Generated
files".
"""
import json
import os
import subprocess
import sys
import tempfile

import gen_output  # whole or not at all, as tools/common/out_file.h
import osl_headers
import pov_includes

PROG = "gen_tables"
SRC = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))

FKUB_C = "libabrdf/src/kernels/fkub_table.c"
HAIR_C = "libabrdf/src/hair/hair_tables.c"
BELCOUR_C = "libabrdf/src/layered/belcour_tables.c"
TEAPOT = "scenes/teapot.obj"
# The C generators: (tree path, program, arguments before the output path).
C_GENERATORS = [(FKUB_C, "fit_fkub", []), (HAIR_C, "gen_hair_tables", []),
                (BELCOUR_C, "gen_belcour_tables", []), (TEAPOT, "gen_teapot", ["-o"])]


def fail(message, code=1):
    sys.stderr.write(f"{PROG}: {message}\n")
    raise SystemExit(code)


def read(path):
    try:
        with open(path) as f:
            return f.read()
    except OSError as e:
        fail(f"{path}: {e.strerror or e}")


def run_c_generators(bin_dir, scratch):
    """Run the C generators side by side, each writing into scratch; {tree path: text}."""
    procs = []
    for rel, prog, args in C_GENERATORS:
        out = os.path.join(scratch, os.path.basename(rel))
        exe = os.path.join(bin_dir, prog)
        # restore_signals=False: a file size limit (SIGXFSZ, which Python ignores) makes a
        # write fail with its reason instead of killing the generator
        procs.append((rel, prog, out, subprocess.Popen(
            [exe] + args + [out], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
            restore_signals=False)))
    texts, errors = {}, []
    for rel, prog, out, p in procs:
        err = p.communicate()[1].strip()
        if p.returncode < 0:
            errors.append(f"{prog} was killed by signal {-p.returncode}")
        elif p.returncode != 0:
            errors.append(f"{prog} failed ({p.returncode}): "
                          f"{err.splitlines()[-1] if err else 'no message'}")
        else:
            texts[rel] = read(out)
    if errors:
        fail("; ".join(errors))
    return texts


def abrdf_json(bin_dir, *args):
    exe = os.path.join(bin_dir, "abrdf")
    try:
        p = subprocess.run([exe] + list(args), capture_output=True, text=True)
    except OSError as e:
        fail(f"{exe}: {e.strerror or e}")
    if p.returncode != 0:
        fail(f"{exe} {' '.join(args)} failed ({p.returncode}): {p.stderr.strip()}")
    try:
        return json.loads(p.stdout)
    except json.JSONDecodeError as e:
        fail(f"{exe} {' '.join(args)} printed no JSON ({e})")


def check_programs(bin_dir):
    """Every program the run needs, before any starts."""
    for prog in [g[1] for g in C_GENERATORS] + ["abrdf"]:
        exe = os.path.join(bin_dir, prog)
        if not (os.path.isfile(exe) and os.access(exe, os.X_OK)):
            fail(f"{exe}: no such program (build first: make build)", 2)


def generate(bin_dir):
    """{tree path: text} of every generated file."""
    with tempfile.TemporaryDirectory(prefix="abrdf-gen-") as scratch:
        files = run_c_generators(bin_dir, scratch)
    reg = abrdf_json(bin_dir, "models", "--json")
    rules = abrdf_json(bin_dir, "advise", "--rules", "--json")
    belcour_h = read(os.path.join(SRC, "libabrdf/src/layered/belcour_tables.h"))
    hair_h = read(os.path.join(SRC, "libabrdf/src/hair/hair.h"))
    pov = "povray_macros"
    files[pov + "/abrdf_params.inc"] = pov_includes.params_inc(
        reg, rules, files[FKUB_C], os.path.join(SRC, pov, "abrdf_models.inc"))
    files[pov + "/abrdf_belcour_tables.inc"] = pov_includes.belcour_inc(belcour_h, files[BELCOUR_C])
    files[pov + "/abrdf_huang_tables.inc"] = pov_includes.huang_tables_inc(files[HAIR_C], hair_h)
    osl = osl_headers.headers(reg["models"], rules, files[FKUB_C], files[BELCOUR_C], belcour_h,
                              files[HAIR_C], hair_h)
    for name, text in osl.items():
        files["osl/" + name] = text
    return files


def check(files):
    """Compare with the tree: 0 when every file is what the generators make now."""
    stale = []
    for rel, text in sorted(files.items()):
        path = os.path.join(SRC, rel)
        try:
            with open(path) as f:
                same = f.read() == text
        except OSError:
            same = False
        if not same:
            stale.append(rel)
            with tempfile.NamedTemporaryFile("w", suffix=os.path.basename(rel)) as t:
                t.write(text)
                t.flush()
                diff = subprocess.run(["diff", "-u", path, t.name], capture_output=True,
                                      text=True).stdout
            sys.stdout.write(f"{rel} differs from what its generator makes now:\n")
            sys.stdout.write("\n".join(diff.splitlines()[:40]) + "\n")
    if stale:
        fail(f"{len(stale)} of {len(files)} generated files are out of date ({', '.join(stale)}); "
             "run: python3 tools/gen/gen_tables.py build/bin")
    print(f"{PROG}: all {len(files)} generated files are what their generators make now")
    return 0


def main(argv):
    args, mode, out = [], "write", SRC
    i = 0
    while i < len(argv):
        a = argv[i]
        if a == "--check":
            mode = "check"
        elif a == "--out" and i + 1 < len(argv):
            out = argv[i + 1]
            i += 1
        elif a.startswith("-"):
            fail(f"unknown option {a} (usage: gen_tables.py BIN_DIR [--check | --out DIR])", 2)
        else:
            args.append(a)
        i += 1
    if len(args) != 1:
        fail("usage: gen_tables.py BIN_DIR [--check | --out DIR]", 2)
    if mode == "check" and out != SRC:
        fail("--check compares with the source tree; it takes no --out", 2)
    if not os.path.isdir(out):
        fail(f"{out}: no such directory", 2)
    check_programs(args[0])
    files = generate(args[0])
    if mode == "check":
        return check(files)
    targets = {}
    for rel, text in files.items():
        directory = os.path.join(out, os.path.dirname(rel))
        if not os.path.isdir(directory):
            fail(f"{directory}: no such directory; nothing was written", 2)
        targets[os.path.join(out, rel)] = text
    gen_output.write_all(PROG, targets, inputs=[os.path.join(args[0], "abrdf")])
    print(f"{PROG}: wrote {len(files)} files under {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
