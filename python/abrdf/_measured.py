"""Measured materials (docs/MEASURED.md): load_measured(), measured_from_array(), Measured."""
from __future__ import annotations

import os
from typing import Union

import numpy as np
import numpy.typing as npt

from . import _abrdf
from ._arrays import real_array
from ._brdf import Precision, eval_block

PathLike = Union[str, "os.PathLike[str]"]

# The library's grid bounds (abrdf_prepare_measured): cells per axis, cells in all.
_DIM_MIN, _DIM_MAX = 2, 1024
_CELLS_MAX = 1 << 26
# File names read as measured files (tools/measured/measured_file.c), not as material names.
MEASURED_EXTENSIONS = (".binary", ".bsdf")


def is_measured_path(x: object) -> bool:
    """Does `x` name a measured file (an os.PathLike, or a str ending in .binary or .bsdf)?"""
    if isinstance(x, os.PathLike):
        return True
    return isinstance(x, str) and x.lower().endswith(MEASURED_EXTENSIONS)


class Measured:
    """A measured isotropic BRDF: f_r on the half/difference grid of the MERL database,
    evaluated by the library's `measured` model (abrdf_prepare_measured; docs/MEASURED.md,
    "The measured model": trilinear, unmeasured cells dropped, exactly reciprocal).

    Made by load_measured(path) or measured_from_array(array). `table` is the table itself,
    a read-only float32 array of shape (n_theta_h, n_theta_d, n_phi_d, 3): f_r in 1/sr per
    RGB channel, without the cosine, a negative value where a cell is not measured. Its
    memory is an immutable bytes object that the prepared C object holds while it lives, so
    the library's pointer stays valid however the array is passed around. A Measured pickles
    with its table (dask ships it so)."""

    __slots__ = ("_table", "_block", "_path", "_unmeasured", "_format")

    def __init__(self) -> None:
        raise TypeError("Measured: use abrdf.load_measured(path) or abrdf.measured_from_array(a)")

    @classmethod
    def _from_bytes(cls, data: bytes, grid: tuple[int, int, int], unmeasured: int,
                    path: str | None, fmt: str | None) -> Measured:
        m = cls.__new__(cls)
        table = np.frombuffer(data, np.float32).reshape(*grid, 3)  # read-only: data is bytes
        m._block = _abrdf.Table(table.reshape(-1), *grid)
        m._table = table
        m._path = path
        m._unmeasured = int(unmeasured)
        m._format = fmt
        return m

    def __reduce__(self) -> tuple[object, tuple[object, ...]]:
        return (Measured._from_bytes, (self._table.tobytes(), self.grid, self._unmeasured,
                                       self._path, self._format))

    @property
    def table(self) -> np.ndarray:
        """f_r, float32, shape (n_theta_h, n_theta_d, n_phi_d, 3), read-only; < 0: not
        measured."""
        return self._table

    @property
    def grid(self) -> tuple[int, int, int]:
        """(n_theta_h, n_theta_d, n_phi_d); MERL's is (90, 90, 180)."""
        return self._block.grid

    @property
    def unmeasured(self) -> int:
        """Cells with at least one channel not measured (as `abrdf inspect` counts them)."""
        return self._unmeasured

    @property
    def path(self) -> str | None:
        """The file it was read from (None for a table made from an array)."""
        return self._path

    @property
    def format(self) -> str | None:
        """The file's format as the reader names it ("MERL BRDF database", ...), or None."""
        return self._format

    @property
    def block(self) -> _abrdf.Table:
        """The prepared C object (what the extension module's functions take)."""
        return self._block

    def __repr__(self) -> str:
        src = repr(self._path) if self._path is not None else "array"
        return "Measured(%s, grid=%r, unmeasured=%d)" % (src, self.grid, self._unmeasured)

    def eval(self, wi: npt.ArrayLike, wo: npt.ArrayLike, precision: Precision = "float",
             threads: int = 0, out: np.ndarray | None = None) -> np.ndarray:
        """f_r(wi, wo) per RGB channel, 1/sr, without the cosine: BRDF.eval's arguments and
        result. precision "float": the library's float batch path on the prepared table
        (abrdf_eval_prepared_rows; float64 rows converted to float rows first),
        float32; "double": abrdf_eval_prepared, float64; out: as BRDF.eval's. The
        GIL is released while the library works."""
        return eval_block(self._block, wi, wo, precision, threads, out)


def load_measured(path: PathLike) -> Measured:
    """Read a measured BRDF file by the readers of `abrdf inspect` (tools/measured), its
    format chosen by the extension: a MERL `.binary` (any grid its header gives) or an RGL
    `.bsdf` (resampled onto MERL's 90 x 90 x 180 grid). A file that cannot be read (missing,
    not a regular file, truncated, an unknown extension, a value that is NaN or implausible)
    raises abrdf.Error with the reader's one line, `status` ABRDF_E_TABLE (-7). The GIL is
    released while the file is read."""
    p = os.fspath(path)
    if not isinstance(p, str):
        p = os.fsdecode(p)
    d = _abrdf.read_measured(p)
    return Measured._from_bytes(d["data"], d["grid"], d["unmeasured"], p, d["format"])


def measured_from_array(array: npt.ArrayLike) -> Measured:
    """A Measured from a table made in NumPy: shape (n_theta_h, n_theta_d, n_phi_d, 3), each
    axis in [2, 1024] and at most 2^26 cells, of integers or floats; every value finite, f_r
    in 1/sr, negative where a cell is not measured (docs/MEASURED.md gives the grid's
    angles). The values are copied into a C-contiguous float32 table the Measured owns.
    TypeError for a dtype that is not numbers, ValueError for a shape or a value that is not
    a table's."""
    a = real_array(array, "table")
    if a.ndim != 4 or a.shape[-1] != 3:
        raise ValueError("table: an array of shape (n_theta_h, n_theta_d, n_phi_d, 3) is "
                         "needed, got %s" % (a.shape,))
    grid = tuple(int(n) for n in a.shape[:3])
    if not all(_DIM_MIN <= n <= _DIM_MAX for n in grid):
        raise ValueError("table: grid %s: each axis must be in [%d, %d]"
                         % (grid, _DIM_MIN, _DIM_MAX))
    if grid[0] * grid[1] * grid[2] > _CELLS_MAX:
        raise ValueError("table: grid %s has %d cells, more than the library's %d"
                         % (grid, grid[0] * grid[1] * grid[2], _CELLS_MAX))
    with np.errstate(over="ignore"):  # a value past float32's range: refused just below
        f = np.ascontiguousarray(a, dtype=np.float32)
    bad = ~np.isfinite(f)
    if bad.any():
        idx = tuple(int(i) for i in np.argwhere(bad)[0])
        raise ValueError("table[%d, %d, %d, %d] = %r (as float32): values are f_r (1/sr) or "
                         "negative for not measured, never NaN or an infinity"
                         % (idx + (float(f[idx]),)))
    unmeasured = int(np.count_nonzero((f < 0).any(axis=-1)))
    return Measured._from_bytes(f.tobytes(), grid, unmeasured, None, None)  # type: ignore[arg-type]
