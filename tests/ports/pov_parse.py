"""Runs an SDL script in the real povray for its parse-time output only (a 1 x 1 image
that is not written): the tests evaluate the port's macros and functions at parse time
and print the values with #debug. Shared by test_pov_select.py and test_pov_belcour.py."""
import os
import subprocess


def parse_run(povray, inc_dir, work, name, lines):
    """Writes LINES to WORK/NAME, runs povray on it with INC_DIR on the library path, and
    returns its console output (stdout + stderr). POV-Ray wraps long console lines, so
    callers look for markers at the start of a line."""
    path = os.path.join(work, name)
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    p = subprocess.run([povray, "-D", "+I" + path, "+L" + inc_dir, "-F", "+W1", "+H1"],
                       capture_output=True, text=True)
    return p.stdout + p.stderr
