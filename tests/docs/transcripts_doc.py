"""transcripts_doc.py DOC BIN SRC - every transcript of a page (a fenced block of `$ command`
lines, each followed by lines it prints) still holds: the commands are run with the build's
programs (BIN) first on PATH, in a scratch folder that sees SRC's scenes/ and data/, and the
quoted lines must appear, in order, in what each prints (doc_check.check_transcripts)."""
import os

from doc_check import check_transcripts, guarded, main_args, read

doc_path, bin_dir, src = main_args("DOC BIN SRC", 3)
name = os.path.relpath(doc_path, src)


def body():
    n = check_transcripts(name, read(doc_path), bin_dir, src)
    print(f"{name}: {n} commands run")


guarded(os.path.splitext(os.path.basename(doc_path))[0].lower() + "_doc", body)
