"""Image comparison: compare() and read_image(), as `abrdf compare` does them.

The metrics are the command's C code (tools/image/metrics.c, in the extension module). Files
are read with OpenImageIO's Python bindings (the PyPI package OpenImageIO, a dependency of
this package), by the rules of the command's reader (tools/image/image_io.cpp): RGB from the
first three channels, grey replicated, alpha dropped; display-referred files (tagged sRGB, or
untagged integer pixels: 8/16-bit PNG, JPEG, TIFF) decoded to scene-linear by OpenImageIO's
colour conversion from sRGB (OpenColorIO's optimised path, within 2.5e-4 relative of the
exact curve per sample; the command's OpenColorIO decodes 8-bit values exactly), float files
(EXR, HDR, float TIFF) taken as scene-linear.
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Union

import numpy as np
import numpy.typing as npt

from . import _abrdf

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


def _read(path: PathLike) -> tuple[np.ndarray, int]:
    try:
        import OpenImageIO as oiio
    except ImportError as e:  # a declared dependency; say which one is missing
        raise ImportError("abrdf.read_image needs OpenImageIO's Python bindings "
                          "(pip install OpenImageIO)") from e
    name = os.fspath(path)
    buf = oiio.ImageBuf(name)
    # In float: a colour conversion keeps the buffer's pixel type (8 bits would round it).
    if not buf.read(0, 0, True, oiio.FLOAT) or buf.spec().nchannels <= 0:
        err = _abrdf.Error("%s: %s" % (name, buf.geterror() or "cannot read the image"))
        err.status = None
        raise err
    spec = buf.nativespec()
    nch = spec.nchannels
    cs = spec.get_string_attribute("oiio:ColorSpace").lower()
    integer = spec.format.basetype not in (oiio.FLOAT, oiio.HALF, oiio.DOUBLE)
    if cs in _SRGB_NAMES or (not cs and integer):
        buf = oiio.ImageBufAlgo.colorconvert(buf, "sRGB", _LINEAR)
        if buf.has_error:
            raise RuntimeError("%s: %s" % (name, buf.geterror()))
    px = np.asarray(buf.get_pixels(oiio.FLOAT), dtype=np.float32)
    px = px.reshape(spec.height, spec.width, nch)
    colour = nch >= 3 and spec.alpha_channel not in (1, 2)
    rgb = px[..., :3] if colour else np.repeat(px[..., :1], 3, axis=2)
    return np.ascontiguousarray(rgb), nch


def read_image(path: PathLike) -> np.ndarray:
    """The image at `path` as scene-linear float32 RGB, shape (height, width, 3), read as
    `abrdf compare` reads it."""
    return _read(path)[0]


def _image(x: ImageLike, what: str) -> tuple[np.ndarray, int | None, str]:
    if isinstance(x, (str, os.PathLike)):
        a, nch = _read(x)
        return a, nch, os.fspath(x)
    a = np.ascontiguousarray(x, dtype=np.float32)
    return a, None, what


def compare(reference: ImageLike, test: ImageLike) -> Comparison:
    """NMSE, PSNR and the Table-8 class of `test` against `reference` (the order matters:
    the NMSE is relative to the reference's energy). Each is an image file or an array of
    shape (height, width) or (height, width, channels), the same for both. Files need the
    same size and channel count, as for `abrdf compare`. abrdf.Error names what differs or
    the first NaN/infinite sample."""
    r, rn, rname = _image(reference, "reference")
    t, tn, tname = _image(test, "test")
    if rn is not None and tn is not None and rn != tn:
        err = _abrdf.Error("images differ in channels: %s has %d, %s has %d"
                           % (rname, rn, tname, tn))
        err.status = None
        raise err
    return Comparison(**_abrdf.compare(r, t))
