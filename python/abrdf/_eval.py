"""abrdf.eval and Lobes: f_r of a model given by name, a BRDF, a Measured table or a material
made of several lobes, over arrays of direction pairs. Above both _brdf.py and _measured.py,
which it dispatches to."""
from __future__ import annotations

from typing import Iterable, Iterator

import numpy as np
import numpy.typing as npt

from ._brdf import BRDF, ParamValue, Precision, eval_block
from ._measured import Measured


class Lobes:
    """A material made of several lobes, f_r their sum: Lobes([BRDF("disney_diffuse", ...),
    BRDF("disney_specular", ...)]), or Lobes(abrdf.pbr_lobes(p)). Each lobe is a BRDF or a
    Measured table; at least one."""

    __slots__ = ("_lobes", "_blocks")

    def __init__(self, lobes: Iterable[BRDF | Measured]) -> None:
        if isinstance(lobes, (BRDF, Measured, str, bytes)):
            raise TypeError("Lobes: a sequence of BRDFs and Measured tables is needed, got %s"
                            % type(lobes).__name__)
        self._lobes = tuple(lobes)
        if not self._lobes:
            raise ValueError("Lobes: a material needs at least one lobe")
        for i, x in enumerate(self._lobes):
            if not isinstance(x, (BRDF, Measured)):
                raise TypeError("Lobes: lobe %d is a %s, not a BRDF or a Measured"
                                % (i, type(x).__name__))
        self._blocks = tuple(x.block for x in self._lobes)

    @property
    def lobes(self) -> tuple[BRDF | Measured, ...]:
        """The lobes, in the order they are summed."""
        return self._lobes

    def __len__(self) -> int:
        return len(self._lobes)

    def __iter__(self) -> Iterator[BRDF | Measured]:
        return iter(self._lobes)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Lobes):
            return NotImplemented
        return self._lobes == other._lobes

    def __hash__(self) -> int:
        return hash(self._lobes)

    def __reduce__(self) -> tuple[object, tuple[object, ...]]:
        return (Lobes, (list(self._lobes),))

    def __repr__(self) -> str:
        return "Lobes([%s])" % ", ".join(repr(x) for x in self._lobes)

    def eval(self, wi: npt.ArrayLike, wo: npt.ArrayLike, precision: Precision = "float",
             threads: int = 0, out: np.ndarray | None = None) -> np.ndarray:
        """f_r(wi, wo) of the material: the sum of its lobes' f_r, with BRDF.eval's arguments
        and result. precision "float": one pass over the rows, every lobe evaluated on each
        block of rows while it is in cache (abrdf_eval_prepared_rows, which makes the rows
        unit) and added in the lobes' order: the float32 sum of the lobes' own evals, bit for
        bit, whatever `threads`; "double": each lobe's double reference, summed in
        float64."""
        return eval_block(self._blocks, wi, wo, precision, threads, out)


def eval(model: str | BRDF | Measured | Lobes, wi: npt.ArrayLike, wo: npt.ArrayLike,
         precision: Precision = "float", threads: int = 0, out: np.ndarray | None = None,
         **params: ParamValue) -> np.ndarray:
    """f_r of `model` (a name, with its parameters as keywords, a BRDF, a Measured table or a
    Lobes material) for arrays of direction pairs: BRDF(model, **params).eval(wi, wo,
    precision, threads, out)."""
    if isinstance(model, str):
        return BRDF(model, **params).eval(wi, wo, precision, threads, out)
    if params:
        raise TypeError("eval: parameters are given to BRDF(...), not with a %s"
                        % type(model).__name__)
    if not isinstance(model, (BRDF, Measured, Lobes)):
        raise TypeError("eval: a model name, a BRDF, a Measured or a Lobes is needed, got %s"
                        % type(model).__name__)
    return model.eval(wi, wo, precision, threads, out)
