"""doc_links.py SRC - every reference to a documentation page can be followed:
  - a Markdown link or image in README.md or docs/*.md names a file that exists, and its
    #anchor a heading of that page (GitHub's anchors: lower case, punctuation dropped, spaces
    to hyphens, -1, -2, ... for repeated headings);
  - a page named in prose (docs/ and its name, or in a page its name alone) exists, in the
    pages and in the sources (comments, help texts, scripts, scenes, data);
  - a section quoted after a page name (the name, then `, "Section"` or ` ("Section"`) is
    a heading of that page, or part of one.
README.md's list of where the old pages went names pages that no longer exist, on purpose,
and tests/data/abi holds the 0.2.0 release's headers as they were released; both are left
out. CHANGELOG.md is not read: its entries name the pages of their day."""
import os
import re
import sys

from doc_check import FAILURES, fail, main_args, read

src = None  # the source tree, from the command line
OLD_PAGES = "Where the old pages went"
SOURCE_DIRS = ("libabrdf", "tools", "osl", "povray_macros", "python", "blender", "scenes", "tests",
               "examples", "scripts", "cmake", "data", ".ci")
SOURCE_FILES = ("CMakeLists.txt", "Makefile", "pyproject.toml")
SKIP = (os.path.join("tests", "data", "abi"),)
TEXT = (".c", ".h", ".cpp", ".py", ".osl", ".inc", ".pov", ".sh", ".toml", ".scene", ".csv",
        ".cmake", ".txt", "")


def slug(text):
    """GitHub's anchor of a heading: the rendered text (code spans, emphasis and link
    targets dropped), lower case, without punctuation, spaces as hyphens."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = text.replace("`", "").lower()
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def outside_fences(lines):
    """(line number, line) of the lines outside fenced code blocks."""
    fence = None
    for i, line in enumerate(lines, 1):
        s = line.lstrip()
        if fence:
            if s.startswith(fence):
                fence = None
            continue
        if s.startswith("```") or s.startswith("~~~"):
            fence = s[:3]
            continue
        yield i, line


def outside_code(lines):
    """(line number, line) of the lines outside fenced code blocks, code spans blanked."""
    for i, line in outside_fences(lines):
        yield i, re.sub(r"`[^`]*`", lambda m: " " * len(m[0]), line)


def headings(text):
    """[(heading text, anchor)] of a page, in order."""
    out, seen = [], {}
    for _, line in outside_fences(text.splitlines()):
        m = re.match(r"(#{1,6}) +(.*?) *#*$", line)
        if m:
            base = slug(m[2])
            n = seen.get(base, 0)
            seen[base] = n + 1
            out.append((m[2], base if n == 0 else f"{base}-{n}"))
    return out


_PAGES = {}
CHECKED = [0, 0, 0]  # links, page names, quoted sections


def page(path):
    """Headings of a Markdown file, read once; None when it does not exist."""
    if path not in _PAGES:
        _PAGES[path] = headings(read(path)) if os.path.isfile(path) else None
    return _PAGES[path]


def page_path(name):
    """The file a page name means: the page in docs/, else the file at the top of the tree."""
    name = name[5:] if name.startswith("docs/") else name
    for path in (os.path.join(src, "docs", name), os.path.join(src, name)):
        if os.path.isfile(path):
            return path
    return None


def plain_text(heading):
    return re.sub(r"[`*]", "", heading).lower()


def check_names(where, lineno, text, bare, limit=None):
    """Page names in prose (those that start before `limit`; the text may run on into the
    next line, where a quoted section may end), and the sections quoted after them."""
    pattern = r"(?<![\w/.-])((?:docs/)?[A-Z][A-Z0-9_]*\.md)\b" if bare else r"\b(docs/[A-Z][A-Z0-9_]*\.md)\b"
    for m in re.finditer(pattern, text):
        if limit is not None and m.start() >= limit:
            break
        path = page_path(m[1])
        CHECKED[1] += 1
        if path is None:
            fail(f"{where}:{lineno}: names {m[1]}, which does not exist")
            continue
        rest = text[m.end():]
        q = re.match(r"(?:,|,? section| \(| ) *\"([^\"]+)\"", rest)
        n = re.match(r",? section (\d+)\b", rest)
        if (q or n) and path.endswith(".md"):
            CHECKED[2] += 1
            heads = [plain_text(h) for h, _ in page(path)]
            if q and not any(plain_text(q[1]) in h for h in heads):
                fail(f"{where}:{lineno}: {m[1]} has no section \"{q[1]}\"")
            if n and not any(h.startswith(n[1] + ". ") for h in heads):
                fail(f"{where}:{lineno}: {m[1]} has no section {n[1]}")


def check_page(path):
    rel = os.path.relpath(path, src)
    lines = read(path).splitlines()
    old_pages = set()  # README's map of the old page names
    level = None
    for lineno, line in outside_code(lines):
        h = re.match(r"(#{1,6}) +(.*)", line)
        if h and level and len(h[1]) <= level:
            level = None
        if h and rel == "README.md" and h[2].startswith(OLD_PAGES):
            level = len(h[1])
        if level:
            old_pages.add(lineno)
    for lineno, line in enumerate(lines, 1):
        if lineno not in old_pages:
            prose = re.sub(r"\]\([^)]*\)", "]", line)  # a link's target is checked below
            check_names(rel, lineno, prose + " " + "".join(lines[lineno:lineno + 1]).strip(), True, len(prose))
    text = [""] * len(lines)  # outside code, for the links (whose text may span lines)
    for lineno, line in outside_code(lines):
        text[lineno - 1] = line
    text = "\n".join(text)
    for m in re.finditer(r"!?\[[^\]]*\]\(([^)\s]+)\)", text):
        lineno = text.count("\n", 0, m.start()) + 1
        target = m[1]
        if re.match(r"[a-z]+:", target):
            continue
        file, _, anchor = target.partition("#")
        CHECKED[0] += 1
        dest = os.path.normpath(os.path.join(os.path.dirname(path), file)) if file else path
        if not os.path.exists(dest):
            fail(f"{rel}:{lineno}: link to {file}, which does not exist")
            continue
        if anchor:
            heads = page(dest) if dest.endswith(".md") else None
            if heads is None or anchor not in {a for _, a in heads}:
                fail(f"{rel}:{lineno}: link to {target}: {os.path.relpath(dest, src)} has no heading "
                     f"with the anchor #{anchor}")


def check_sources():
    files = [os.path.join(src, f) for f in SOURCE_FILES]
    for d in SOURCE_DIRS:
        for root, dirs, names in os.walk(os.path.join(src, d)):
            dirs[:] = [x for x in dirs if not os.path.relpath(os.path.join(root, x), src).startswith(SKIP)
                       and x != "__pycache__"]
            files += [os.path.join(root, n) for n in names if os.path.splitext(n)[1] in TEXT]
    for path in sorted(files):
        if not os.path.isfile(path):
            continue
        try:
            text = read(path)
        except UnicodeDecodeError:
            continue
        rel = os.path.relpath(path, src)
        for m in re.finditer(r"docs/[A-Z][A-Z0-9_]*\.md", text):
            # the name and what follows it, comment markers and line breaks dropped (a quoted
            # section may continue on the next line of a comment)
            after = re.sub(r"\s*(//|#|\*)\s*|\s+", " ", text[m.start():m.start() + 300]).replace('\\"', '"')
            check_names(rel, text.count("\n", 0, m.start()) + 1, after, False, 1)


def main():
    global src
    (src,) = main_args("SRC", 1)
    pages = [os.path.join(src, "README.md")] + sorted(
        os.path.join(src, "docs", f) for f in os.listdir(os.path.join(src, "docs")) if f.endswith(".md"))
    for p in pages:
        check_page(p)
    check_sources()
    for f in FAILURES:
        print(f"doc_links: {f}", file=sys.stderr)
    if FAILURES:
        print(f"doc_links: {len(FAILURES)} reference(s) lead nowhere", file=sys.stderr)
        sys.exit(1)
    print(f"doc_links: {len(pages)} pages and the sources checked, {CHECKED[0]} links and "
          f"{CHECKED[1]} page names followed, {CHECKED[2]} of them with a section")


if __name__ == "__main__":
    main()
