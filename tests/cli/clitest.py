"""What the CLI tests share (imported from the tests' own directory, which Python puts first
on the module path when CTest runs a test script): a test case with a temporary directory,
reading a text file, and the check that a run's stderr holds no sanitizer report."""
import os
import tempfile
import unittest


class TempDirCase(unittest.TestCase):
    """A fresh temporary directory per test, self.dir, removed afterwards."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def path(self, name):
        return os.path.join(self.dir, name)

    def put(self, name, data):
        """Writes data (bytes or text) to the file name in self.dir; returns its path."""
        with open(self.path(name), "wb" if isinstance(data, bytes) else "w") as f:
            f.write(data)
        return self.path(name)


def read_text(path):
    with open(path) as f:
        return f.read()


def checked_stderr(p):
    """The stderr (bytes) of the finished process p as text, once it is known to hold no
    AddressSanitizer/UndefinedBehaviorSanitizer report."""
    err = p.stderr.decode("utf-8", "replace")
    assert "Sanitizer" not in err and "runtime error" not in err, err
    return err
