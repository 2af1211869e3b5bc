"""transcripts_doc.py DOC BIN SRC [--only SECTION | --skip SECTION] - every transcript of a page
(a fenced block of `$ command` lines, each followed by lines it prints) still holds: the
commands are run with the build's programs (BIN) first on PATH, in a scratch folder that sees
SRC's scenes/ and data/, and the quoted lines must appear, in order, in what each prints
(doc_check.check_transcripts). --only runs the transcripts of one section of the page (its
heading's start), --skip those of the rest, so two tests can share a page."""
import os
import sys

from doc_check import check_transcripts, guarded, main_args, read, section

options = sys.argv[4:]
del sys.argv[4:]
doc_path, bin_dir, src = main_args("DOC BIN SRC [--only SECTION | --skip SECTION]", 3)
name = os.path.relpath(doc_path, src)
if options and not (len(options) == 2 and options[0] in ("--only", "--skip")):
    print("usage: transcripts_doc.py DOC BIN SRC [--only SECTION | --skip SECTION]", file=sys.stderr)
    sys.exit(2)


def body():
    doc = read(doc_path)
    if options:
        part = section(doc, options[1])
        if options[0] == "--only":
            doc = part
        else:  # the page with that section blanked, lines kept where they were
            doc = "\n".join("" if p else l for l, p in zip(doc.splitlines(), part.splitlines())) + "\n"
    n = check_transcripts(name, doc, bin_dir, src)
    print(f"{name}: {n} commands run" + (f" ({options[0][2:]} '{options[1]}')" if options else ""))


guarded(os.path.splitext(os.path.basename(doc_path))[0].lower() + "_doc", body)
