"""Numbers from the caller: the one converter of user input to NumPy arrays and floats.

Numbers only: NumPy's integer and floating kinds ('i', 'u', 'f'), Python ints and floats.
bool, complex, datetime64/timedelta64, strings, bytes and object arrays (a None among
numbers: [0, None, 1]) raise TypeError naming the argument and the dtype, where a cast
would drop an imaginary part, read None as 0 or a date as its count of seconds. The
extension module applies the same rule to parameter values (abrdf_py_real_number, python/src).
"""
from __future__ import annotations

import numpy as np
import numpy.typing as npt

_REAL_KINDS = "iuf"


def real_array(x: npt.ArrayLike, what: str) -> np.ndarray:
    """`x` as an ndarray of integers or floats (no copy when it already is one)."""
    a = np.asarray(x)
    if a.dtype.kind not in _REAL_KINDS:
        raise TypeError("%s: a real number array is needed, got %s" % (what, a.dtype))
    return a


def real_number(x: object, what: str) -> float:
    """`x`, one integer or float (a Python or NumPy scalar), as a float."""
    if isinstance(x, (int, float)) and not isinstance(x, bool):
        return float(x)
    a = np.asarray(x)
    if a.ndim != 0 or a.dtype.kind not in _REAL_KINDS:
        raise TypeError("%s: a real number is needed, got %s" % (what, type(x).__name__))
    return float(a)
