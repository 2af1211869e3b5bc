"""Every C/C++ source of the tree is formatted by its .clang-format (clang-format 14):
`clang-format --dry-run --Werror` over the tracked .c/.h/.cpp files, except generated tables
("GENERATED" in the first line: their generators own the layout) and the frozen ABI snapshot
under tests/data/. Reformat with:  clang-format -i FILE ...

usage: check_format.py SOURCE_DIR [CLANG_FORMAT]
"""
import os
import subprocess
import sys

SRC = sys.argv[1]
TOOL = sys.argv[2] if len(sys.argv) > 2 else "clang-format"


def sources():
    out = subprocess.run(["git", "-C", SRC, "ls-files", "--cached", "--others", "--exclude-standard"],
                         capture_output=True, text=True)
    if out.returncode == 0 and out.stdout.strip():
        files = out.stdout.split()
    else:  # a source tree without git (a release tarball)
        files = []
        for root, dirs, names in os.walk(SRC):
            dirs[:] = [d for d in dirs if not d.startswith(".") and not d.startswith("build")]
            files += [os.path.relpath(os.path.join(root, n), SRC) for n in names]
    for f in sorted(files):
        if not f.endswith((".c", ".h", ".cpp")) or f.startswith(("osl/", "tests/data/")):
            continue
        with open(os.path.join(SRC, f), encoding="utf-8", errors="replace") as fh:
            if "GENERATED" in fh.readline():
                continue
        yield f


files = list(sources())
bad = []
for f in files:
    r = subprocess.run([TOOL, "--dry-run", "--Werror", "--style=file", os.path.join(SRC, f)],
                       capture_output=True, text=True)
    if r.returncode != 0:
        bad.append(f)
for f in bad:
    print("check_format: %s is not formatted (clang-format -i %s)" % (f, f))
print("check_format: %d files checked, %d not formatted" % (len(files), len(bad)))
if len(files) < 50:
    print("check_format: too few files found; the check would prove nothing")
    sys.exit(1)
sys.exit(1 if bad else 0)
