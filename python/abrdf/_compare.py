"""Image comparison: compare() and read_image(), as `abrdf compare` does them.

The metrics are the command's C code (tools/image/metrics.c, in the extension module). Files
are read with OpenImageIO's Python bindings (the PyPI package OpenImageIO, a dependency of
this package), by the rules of the command's reader (tools/image/image_io.cpp): RGB from the
first three channels, grey replicated, alpha dropped; display-referred files (tagged sRGB, or
untagged integer pixels: 8/16-bit PNG, JPEG, TIFF) decoded to scene-linear by OpenImageIO's
colour conversion from sRGB (OpenColorIO's optimised path, within 2.5e-4 relative of the
exact curve per sample; the command's OpenColorIO decodes 8-bit values exactly), float files
(EXR, HDR, float TIFF) taken as scene-linear.

Files are taken as the command takes its inputs (tools/common/in_file.c): anything but a
regular file (a FIFO, a directory, a device) is refused with abrdf.Error before it is opened
for reading, so a FIFO never blocks. A header is checked before anything is allocated for
it: width x height x the channels used (3 for colour, 1 for grey; alpha and extra channels
are never read) x 4 bytes must be at most 1 GiB, the command's limit, and the pixels are
read in strips of rows, so a truncated file fails after reading what it holds. Arrays are
numbers only (integer or floating dtypes): complex, datetime, bool, string and object
arrays raise TypeError.
"""
from __future__ import annotations

import os
import re
import stat
from dataclasses import dataclass
from typing import Any, Union

import numpy as np
import numpy.typing as npt

from . import _abrdf
from ._arrays import real_array

PathLike = Union[str, "os.PathLike[str]"]
ImageLike = Union[PathLike, npt.ArrayLike]

# The sRGB-encoded space under the names OpenImageIO gives it (2.x "sRGB"; 3.x's colour
# configuration names): such files are display-referred.
_SRGB_NAMES = ("srgb", "srgb_rec709_scene", "srgb encoded rec.709 (srgb)")
_LINEAR = "Linear Rec.709 (sRGB)"


@dataclass(frozen=True)
class Comparison:
    """TEST against REFERENCE (`abrdf compare REF TEST`): the paper's NMSE (Sec. 4;
    sum (TEST - REF)^2 / sum REF^2 over every pixel and channel; None when the reference is
    all black), SSE, the reference's energy, MSE, the peak (largest value in either image),
    PSNR = 10 log10(peak^2 / MSE) dB, the largest |TEST - REF| with its pixel (x from the
    left, y from the top) and channel, and the NMSE's class in the paper's Table 8 ("none",
    "slight", "noticeable", "significant"; "undefined" without an NMSE)."""

    nmse: float | None
    sse: float
    reference_energy: float
    mse: float
    peak: float
    psnr: float
    max_abs_error: float
    max_pixel: tuple[int, int]
    max_channel: int
    nmse_class: str
    nmse_class_description: str

    def passed(self, threshold: float = 1e-4) -> bool:
        """NMSE < threshold (the command's --fail; 1e-4: "no visible difference")."""
        return self.nmse is not None and self.nmse < threshold


# The reader's cap on the pixels it reads, the command's (tools/image/image_io.cpp): a header
# may declare any size, so the size is checked before anything is allocated for it.
_MAX_BYTES = 1 << 30
# Rows read at a time: a truncated file fails at its first missing strip, so memory grows
# with what the file holds, not with what its header declares.
_STRIP_ROWS = 64


def _error(message: str) -> _abrdf.Error:
    err = _abrdf.Error(message)
    err.status = None
    return err


def _shown(name: str) -> str:
    """The name with its control characters as \\xHH, so a message stays one line."""
    return re.sub(r"[\x00-\x1f\x7f]", lambda m: "\\x%02x" % ord(m.group()), name)


def _oneline(why: str) -> str:
    """A library's message of several lines (libpng's, OpenEXR's) as one."""
    return "; ".join(line.strip() for line in why.splitlines() if line.strip())


def _file_kind(mode: int) -> str:
    return ("is a directory, not a file" if stat.S_ISDIR(mode)
            else "is a FIFO, not a regular file" if stat.S_ISFIFO(mode)
            else "is a character device, not a regular file" if stat.S_ISCHR(mode)
            else "is a block device, not a regular file" if stat.S_ISBLK(mode)
            else "is a socket, not a regular file" if stat.S_ISSOCK(mode)
            else "is not a regular file")


def _check_regular(name: str) -> None:
    """abrdf.Error unless `name` is a regular file, in the command's words
    (tools/common/in_file.c). O_NONBLOCK: opening a FIFO must not wait for a writer (nor
    would OpenImageIO's open return); fstat then refuses it."""
    try:
        fd = os.open(name, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0)
                     | getattr(os, "O_CLOEXEC", 0))
    except OSError as e:
        raise _error("%s: cannot open: %s" % (_shown(name), e.strerror)) from None
    try:
        mode = os.fstat(fd).st_mode
    except OSError as e:
        raise _error("%s: cannot open: %s" % (_shown(name), e.strerror)) from None
    finally:
        os.close(fd)
    if not stat.S_ISREG(mode):
        raise _error("%s: %s" % (_shown(name), _file_kind(mode)))


def _read(path: PathLike) -> tuple[np.ndarray, int]:
    try:
        import OpenImageIO as oiio
    except ImportError as e:  # a declared dependency; say which one is missing
        raise ImportError("abrdf.read_image needs OpenImageIO's Python bindings "
                          "(pip install OpenImageIO)") from e
    name = os.fspath(path)
    _check_regular(name)
    inp = oiio.ImageInput.open(name)
    if inp is None:
        raise _error("%s: %s" % (_shown(name), _oneline(oiio.geterror()) or "cannot open"))
    try:
        return _read_pixels(oiio, inp, _shown(name))
    finally:
        inp.close()


def _read_pixels(oiio: Any, inp: Any, name: str) -> tuple[np.ndarray, int]:
    spec = inp.spec()
    w, h, nch = spec.width, spec.height, spec.nchannels
    if w <= 0 or h <= 0 or nch <= 0 or spec.deep or spec.depth > 1:
        kind = ", deep" if spec.deep else ", depth %d" % spec.depth if spec.depth > 1 else ""
        raise _error("%s: unsupported image (size %dx%d, %d channels%s)"
                     % (name, w, h, nch, kind))
    # RGB from the first three channels; grey (and grey+alpha) is replicated. Only those are
    # read: alpha and extra channels cost nothing.
    used = 3 if nch >= 3 and spec.alpha_channel not in (1, 2) else 1
    need = w * h * used * 4
    if need > _MAX_BYTES:
        raise _error("%s: %dx%d pixels x %d channels as 32-bit floats need %d bytes, over the "
                     "image reader's limit of %d bytes" % (name, w, h, used, need, _MAX_BYTES))
    # Tiled files are read in whole rows of tiles, scanline files in strips.
    tile = spec.tile_height if spec.tile_width > 0 else 0
    step = tile * max(1, _STRIP_ROWS // tile) if tile > 0 else _STRIP_ROWS
    strips = []
    for y in range(spec.y, spec.y + h, step):
        y1 = min(y + step, spec.y + h)
        if tile > 0:
            px = inp.read_tiles(0, 0, spec.x, spec.x + w, y, y1, spec.z, spec.z + 1, 0, used,
                                oiio.FLOAT)
        else:
            px = inp.read_scanlines(0, 0, y, y1, spec.z, 0, used, oiio.FLOAT)
        if px is None or inp.has_error:
            raise _error("%s: %s" % (name, _oneline(inp.geterror()) or "cannot read the pixels"))
        strips.append(np.asarray(px, dtype=np.float32).reshape(y1 - y, w, used))
    px = strips[0] if len(strips) == 1 else np.concatenate(strips)
    del strips
    rgb = np.ascontiguousarray(px if used == 3 else np.repeat(px, 3, axis=2))
    cs = spec.get_string_attribute("oiio:ColorSpace").lower()
    integer = spec.format.basetype not in (oiio.FLOAT, oiio.HALF, oiio.DOUBLE)
    if cs in _SRGB_NAMES or (not cs and integer):
        # As the command: the RGB decoded, never an alpha channel (no unpremultiplying).
        buf = oiio.ImageBufAlgo.colorconvert(oiio.ImageBuf(rgb), "sRGB", _LINEAR)
        if buf.has_error:
            raise RuntimeError("%s: %s" % (name, buf.geterror()))
        rgb = np.ascontiguousarray(buf.get_pixels(oiio.FLOAT), dtype=np.float32)
        rgb = rgb.reshape(h, w, 3)
    return rgb, nch


def read_image(path: PathLike) -> np.ndarray:
    """The image at `path` as scene-linear float32 RGB, shape (height, width, 3), read as
    `abrdf compare` reads it. abrdf.Error, naming the file, for anything but a regular file
    (at once, without waiting on a FIFO), an unreadable or truncated image, or one whose
    pixels would need more than the reader's limit of 1 GiB."""
    return _read(path)[0]


def _image(x: ImageLike, what: str) -> tuple[np.ndarray, int | None, str]:
    if isinstance(x, (str, os.PathLike)):
        a, nch = _read(x)
        return a, nch, os.fspath(x)
    a = np.ascontiguousarray(real_array(x, what), dtype=np.float32)
    return a, None, what


def compare(reference: ImageLike, test: ImageLike) -> Comparison:
    """NMSE, PSNR and the Table-8 class of `test` against `reference` (the order matters:
    the NMSE is relative to the reference's energy). Each is an image file or an array of
    shape (height, width) or (height, width, channels), the same for both, of integers or
    floats (TypeError for complex, datetime, bool, string or object arrays). Files need the
    same size and channel count, as for `abrdf compare`, and are read by read_image's
    rules. abrdf.Error names what differs or the first NaN/infinite sample."""
    r, rn, rname = _image(reference, "reference")
    t, tn, tname = _image(test, "test")
    if rn is not None and tn is not None and rn != tn:
        raise _error("images differ in channels: %s has %d, %s has %d"
                     % (rname, rn, tname, tn))
    return Comparison(**_abrdf.compare(r, t))
