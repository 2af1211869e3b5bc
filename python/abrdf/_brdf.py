"""The registry and the BRDF: models(), model(), BRDF (abrdf.eval is in _eval.py)."""
from __future__ import annotations

import functools
import operator
from dataclasses import dataclass
from typing import Literal, Sequence, Union

import numpy as np
import numpy.typing as npt

from . import _abrdf
from ._arrays import real_array

ParamValue = Union[float, int, Sequence[float]]
Precision = Literal["float", "double"]


@dataclass(frozen=True)
class Parameter:
    """One parameter as a model reads it: the registry's name and help, its kind ("scalar",
    "rgb" or "int") and this model's default and inclusive range (every component)."""

    name: str
    help: str
    kind: str
    default: float
    min: float
    max: float


@dataclass(frozen=True)
class Model:
    """A registered model (abrdf_model_info): its stable name, title, the paper's formula
    reference, citation, what it needs ("tangent", "fresnel", "layers", "integration",
    "table": a measured table, not parameters),
    its properties, the paper's Table-4 cost in cycles (None when the table has none) and
    the parameters it reads."""

    id: int
    name: str
    title: str
    equation: str
    citation: str
    needs: tuple[str, ...]
    reciprocal: bool
    energy_conserving: bool
    kind: str
    paper_cycles: int | None
    params: tuple[Parameter, ...]

    def param(self, name: str) -> Parameter:
        """The parameter `name` as this model reads it (KeyError if it does not)."""
        for p in self.params:
            if p.name == name:
                return p
        raise KeyError("%s does not read %r" % (self.name, name))


@functools.lru_cache(maxsize=1)
def _registry() -> tuple[Model, ...]:
    out = []
    for d in _abrdf.models():
        params = tuple(Parameter(**p) for p in d.pop("params"))
        out.append(Model(params=params, **d))
    return tuple(out)


def models() -> list[Model]:
    """Every model of the library, in registry order (the order of `abrdf models`)."""
    return list(_registry())


def model(name: str) -> Model:
    """The model with this stable name; abrdf.Error if there is none."""
    for m in _registry():
        if m.name == name:
            return m
    _abrdf.Params(name)  # raises abrdf.Error with the library's message
    raise AssertionError("unreachable")


def _rows(v: npt.ArrayLike, what: str) -> np.ndarray:
    a = real_array(v, what)
    if a.dtype not in (np.float32, np.float64):
        a = a.astype(np.float64)
    if a.ndim == 0 or a.shape[-1] != 3:
        raise ValueError("%s: directions are arrays of shape (..., 3), got %s" % (what, a.shape))
    return a


Block = Union[_abrdf.Params, _abrdf.Table]


def _out(out: object, shape: tuple[int, ...], dtype: type, precision: str,
         inputs: tuple[np.ndarray, ...]) -> np.ndarray:
    """The caller's `out`, checked: an ndarray of the result's shape and dtype, C-contiguous,
    writable, sharing no memory with the directions."""
    if not isinstance(out, np.ndarray):
        raise TypeError("out: a NumPy array is needed, got %s" % type(out).__name__)
    if out.dtype != dtype:
        raise TypeError("out: %s is needed for precision=%r, got %s"
                        % (np.dtype(dtype).name, precision, out.dtype))
    if out.shape != shape:
        raise ValueError("out: shape %s is needed, got %s" % (shape, out.shape))
    if not out.flags.c_contiguous:
        raise ValueError("out: a C-contiguous array is needed")
    if not out.flags.writeable:
        raise ValueError("out: the array is read-only")
    if any(np.may_share_memory(out, x) for x in inputs):
        raise ValueError("out: shares memory with wi or wo")
    return out


def threads_arg(threads: object) -> int:
    """`threads` as an int in [0, 64] (0 = one per core); ValueError for anything else."""
    try:
        t = -1 if isinstance(threads, bool) else operator.index(threads)  # type: ignore[arg-type]
    except TypeError:
        t = -1
    if not 0 <= t <= 64:
        raise ValueError("threads: an int in [0, 64] (0 = one per core), got %r" % (threads,))
    return t


def eval_block(block: Block | tuple[Block, ...], wi: npt.ArrayLike, wo: npt.ArrayLike,
               precision: Precision, threads: int, out: np.ndarray | None = None) -> np.ndarray:
    """f_r of a C block (a Params, or a measured Table), or the sum of a tuple of them (one
    pass over the rows on the float path), over broadcast direction arrays, into `out` when
    given: what BRDF.eval, Measured.eval and Lobes.eval share."""
    threads = threads_arg(threads)
    if precision not in ("float", "double"):
        raise ValueError("precision: 'float' or 'double', got %r" % (precision,))
    a, b = np.broadcast_arrays(_rows(wi, "wi"), _rows(wo, "wo"))
    shape = a.shape
    double = precision == "double"
    dtype = np.float64 if double else np.float32
    a = np.ascontiguousarray(a.reshape(-1, 3), dtype=np.float64 if double else None)
    b = np.ascontiguousarray(b.reshape(-1, 3), dtype=np.float64 if double else None)
    res = np.empty(shape, dtype) if out is None else _out(out, shape, dtype, precision, (a, b))
    flat = res.reshape(-1, 3)  # a view: res is C-contiguous
    if double:
        blocks = block if isinstance(block, tuple) else (block,)
        _abrdf.eval_double(blocks[0], a, b, flat)
        if len(blocks) > 1:
            more = np.empty_like(flat)
            for x in blocks[1:]:
                _abrdf.eval_double(x, a, b, more)
                flat += more
    else:
        _abrdf.eval_float(block, a, b, flat, threads)
    return res


class BRDF:
    """A model with a validated parameter block.

    BRDF("disney_specular", r=0.3, f0=(0.9, 0.6, 0.3)) takes the model's defaults and sets
    the given parameters (the registry's names; a colour as one number or three). A value
    is an int or a float (NumPy's integer and floating scalars too); bool, complex, None and
    strings raise TypeError. Values outside the model's range, and parameters the model
    does not read, raise abrdf.Error with the library's message (abrdf_params_check)."""

    __slots__ = ("_p",)

    def __init__(self, model: str, **params: ParamValue) -> None:
        self._p = _abrdf.Params(model, params)

    @classmethod
    def _from_params(cls, p: _abrdf.Params) -> BRDF:
        b = cls.__new__(cls)
        b._p = p
        return b

    @property
    def model(self) -> str:
        """The model's stable name."""
        return self._p.model

    @property
    def params(self) -> dict[str, float | int | tuple[float, float, float]]:
        """Every parameter the model reads, with its value."""
        return self._p.values()

    @property
    def block(self) -> _abrdf.Params:
        """The C parameter block (what the extension module's functions take)."""
        return self._p

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, BRDF):
            return NotImplemented
        return self.model == other.model and self.params == other.params

    def __hash__(self) -> int:
        return hash((self.model, tuple(sorted(self.params.items()))))

    def __reduce__(self) -> tuple[object, tuple[object, ...]]:
        # The values read back set the same doubles: a pickled BRDF is the same block.
        return (_brdf_from, (self.model, self.params))

    def __repr__(self) -> str:
        return "BRDF(%r, %s)" % (self.model, ", ".join(
            "%s=%r" % kv for kv in self.params.items()))

    def eval(self, wi: npt.ArrayLike, wo: npt.ArrayLike, precision: Precision = "float",
             threads: int = 0, out: np.ndarray | None = None) -> np.ndarray:
        """f_r(wi, wo) per RGB channel, 1/sr, without the cosine.

        wi, wo: local-frame directions, arrays of shape (..., 3) broadcast against each
        other, of integers or floats (TypeError for complex, datetime, bool, string or
        object arrays: [0, None, 1] is not [0, 0, 1]); normalised here (zero or non-finite
        vectors give 0). precision "float": the library's float batch path
        (abrdf_eval_batch), result float32; "double": the double-precision scalar reference
        (abrdf_eval), float64. The result has the
        broadcast shape (..., 3). The C loop runs without the GIL; on the float path a large
        array is spread over the machine's cores (threads=0: one thread per core, each with at
        least 32768 pairs; threads=N: N threads, at most 64 and one per 16384 pairs; the
        threads take blocks of 16384 pairs in turn), the same result as one thread. out: an array to write the result into and return, instead of a new one:
        an ndarray of the result's shape, float32 ("float") or float64 ("double"),
        C-contiguous, writable, sharing no memory with wi or wo (else TypeError or
        ValueError)."""
        return eval_block(self._p, wi, wo, precision, threads, out)


def _brdf_from(model: str, params: dict[str, ParamValue]) -> BRDF:
    return BRDF(model, **params)
