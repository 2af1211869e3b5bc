"""The house rules of the source tree, checked (README.md, "Layout"):

  1. no two compiled files depend on each other in a circle: the object files of the library
     and the tools, linked by the symbols one defines and another uses (nm), have no cycle;
  2. no header includes itself through others (C headers and the OSL port);
  3. every OSL header uses only functions and macros that it defines or includes, directly or
     through what it includes (so none depends on its includer);
  4. one name per file across the tree (except the names a tool requires: CMakeLists.txt,
     and __init__.py, which Python and Blender require of a package);
  5. tests link targets: no CMakeLists.txt under tests/ names a source file outside tests/;
  6. the library's folders (libabrdf/src/*/, one concern each) are layered: no two of them
     include or call each other in a circle.

usage: check_structure.py SOURCE_DIR OBJECT_FILE...
"""
import os
import re
import subprocess
import sys

SRC = sys.argv[1]
OBJECTS = [o for a in sys.argv[2:] for o in a.split(";") if o]  # CTest passes lists joined
problems = []


def cycles(graph):
    """Strongly connected components with more than one node (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in list(graph):
        if v not in index:
            visit(v)
    return out


def source_name(obj):
    """tools/cli/CMakeFiles/abrdf_cli.dir/cmd_eval.c.o -> cmd_eval.c"""
    base = os.path.basename(obj)
    return base[:-2] if base.endswith(".o") else base


# ---- 1. object files --------------------------------------------------------------------
defined, used = {}, {}
for obj in OBJECTS:
    name = source_name(obj)
    out = subprocess.run(["nm", obj], capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 2 and parts[0] == "U":
            used.setdefault(name, set()).add(parts[1])
        elif len(parts) == 3 and parts[1] in "TDBR":
            defined.setdefault(parts[2], set()).add(name)
graph = {}
for name, syms in used.items():
    for s in syms:
        for d in defined.get(s, ()):
            if d != name:
                graph.setdefault(name, set()).add(d)
for comp in cycles(graph):
    problems.append("object files depend on each other in a circle: " + " <-> ".join(comp))
if len(used) < 10:
    problems.append("only %d object files given: the check would prove nothing" % len(used))


# ---- 2. and 3. headers ----------------------------------------------------------------------
def tracked():
    out = subprocess.run(["git", "-C", SRC, "ls-files", "--cached", "--others", "--exclude-standard"], capture_output=True, text=True)
    if out.returncode == 0 and out.stdout.strip():
        return sorted(set(out.stdout.split()))  # a file in a merge is listed once per stage
    files = []
    for root, dirs, names in os.walk(SRC):
        dirs[:] = [d for d in dirs if not d.startswith(".") and not d.startswith("build")]
        files += [os.path.relpath(os.path.join(root, n), SRC) for n in names]
    return files


files = tracked()
by_name = {os.path.basename(f): f for f in files}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
include_graph = {}
for f in files:
    if f.endswith((".h", ".c", ".cpp", ".osl")) and not f.startswith("tests/"):
        with open(os.path.join(SRC, f), encoding="utf-8", errors="replace") as fh:
            text = fh.read()
        d = os.path.dirname(f)
        for inc in INCLUDE.findall(text):
            target = os.path.normpath(os.path.join(d, inc))
            if target not in files:  # found on an include path: names are unique (rule 4)
                target = by_name.get(inc)
            if target in files:
                include_graph.setdefault(f, set()).add(target)
for comp in cycles(include_graph):
    problems.append("headers include each other in a circle: " + " <-> ".join(comp))

osl = [f for f in files if f.startswith("osl/") and f.endswith((".h", ".osl"))]
BUILTIN_CALL = re.compile(r"\b(abrdf_\w+|ABRDF_\w+)\b")
FUNC_DEF = re.compile(r"^(?:\w+\s+)+(abrdf_\w+)\s*\(", re.M)
STRUCT_DEF = re.compile(r"^struct\s+(abrdf_\w+)", re.M)
MACRO_DEF = re.compile(r"^\s*#\s*define\s+(ABRDF_\w+)", re.M)
texts, defs = {}, {}
for f in osl:
    with open(os.path.join(SRC, f), encoding="utf-8", errors="replace") as fh:
        text = fh.read()
    # comments and strings do not use anything
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r'"(?:\\.|[^"\\])*"', '""', text)
    texts[f] = text
    defs[f] = set(FUNC_DEF.findall(text)) | set(STRUCT_DEF.findall(text)) | set(MACRO_DEF.findall(text))
owner = {}
for f, names in defs.items():
    for n in names:
        owner.setdefault(n, f)


def reachable(f, seen=None):
    seen = seen if seen is not None else set()
    if f in seen:
        return seen
    seen.add(f)
    for g in include_graph.get(f, ()):
        reachable(g, seen)
    return seen


for f in osl:
    visible = set()
    for g in reachable(f):
        visible |= defs.get(g, set())
    missing = sorted({n for n in BUILTIN_CALL.findall(texts[f])
                      if n in owner and n not in visible})
    if missing:
        problems.append("%s uses %s without including %s" %
                        (f, ", ".join(missing[:4]), ", ".join(sorted({owner[n] for n in missing}))))

# ---- 4. one name per file -------------------------------------------------------------
seen = {}
for f in files:
    base = os.path.basename(f)
    if base in ("CMakeLists.txt", "__init__.py"):
        continue
    if base in seen:
        problems.append("two files named %s: %s and %s" % (base, seen[base], f))
    seen[base] = f

# ---- 5. tests link targets ------------------------------------------------------------
TARGET_CALL = re.compile(r"\b(?:add_executable|add_library|abrdf_check_test|target_sources)\s*\(([^)]*)\)")
SOURCE_REF = re.compile(r"\$\{PROJECT_SOURCE_DIR\}/(?!tests/)[\w/.-]+\.(?:c|cpp)\b")
for f in files:
    if f.startswith("tests/") and os.path.basename(f) == "CMakeLists.txt":
        with open(os.path.join(SRC, f), encoding="utf-8") as fh:
            for call in TARGET_CALL.finditer(fh.read()):
                for m in SOURCE_REF.finditer(call.group(1)):
                    problems.append("%s compiles another target's source %s" % (f, m.group(0)))

# ---- 6. the library's folders are layered -----------------------------------------------
LIB = "libabrdf/src/"


def lib_folder(path):
    """libabrdf/src/core/api.c -> libabrdf/src/core/; None outside the library's folders."""
    if path and path.startswith(LIB) and path.count("/") == 3:
        return LIB + path.split("/")[2] + "/"
    return None


folder_graph, folder_why = {}, {}
edges = [(a, b) for a, bs in include_graph.items() for b in bs]
edges += [(by_name.get(a), by_name.get(b)) for a, bs in graph.items() for b in bs]
for a, b in edges:
    fa, fb = lib_folder(a), lib_folder(b)
    if fa and fb and fa != fb:
        folder_graph.setdefault(fa, set()).add(fb)
        folder_why.setdefault((fa, fb), "%s -> %s" % (a, b))
for comp in cycles(folder_graph):
    ties = ["%s -> %s (%s)" % (k[0], k[1], v) for k, v in sorted(folder_why.items())
            if k[0] in comp and k[1] in comp]
    problems.append("the library's folders use each other in a circle: " + "; ".join(ties))
if len(folder_graph) < 2:
    problems.append("no folders found under %s: the layering check would prove nothing" % LIB)

for p in problems:
    print("check_structure: " + p)
print("check_structure: %d object files, %d headers, %d OSL files, %d tracked files: %s" %
      (len(used), len(include_graph), len(osl), len(files), "FAIL" if problems else "ok"))
sys.exit(1 if problems else 0)
