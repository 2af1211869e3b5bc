"""doc_check.py - what the *_doc checks share: run a program, and hold a document's quoted
numbers to what it prints. A check fails with the document's line, the quoted text and what
the program printed instead, so the fix (paste the new output) is obvious.

Three ways a document quotes a program:
  - verbatim lines (a pasted table or listing): `require_lines`;
  - a transcript, a fenced block whose lines start with `$ ` (the command, run as written)
    followed by the lines it prints: `check_transcripts`;
  - a number in prose or in a hand-made table: `require_number`, which accepts the document's
    figure when it is the program's value rounded to the figure's own last digit."""
import math
import os
import re
import subprocess
import sys
import tempfile


class DocError(Exception):
    pass


FAILURES = []


def fail(msg):
    FAILURES.append(msg)


def finish(name):
    """Print the verdict; exit 1 on any failure."""
    if FAILURES:
        for f in FAILURES:
            print(f"{name}: {f}\n", file=sys.stderr)
        print(f"{name}: {len(FAILURES)} quoted figure(s) differ from what the programs print now; "
              "re-run the commands the document names and paste their output", file=sys.stderr)
        sys.exit(1)
    print(f"{name}: every checked figure agrees with its program")


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


_RUNS = {}


def run(cmd, cwd=None):
    """Run a command (list), return its stdout; a failure to run is a check failure. A
    command is run once per check (the programs are deterministic)."""
    key = (tuple(cmd), cwd)
    if key not in _RUNS:
        p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=600)
        if p.returncode != 0:
            raise DocError(f"`{' '.join(cmd)}` exited with {p.returncode}:\n{p.stderr[-2000:]}")
        _RUNS[key] = p.stdout
    return _RUNS[key]


def section(doc, title):
    """The document with only the section whose heading starts with `title` left (to the next
    heading of its level or above); the other lines are blanked, so line numbers stay the
    page's. A page quotes several programs, one section each."""
    lines, keep, level, fence, found = doc.splitlines(), [], None, False, False
    for line in lines:
        if line.lstrip().startswith("```"):
            fence = not fence
        m = None if fence else re.match(r"(#+) (.*)", line)
        if m and level and len(m[1]) <= level:
            level = None
        if m and level is None and m[2].startswith(title) and not found:
            level, found = len(m[1]), True
        keep.append(level is not None)
    if not found:
        raise DocError(f"no section '{title}'")
    return "\n".join(l if k else "" for l, k in zip(lines, keep)) + "\n"


def line_of(doc, text):
    i = doc.find(text)
    return doc.count("\n", 0, i) + 1 if i >= 0 else 0


def quoted(doc, line):
    """The document has this line as one of its own (trailing blanks aside); a Markdown
    heading may sit at another level."""
    lines = {l.rstrip() for l in doc.splitlines()}
    if line.rstrip() in lines:
        return True
    if line.startswith("#"):
        return line.lstrip("#").strip() in {l.lstrip("#").strip() for l in lines if l.startswith("#")}
    return False


def require_lines(doc_name, doc, output, what, also=None):
    """Every non-empty line of `output` is a line of the document; `also(line)` may accept a
    line another way. Returns the number checked."""
    n = 0
    for line in output.splitlines():
        line = line.rstrip()
        if not line:
            continue
        n += 1
        if not quoted(doc, line) and not (also and also(line)):
            fail(f"{doc_name} does not quote this line of {what}:\n  {line}")
    if n == 0:
        fail(f"{what} printed nothing to compare")
    return n


# ---- numbers ---------------------------------------------------------------------------

NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def half_unit(text):
    """Half a unit of the last printed digit of a decimal string ("0.027" -> 5e-4,
    "3.7e-16" -> 5e-18, "1248" -> 0.5)."""
    m = re.fullmatch(r"[-+]?(\d*)(?:\.(\d*))?(?:[eE]([-+]?\d+))?", text.strip())
    if not m:
        raise ValueError(text)
    decimals = len(m.group(2) or "")
    exp = int(m.group(3) or 0)
    return 0.5 * 10.0 ** (exp - decimals)


def agrees(quoted, value, sig=None):
    """The quoted figure is `value` rounded to the figure's last digit (a quoted 0 must be 0).
    `value` is a float, or a string as the program printed it: its own rounding is allowed
    for, at its last digit, or at `sig` significant digits for a `%.<sig>g` format (which
    drops trailing zeros)."""
    q, v = float(quoted), float(value)
    slack = 0.0
    if isinstance(value, str) and v != 0:
        slack = 0.5 * 10.0 ** (math.floor(math.log10(abs(v))) - sig + 1) if sig else half_unit(value)
    tol = (half_unit(quoted) if q != 0 else 0.0) + slack
    return q == v or abs(q - v) < tol * (1 - 1e-9)  # at the edge the true value would round away


def round_sig(value, digits):
    """value rounded to `digits` significant digits (101.6, 2 -> 100.0)."""
    return 0.0 if value == 0 else round(value, digits - 1 - math.floor(math.log10(abs(value))))


def require_number(doc_name, doc, quoted, value, what, sig=None):
    try:
        ok = agrees(quoted, value, sig)
    except (TypeError, ValueError):
        ok = False
    if not ok:
        fail(f"{doc_name}:{line_of(doc, quoted)}: {what}: the document says {quoted}, "
             f"the program gives {value}")


def parse_table(lines, start):
    """Markdown table starting at lines[start] -> (header cells, rows of cells, end)."""
    def cells(l):
        return [c.strip() for c in l.strip().strip("|").split("|")]
    head = cells(lines[start])
    rows, i = [], start + 2
    while i < len(lines) and lines[i].startswith("|"):
        rows.append(cells(lines[i]))
        i += 1
    return head, rows, i


# ---- transcripts -----------------------------------------------------------------------

def transcripts(doc):
    """Fenced blocks that start with `$ `: [(line number, [(command, [expected lines])])]."""
    out, lines, i = [], doc.splitlines(), 0
    while i < len(lines):
        if lines[i].lstrip().startswith("```"):
            indent = len(lines[i]) - len(lines[i].lstrip())  # a block inside a list item
            j = i + 1
            while j < len(lines) and not lines[j].lstrip().startswith("```"):
                j += 1
            body = [l[indent:] for l in lines[i + 1:j]]
            if body and body[0].startswith("$ "):
                steps = []
                for l in body:
                    if l.startswith("$ "):
                        steps.append((l[2:], []))
                    else:
                        steps[-1][1].append(l.rstrip())
                out.append((i + 2, steps))
            i = j
        i += 1
    return out


def matches(expected, got):
    """A line matches itself; `...` alone matches nothing (an elision); a line ending in `...`
    matches any line that starts with the text before it."""
    if expected.endswith("...") and expected != "...":
        return got.startswith(expected[:-3])
    return got == expected


def check_transcripts(doc_name, doc, bin_dir, src_dir):
    """Run every `$ ` command of the document (in a scratch folder that sees the tree's scenes/
    and data/, with the build's programs first on PATH) and require the lines quoted under it,
    in their order, in what it prints (stdout, then stderr). `$ echo $?` prints the previous
    command's exit status. Returns the number of commands run."""
    env = dict(os.environ, PATH=bin_dir + os.pathsep + os.environ.get("PATH", ""))
    count = 0
    with tempfile.TemporaryDirectory(prefix="doc_transcript_") as work:
        for d in ("scenes", "data"):
            os.symlink(os.path.join(src_dir, d), os.path.join(work, d))
        for line, steps in transcripts(doc):
            status = 0
            for cmd, expected in steps:
                count += 1
                if cmd.strip() == "echo $?":
                    printed = [str(status)]
                else:
                    p = subprocess.run(["bash", "-c", cmd], cwd=work, env=env, capture_output=True,
                                       text=True, timeout=600)
                    status = p.returncode
                    printed = [l.rstrip() for l in (p.stdout + p.stderr).splitlines()]
                k = 0
                for e in expected:
                    if e == "...":
                        continue
                    while k < len(printed) and not matches(e, printed[k]):
                        k += 1
                    if k == len(printed):
                        shown = "\n".join("    " + l for l in printed[:80])
                        fail(f"{doc_name}:{line}: `{cmd}` does not print (in this order):\n  {e}\n"
                             f"  it printed:\n{shown}")
                        break
                    k += 1
    if count == 0:
        fail(f"{doc_name} has no `$ ` transcript")
    return count


def main_args(usage, n):
    """The command line: n paths (programs, folders), made absolute."""
    if len(sys.argv) != n + 1:
        print(f"usage: {os.path.basename(sys.argv[0])} {usage}", file=sys.stderr)
        sys.exit(2)
    return [os.path.abspath(a) for a in sys.argv[1:]]


def guarded(name, body):
    """Run body(); a program that cannot run is a failure, not a crash with a traceback."""
    try:
        body()
    except DocError as e:
        fail(str(e))
    finish(name)

