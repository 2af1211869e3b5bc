"""What the package takes from its caller: image files by the command's rules (regular files
only, a header's cost bounded before anything is allocated) and numbers only, never cast into
numbers (complex, datetime, bool, strings, None refused with TypeError)."""
import os
import struct
import subprocess
import sys
import zlib

import numpy as np
import pytest

import abrdf

WI, WO = [0.3, 0.0, 1.0], [-0.2, 0.1, 1.0]

# A child that runs image reads and prints one line per call: the abrdf.Error's message, or
# "read HxW". Its address space may grow by at most GROW bytes past what the imports took.
CHILD = r"""
import resource, sys
import numpy as np
import abrdf
GROW = 1 << 30
with open("/proc/self/status") as f:
    vm = next(int(l.split()[1]) * 1024 for l in f if l.startswith("VmSize:"))
resource.setrlimit(resource.RLIMIT_AS, (vm + GROW, resource.RLIM_INFINITY))
calls = {"read": lambda p: abrdf.read_image(p),
         "compare": lambda p: abrdf.compare(p, np.zeros((2, 2, 3), np.float32))}
for arg in sys.argv[1:]:
    how, path = arg.split(":", 1)
    try:
        img = calls[how](path)
        print("read %dx%d" % img.shape[:2])
    except abrdf.Error as e:
        print(e)
# the peak RSS of this process's own image (VmHWM, KiB): getrusage's ru_maxrss is kept across
# the exec that started it, so it also counts the pages of the parent it was forked from
with open("/proc/self/status") as f:
    print("maxrss %d" % next(int(l.split()[1]) for l in f if l.startswith("VmHWM:")))
"""


def run_child(*calls):
    """The child's lines for these calls ("read:PATH", "compare:PATH") and its own peak RSS
    in KiB; a call that blocks fails the test at the timeout instead of hanging it."""
    r = subprocess.run([sys.executable, "-c", CHILD, *calls], capture_output=True, text=True,
                       timeout=60)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    return lines[:-1], int(lines[-1].split()[1])


def write_image(path, pixels, fmt="float", **attrs):
    import OpenImageIO as oiio
    h, w, nch = pixels.shape
    spec = oiio.ImageSpec(w, h, nch, fmt)
    for k, v in attrs.items():  # a field of ImageSpec (x, tile_width, ...) or an attribute
        if hasattr(spec, k):
            setattr(spec, k, v)
        else:
            spec.attribute(k, v)
    out = oiio.ImageOutput.create(str(path))
    assert out.open(str(path), spec) and out.write_image(pixels) and out.close()


def exr_header_only(path, width, height, channels):
    """An EXR whose header declares width x height x channels half pixels and that ends with
    its header: no offset table, no pixels (a few hundred bytes)."""
    write_image(path, np.ones((16, 16, channels), np.float32), "half", compression="none")
    b = bytearray(path.read_bytes())
    end = 8  # magic and version; then attributes name\0 type\0 size value, up to a \0
    while b[end]:
        end = b.index(b"\0", b.index(b"\0", end) + 1) + 1
        end += 4 + struct.unpack_from("<i", b, end)[0]
    for name in (b"dataWindow\0box2i\0", b"displayWindow\0box2i\0"):
        at = b.index(name) + len(name) + 4
        b[at:at + 16] = struct.pack("<4i", 0, 0, width - 1, height - 1)
    path.write_bytes(bytes(b[:end + 1]))


def png_header_only(path, width, height):
    """An 8-bit RGB PNG whose header (IHDR, its CRC fixed) declares width x height and whose
    pixels are those of a 16 x 16 image: a truncated file."""
    write_image(path, np.zeros((16, 16, 3), np.uint8), "uint8")
    b = bytearray(path.read_bytes())
    at = b.index(b"IHDR")
    struct.pack_into(">II", b, at + 4, width, height)
    struct.pack_into(">I", b, at + 17, zlib.crc32(bytes(b[at:at + 17])))
    path.write_bytes(bytes(b))


# ---- files: the command's rules ---------------------------------------------------------

def test_a_fifo_is_refused_at_once(tmp_path):
    # Opening a FIFO for reading waits for a writer: the child would hang until the timeout.
    fifo = tmp_path / "pipe.exr"
    os.mkfifo(fifo)
    lines, _ = run_child("read:%s" % fifo, "compare:%s" % fifo)
    assert lines == ["%s: is a FIFO, not a regular file" % fifo] * 2


def test_what_is_not_a_regular_file(tmp_path):
    cases = [(tmp_path, "is a directory, not a file"),
             (tmp_path / "missing.exr", "cannot open: No such file or directory")]
    if os.path.exists("/dev/null"):
        cases.append(("/dev/null", "is a character device, not a regular file"))
    for path, why in cases:
        for call in (abrdf.read_image, lambda p: abrdf.compare(p, p)):
            with pytest.raises(abrdf.Error) as e:
                call(path)
            assert str(e.value) == "%s: %s" % (path, why)
            assert e.value.status is None


@pytest.mark.parametrize("width,height", [(8192, 8192), (8192, 4096)])
def test_a_header_declaring_a_huge_image(tmp_path, width, height):
    # The file: 12 channels, no pixels. Reading every channel as float would take
    # 3.2 GB (1.6 GB for the smaller one); the child may grow by 1 GiB. OpenImageIO 3.x
    # itself refuses the larger claim at open; the smaller one reaches the strips, whose
    # first fails.
    path = tmp_path / "header.exr"
    exr_header_only(path, width, height, 12)
    assert path.stat().st_size < 4096
    lines, maxrss_kib = run_child("read:%s" % path, "compare:%s" % path)
    for line in lines:
        assert line.startswith("%s: " % path) and "memory" not in line and "alloc" not in line
    assert maxrss_kib < 512 * 1024


def test_the_reader_limit(tmp_path, monkeypatch):
    # 16400 x 16400 x 3 floats: 3.2 GB, over the limit before anything is allocated.
    big = tmp_path / "big.png"
    png_header_only(big, 16400, 16400)
    with pytest.raises(abrdf.Error) as e:
        abrdf.read_image(big)
    assert str(e.value) == ("%s: 16400x16400 pixels x 3 channels as 32-bit floats need "
                            "3227520000 bytes, over the image reader's limit of 1073741824 "
                            "bytes" % big)
    # Under the limit, a truncated file fails reading, after its first strip.
    short = tmp_path / "short.png"
    png_header_only(short, 8192, 8192)
    lines, maxrss_kib = run_child("read:%s" % short)
    assert lines[0].startswith("%s: " % short) and maxrss_kib < 512 * 1024
    # The limit counts the channels read: RGB of 12, grey of grey + alpha.
    rgb12, grey = tmp_path / "rgb12.exr", tmp_path / "grey.png"
    write_image(rgb12, np.ones((16, 16, 12), np.float32))
    write_image(grey, np.zeros((16, 16, 2), np.uint8), "uint8", alpha_channel=1)
    monkeypatch.setattr(abrdf._compare, "_MAX_BYTES", 16 * 16 * 3 * 4)
    assert abrdf.read_image(rgb12).shape == (16, 16, 3)
    monkeypatch.setattr(abrdf._compare, "_MAX_BYTES", 16 * 16 * 4 - 1)
    for path, used in ((rgb12, 3), (grey, 1)):
        with pytest.raises(abrdf.Error) as e:
            abrdf.read_image(path)
        assert "16x16 pixels x %d channels as 32-bit floats need %d bytes, over the image " \
               "reader's limit of 1023 bytes" % (used, 16 * 16 * used * 4) in str(e.value)


def test_strips_and_tiles_read_the_whole_image(tmp_path):
    # Strips of 64 rows, tiles of 16 rows, a data window off the origin, 5 channels.
    rng = np.random.default_rng(3)
    px = rng.random((150, 70, 5)).astype(np.float32)
    flat, tiled = tmp_path / "flat.exr", tmp_path / "tiled.exr"
    write_image(flat, px)
    write_image(tiled, px, x=3, y=-2, tile_width=32, tile_height=16)
    for path in (flat, tiled):
        img = abrdf.read_image(path)
        assert img.dtype == np.float32 and np.array_equal(img, px[..., :3])
    # A file cut in its pixels fails, naming it.
    big = tmp_path / "cut.exr"
    write_image(big, rng.random((512, 256, 3)).astype(np.float32), compression="none")
    cut = big.read_bytes()
    big.write_bytes(cut[:len(cut) // 2])
    with pytest.raises(abrdf.Error) as e:
        abrdf.read_image(big)
    assert str(e.value).startswith("%s: " % big)


# ---- numbers only ---------------------------------------------------------------------

NOT_NUMBERS = [
    (np.array(WI, complex), "complex128"),
    (np.array([0, 0, 1], "datetime64[s]"), "datetime64[s]"),
    (np.array([0, 0, 1], "timedelta64[s]"), "timedelta64[s]"),
    ([0, None, 1], "object"),
    (["0", "0", "1"], "<U1"),
    (np.array([b"0", b"0", b"1"]), "|S1"),
    ([False, False, True], "bool"),
]


@pytest.mark.parametrize("bad,dtype", NOT_NUMBERS)
def test_directions_are_numbers(bad, dtype):
    b = abrdf.BRDF("lambert")
    for call, what in ((lambda: abrdf.eval("lambert", bad, WO), "wi"),
                       (lambda: b.eval(WI, bad), "wo"),
                       (lambda: b.eval(bad, WO, precision="double"), "wi")):
        with pytest.raises(TypeError) as e:
            call()
        assert str(e.value) == "%s: a real number array is needed, got %s" % (what, dtype)


@pytest.mark.parametrize("bad,dtype", NOT_NUMBERS)
def test_images_are_numbers(bad, dtype):
    img = np.ones((1, 3), np.float32)
    bad = np.asarray(bad).reshape(1, 3)
    with pytest.raises(TypeError, match="^test: a real number array is needed, got "):
        abrdf.compare(img, bad)
    with pytest.raises(TypeError, match="^reference: a real number array is needed, got "):
        abrdf.compare(bad, img)


def test_complex_images_are_not_compared_on_their_real_part():
    # They used to compare at NMSE 0, with a ComplexWarning only.
    a = np.ones((2, 2, 3))
    with pytest.raises(TypeError, match="complex128"):
        abrdf.compare(a + 0j, a + 1j)


def test_integers_are_numbers():
    want = abrdf.eval("disney_specular", [0.0, 0, 1], [0.0, 0.6, 0.8], r=0.3)
    for dtype in (np.int8, np.int64, np.uint16):
        got = abrdf.eval("disney_specular", np.array([0, 0, 1], dtype),
                         np.array([0, 3, 4], dtype), r=0.3)
        assert got.dtype == np.float32 and np.allclose(got, want, rtol=1e-6)
    assert abrdf.compare(np.ones((2, 2), np.uint8), np.full((2, 2), 2, np.int32)).nmse == 1.0
    # Parameters: NumPy's integer and floating scalars are numbers too.
    assert abrdf.BRDF("disney_specular", r=np.float32(0.25), f0=np.int64(1)).params["r"] == 0.25
    assert abrdf.BRDF("lambert", kd=np.array([0.5, 0.25, 1], np.float32)).params["kd"] == \
        (0.5, 0.25, 1.0)


@pytest.mark.parametrize("bad", [
    0.3 + 0j, np.complex128(0.3), np.complex64(0.3), None, "0.3", b"0.3", True, np.bool_(True),
    np.datetime64(1, "s"), np.timedelta64(1, "s"),
], ids=lambda v: type(v).__name__)
def test_parameters_are_numbers(bad):
    t = type(bad)
    why = "a real number is needed, got %s" % (
        t.__name__ if t.__module__ == "builtins" else "%s.%s" % (t.__module__, t.__name__))
    with pytest.raises(TypeError) as e:
        abrdf.BRDF("disney_specular", r=bad)
    assert str(e.value) == "parameter 'r': " + why
    with pytest.raises(TypeError) as e:
        abrdf.BRDF("disney_specular", f0=(0.9, bad, 0.3))
    assert str(e.value) == "parameter 'f0': " + why
    with pytest.raises(TypeError) as e:
        abrdf.eval("disney_specular", WI, WO, r=bad)
    assert str(e.value) == "parameter 'r': " + why
    if bad is None:  # None leaves a material's field, a budget, a tolerance at its default
        return
    with pytest.raises(TypeError) as e:
        abrdf.select(abrdf.Material(r=bad))
    assert str(e.value) == "r: " + why
    with pytest.raises(TypeError, match="^max_rel_error: a real number is needed"):
        abrdf.select("gold", goal="performance", max_rel_error=bad)
    if not isinstance(bad, str):  # a string budget is a Table-8 class
        with pytest.raises(TypeError, match="^budget: a real number is needed"):
            abrdf.budget_nmse(bad)
