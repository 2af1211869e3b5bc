"""huang tabulated (abrdf.h, "huang tabulated"; docs/MODELS.md, "A tabulated huang"):
huang_table(), HuangTable."""
from __future__ import annotations

import operator
import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import numpy.typing as npt

from . import _abrdf
from ._brdf import BRDF, Precision, eval_block, threads_arg

# ABRDF_HUANG_TABLE_SIZES: the sizes docs/MODELS.md measures (about a minute of one core).
DEFAULT_SIZES = (24, 9, 32, 16)


class HuangTable:
    """huang with its residual lobes (TT, TRT, TRRT+) tabulated once for one parameter block:
    each node of a grid of directions the mean of `sets` rotations of the block's own
    quadrature grids, read back by cubic interpolation; R keeps the quadrature. Nearer the
    converged model than the per-call quadrature and about 150 times cheaper per call
    (docs/MODELS.md, "A tabulated huang").

    Made by huang_table(brdf, sizes). `values` is the table itself, a read-only float64 array
    (the library's own format, its header first); its memory is an immutable bytes object
    that the prepared C object holds while it lives. A HuangTable pickles with its values.
    It is valid only for the library that built it: one built by another library revision is
    refused when unpickled (abrdf.Error)."""

    __slots__ = ("_brdf", "_sizes", "_values", "_block")

    def __init__(self) -> None:
        raise TypeError("HuangTable: use abrdf.huang_table(brdf, sizes)")

    @classmethod
    def _from_bytes(cls, brdf: BRDF, sizes: tuple[int, int, int, int], data: bytes) -> HuangTable:
        t = cls.__new__(cls)
        values = np.frombuffer(data, np.float64)  # read-only: data is bytes
        t._block = _abrdf.huang_table(brdf.block, sizes, values)
        t._brdf = brdf
        t._sizes = sizes
        t._values = values
        return t

    def __reduce__(self) -> tuple[object, tuple[object, ...]]:
        return (HuangTable._from_bytes, (self._brdf, self._sizes, self._values.tobytes()))

    @property
    def brdf(self) -> BRDF:
        """The huang BRDF it tabulates (its parameter block)."""
        return self._brdf

    @property
    def sizes(self) -> tuple[int, int, int, int]:
        """(theta nodes, view azimuths, light azimuths, shift sets)."""
        return self._sizes

    @property
    def values(self) -> np.ndarray:
        """The table, float64, read-only, header first (abrdf.h, "THE GRID")."""
        return self._values

    @property
    def block(self) -> _abrdf.Table:
        """The prepared C object (what the extension module's functions take)."""
        return self._block

    def __repr__(self) -> str:
        return "HuangTable(%r, sizes=%r)" % (self._brdf, self._sizes)

    def eval(self, wi: npt.ArrayLike, wo: npt.ArrayLike, precision: Precision = "float",
             threads: int = 0, out: np.ndarray | None = None) -> np.ndarray:
        """f_r(wi, wo) per RGB channel, 1/sr, without the cosine: BRDF.eval's arguments and
        result, read from the table (R by its quadrature). The GIL is released while the
        library works."""
        return eval_block(self._block, wi, wo, precision, threads, out)

    def cost(self, costs: dict[str, float] | None = None, cost_unit: str | None = None) -> float:
        """What one evaluation costs in the unit of `costs` (None: the budget mode's built-in
        table): huang's entry times the ratio of the table's time to the per-call
        quadrature's, both timed now on the float batch path, so that the ratio carries over
        from this machine (select's reference_cost); -1 if it cannot be timed (costs without a
        huang entry). The GIL is released while it times."""
        return float(_abrdf.prepared_cost(self._block, self._brdf.block, costs, cost_unit))


def _sizes(sizes: object) -> tuple[int, int, int, int]:
    try:
        s = tuple(operator.index(x) for x in sizes)  # type: ignore[union-attr]
    except TypeError:
        s = ()
    if len(s) != 4:
        raise ValueError("sizes: four ints (theta nodes, view azimuths, light azimuths, shift "
                         "sets), got %r" % (sizes,))
    return s  # type: ignore[return-value]


def huang_table(brdf: BRDF, sizes: tuple[int, int, int, int] = DEFAULT_SIZES,
                threads: int = 0) -> HuangTable:
    """huang's residual lobes tabulated for one parameter block (abrdf_huang_table_build):
    sizes = (theta nodes [4, 256], view azimuths [2, 256] or 1 for a round fibre, light
    azimuths [4, 256], shift sets [1, 64]); the default, DEFAULT_SIZES, is what
    docs/MODELS.md measures and takes about a minute of one core. The table's rows are built
    over `threads` threads (0: one per core), the GIL released. Sizes out of range or a BRDF
    that is not huang raise abrdf.Error with the library's message."""
    if not isinstance(brdf, BRDF):
        raise TypeError("huang_table: a BRDF('huang', ...) is needed, not %r" % (brdf,))
    s = _sizes(sizes)
    t = threads_arg(threads)
    count, rows = _abrdf.huang_table_size(brdf.block, s)
    values = np.empty(count, np.float64)
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    workers = min(t or (cores or 1), rows)
    _abrdf.huang_table_build(brdf.block, s, 0, 0, values)  # the header
    if workers <= 1:
        _abrdf.huang_table_build(brdf.block, s, 0, rows, values)
    else:
        # disjoint runs of rows, each call releasing the GIL; rows differ in cost (grazing
        # views), so small runs keep the threads busy to the end
        step = max(1, rows // (8 * workers))
        with ThreadPoolExecutor(workers) as pool:
            for f in [pool.submit(_abrdf.huang_table_build, brdf.block, s, r,
                                  min(rows, r + step), values) for r in range(0, rows, step)]:
                f.result()
    return HuangTable._from_bytes(brdf, s, values.tobytes())
