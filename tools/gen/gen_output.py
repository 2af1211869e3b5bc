"""gen_output.py - how the Python generators write their files: whole or not at all, the same
rule as tools/common/out_file.h. Each file goes to a temporary file beside it (same directory,
same extension), is flushed, synced and closed, and only when every file of the run is
complete are they renamed over their targets; a failure removes the temporary files, leaves
existing targets as they were and exits 1 with "PROGRAM: FILE: reason". An output that is the
same file as an input (device and inode: "./x", symbolic and hard links) is refused, exit 2.

    write_all("gen_x", {out_path: text, ...}, inputs=[in_path, ...])
"""
import os
import sys
import tempfile


def _key(path):
    """(dev, ino) of the file, or of its directory and its name if it does not exist yet."""
    try:
        st = os.stat(path)
        return ("file", st.st_dev, st.st_ino)
    except FileNotFoundError:
        d = os.stat(os.path.dirname(path) or ".")
        return ("new", d.st_dev, d.st_ino, os.path.basename(path))


def write_all(program, outputs, inputs=()):
    keys = {}
    for path in inputs:
        try:
            keys[_key(path)] = path
        except OSError:
            pass  # an input that cannot be found fails where it is read
    for path in outputs:
        try:
            k = _key(path)
        except OSError:
            continue  # the directory is missing: creating the file reports it
        if k in keys:
            sys.stderr.write(f"{program}: {path} is the same file as {keys[k]}; nothing was "
                             "written\n")
            raise SystemExit(2)
        keys[k] = path
    temps = []
    path = "output"
    try:
        for path, text in outputs.items():
            target = os.path.realpath(path) if os.path.islink(path) else path
            directory, name = os.path.split(target)
            stem, ext = os.path.splitext(name)
            fd, temp = tempfile.mkstemp(prefix="." + stem + ".", suffix=ext, dir=directory or ".")
            temps.append((temp, target, path))
            with os.fdopen(fd, "w") as f:
                f.write(text)
                f.flush()
                os.fsync(f.fileno())
            if os.path.exists(target):
                os.chmod(temp, os.stat(target).st_mode & 0o7777)
            else:
                mask = os.umask(0)
                os.umask(mask)
                os.chmod(temp, 0o666 & ~mask)
        for temp, target, path in temps:
            os.replace(temp, target)
        temps = []
    except OSError as e:
        for temp, _, _ in temps:
            try:
                os.unlink(temp)
            except OSError:
                pass
        name = path  # the output being written or renamed when it failed
        sys.stderr.write(f"{program}: {name}: {e.strerror or e}\n")
        raise SystemExit(1)
