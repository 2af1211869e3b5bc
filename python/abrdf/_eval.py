"""abrdf.eval: f_r of a model given by name, a BRDF or a Measured table, over arrays of
direction pairs. Above both _brdf.py and _measured.py, which it dispatches to."""
from __future__ import annotations

import numpy as np
import numpy.typing as npt

from ._brdf import BRDF, ParamValue, Precision
from ._measured import Measured


def eval(model: str | BRDF | Measured, wi: npt.ArrayLike, wo: npt.ArrayLike,
         precision: Precision = "float", threads: int = 0, **params: ParamValue) -> np.ndarray:
    """f_r of `model` (a name, with its parameters as keywords, a BRDF or a Measured table)
    for arrays of direction pairs: BRDF(model, **params).eval(wi, wo, precision, threads)."""
    if isinstance(model, str):
        return BRDF(model, **params).eval(wi, wo, precision, threads)
    if params:
        raise TypeError("eval: parameters are given to BRDF(...), not with a %s"
                        % type(model).__name__)
    if not isinstance(model, (BRDF, Measured)):
        raise TypeError("eval: a model name, a BRDF or a Measured is needed, got %s"
                        % type(model).__name__)
    return model.eval(wi, wo, precision, threads)
