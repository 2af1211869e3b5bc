#!/usr/bin/env python3
"""Build the Blender extension package (a .zip for Blender 4.2+, docs/OSL.md, "The Blender extension"):

  blender_manifest.toml     blender/'s, plus `platforms` and `wheels` for the bundled wheel
  __init__.py, abrdf_ext_*.py   the add-on (blender/)
  osl/                      the OSL port: every osl/*.h and *.osl, and osl/abrdf_cycles.py
  wheels/abrdf-*.whl        the abrdf Python package (`pip wheel .`), which the add-on uses
                            for the registry and the selection

usage: build_extension.py --wheel WHEEL|DIR -o OUT.zip [--source DIR]
(a directory: the one abrdf-*.whl in it)
The wheel must be for CPython 3.11 (the Python of Blender 4.2 to 5.0) and of the manifest's
version. The zip is reproducible: fixed timestamps and file order. What the CMake target
abrdf_blender_extension runs; Blender installs the zip with Install from Disk or
`blender --command extension install-file -r user_default FILE`.
"""
import argparse
import os
import re
import sys
import zipfile

# Wheel platform tags -> Blender's platform names.
PLATFORMS = [(r"(many)?linux.*_x86_64$", "linux-x64"), (r"(many)?linux.*_aarch64$", "linux-arm64"),
             (r"macosx_.*_arm64$", "macos-arm64"), (r"macosx_.*_x86_64$", "macos-x64"),
             (r"win_amd64$", "windows-x64"), (r"win_arm64$", "windows-arm64")]
BLENDER_PYTHON = "cp311"


def fail(msg):
    sys.exit("build_extension: " + msg)


def wheel_tags(path):
    """(version, python tag, platform) from a wheel's file name (PEP 427)."""
    m = re.match(r"abrdf-([^-]+)-([^-]+)-([^-]+)-([^-]+)\.whl$", os.path.basename(path))
    if not m:
        fail("%s is not an abrdf wheel (abrdf-VERSION-PY-ABI-PLATFORM.whl)" % path)
    return m.group(1), m.group(2), m.group(4)


def manifest_version(text):
    m = re.search(r'^version\s*=\s*"([^"]+)"', text, re.M)
    if not m:
        fail("blender_manifest.toml has no version")
    return m.group(1)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--wheel", required=True,
                    help="the abrdf wheel to bundle, or a directory holding exactly one")
    ap.add_argument("-o", "--out", required=True, help="the .zip to write")
    ap.add_argument("--source", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                    help="the source tree (default: this script's)")
    a = ap.parse_args(argv)
    blender = os.path.join(a.source, "blender")
    osl = os.path.join(a.source, "osl")
    with open(os.path.join(blender, "blender_manifest.toml")) as f:
        manifest = f.read()
    if os.path.isdir(a.wheel):
        found = [n for n in os.listdir(a.wheel) if n.startswith("abrdf-") and n.endswith(".whl")]
        if len(found) != 1:
            fail("%s holds %d abrdf wheels, not one" % (a.wheel, len(found)))
        a.wheel = os.path.join(a.wheel, found[0])
    version, py, plat = wheel_tags(a.wheel)
    if version != manifest_version(manifest):
        fail("the wheel is version %s, the manifest %s" % (version, manifest_version(manifest)))
    if py != BLENDER_PYTHON:
        fail("the wheel is for %s; Blender 4.2 to 5.0 run CPython 3.11: build it with a "
             "Python 3.11" % py)
    platforms = sorted({name for tag in plat.split(".") for pat, name in PLATFORMS
                        if re.search(pat, tag)})
    if not platforms:
        fail("no Blender platform for the wheel's platform tag %s" % plat)
    wheel_name = os.path.basename(a.wheel)
    manifest += ("\n# Added by blender/build_extension.py for the bundled wheel.\n"
                 "platforms = [%s]\nwheels = [\"./wheels/%s\"]\n"
                 % (", ".join('"%s"' % p for p in platforms), wheel_name))

    files = [(os.path.join(blender, n), n) for n in sorted(os.listdir(blender))
             if n.endswith(".py") and n != os.path.basename(__file__)]
    files += [(os.path.join(osl, n), "osl/" + n) for n in sorted(os.listdir(osl))
              if n.endswith((".h", ".osl")) or n == "abrdf_cycles.py"]
    files.append((a.wheel, "wheels/" + wheel_name))
    tmp = a.out + ".tmp"
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
        def add(name, data):
            info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
            info.external_attr = 0o644 << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(info, data)
        add("blender_manifest.toml", manifest)
        for src, name in files:
            with open(src, "rb") as f:
                add(name, f.read())
    os.replace(tmp, a.out)
    print("build_extension: %s (%d files, %s)" % (a.out, len(files) + 1, ", ".join(platforms)))


if __name__ == "__main__":
    main()
