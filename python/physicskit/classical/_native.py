"""Helpers shared by the Python layer: input conversion and access to the native module.

Conversion rules
----------------
Every number a user passes to physicskit goes through one of the converters below, which
either return exactly the value given (as a float64 array, a float or an int) or raise a
``ValueError`` whose message starts with the argument's name. Nothing is ever silently
truncated, and no ``OverflowError``, ``TypeError`` or numpy warning escapes from deep inside.
The exception is always ``ValueError`` (the spec's exception for bad input), whatever is wrong.

=====================================  ========================  =========================
value given                            real (``as_scalar``,      integer (``as_int``)
                                       ``as_vector`` entries)
=====================================  ========================  =========================
Python ``int``, numpy integer          accepted (rounded to the  accepted if in range
                                       nearest float64)
``int`` beyond float64 (``10**400``)   refused: "too large"      refused: "too large"
``int`` beyond the native range        —                         refused: "must be <= max"
Python ``float``, numpy floating       accepted if finite [1]_   refused, even ``32.0`` or
                                                                 ``5.4e16``: pass an int
NaN, +-inf                             refused [1]_              refused
``bool``, ``numpy.bool_``              refused                   refused
``complex``, numpy complex (even with  refused: "is complex"     refused: "is complex"
a zero imaginary part)
``str``, ``bytes``, ``None``, other    refused                   refused
0-d numpy array                        as its element            as its element
array with ``ndim > 0`` as a scalar    refused                   refused
=====================================  ========================  =========================

.. [1] ``as_vector(..., finite=False)`` (the optional ``state`` of ``energy``, which may be
   evaluated where it is not finite) lets NaN and infinity through; everything else still
   applies.

Arrays (``as_vector``) take any array-like of such numbers: a numpy array of integer or
floating dtype, or a (nested) list of Python/numpy numbers. A numpy array of complex, bool,
string or datetime dtype is refused by its dtype; an object array (what numpy makes of
``[1, 10**400]`` or a list holding ``Fraction`` objects) is checked element by element with
the scalar rules. Shape: one-dimensional (a scalar becomes a vector of length 1), with the
required length when one is given.

Error messages have the forms ``"<name> must be a real number, got <repr>"``, ``"<name> is
complex (<repr>); pass a real number"``, ``"<name> = <value> is too large for a float"``,
``"<name> must be an integer, got <repr>"``, ``"<name> must be >= <min>, got <n>"``,
``"<name> contains NaN or infinity; pass finite numbers"``, ``"<name> has length <n>,
expected <m>"``.
"""

from __future__ import annotations

import math
import numbers
import operator
from typing import Any

import numpy as np

from .. import _core

__all__ = [
    "_core", "as_array", "as_vector", "as_real", "as_scalar", "as_int", "as_t_span", "native",
    "MAX_NATIVE_INT",
]

MAX_NATIVE_INT = 2**64 - 1
"""The largest integer the native layer takes (``usize``/``u64`` on a 64-bit platform).
Sizes below it that would not fit in memory are refused by the native constructors."""

#: numpy dtype kinds holding real numbers that convert to float64 exactly or by rounding.
_REAL_KINDS = frozenset("iuf")

_DTYPE_WORDS = {
    "b": "booleans",
    "c": "complex numbers",
    "U": "strings",
    "S": "bytes",
    "M": "datetimes",
    "m": "timedeltas",
    "V": "raw records",
}


def _is_complex(value: Any) -> bool:
    """A complex number (Python, numpy or any ``numbers.Complex`` that is not real)."""
    return isinstance(value, numbers.Complex) and not isinstance(value, numbers.Real)


def _real(name: str, value: Any) -> float:
    """One real number by the rules of the module docstring, finite or not."""
    if isinstance(value, np.ndarray):
        if value.ndim != 0:
            raise ValueError(
                f"{name} must be a single real number, got an array of shape {value.shape}"
            )
        value = value[()]
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be a real number, got {value!r}")
    if _is_complex(value):
        raise ValueError(f"{name} is complex ({value!r}); pass a real number")
    if isinstance(value, (str, bytes)) or not hasattr(value, "__float__"):
        raise ValueError(f"{name} must be a real number, got {value!r}")
    try:
        return float(value)
    except OverflowError:
        raise ValueError(f"{name} = {_short(value)} is too large for a float") from None
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None


def _short(value: Any) -> str:
    """``repr`` of a possibly huge number, cut to something readable."""
    text = repr(value)
    return text if len(text) <= 40 else f"{text[:20]}...({len(text)} digits)"


def as_real(name: str, value: Any) -> float:
    """Return ``value`` as a float by the rules of the module docstring, NaN and infinity
    included (for values a computation returned, which the caller checks)."""
    return _real(name, value)


def as_scalar(name: str, value: Any) -> float:
    """Return ``value`` as a finite float, or raise ValueError naming ``name`` (see the module
    docstring for what is accepted)."""
    x = _real(name, value)
    if not math.isfinite(x):
        raise ValueError(f"{name} must be finite, got {x}")
    return x


def as_int(name: str, value: Any, minimum: int = 0, maximum: int = MAX_NATIVE_INT) -> int:
    """``value`` as an int in ``[minimum, maximum]``; ValueError naming ``name`` otherwise.

    Takes what Python takes as an index (``int``, numpy integers, objects with
    ``__index__``) and nothing else: not ``bool``, not a float even when it is integral
    (``5.4e16``, ``32.0``), not a complex number, not a string.
    """
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be an integer, got {value!r}")
    if _is_complex(value):
        raise ValueError(f"{name} is complex ({value!r}); pass an integer")
    try:
        n = operator.index(value)
    except TypeError:
        hint = " (a float); pass an int" if isinstance(value, (float, np.floating)) else ""
        raise ValueError(f"{name} must be an integer, got {_short(value)}{hint}") from None
    if n < minimum:
        raise ValueError(f"{name} must be >= {minimum}, got {_short(n)}")
    if n > maximum:
        raise ValueError(f"{name} must be <= {maximum}, got {_short(n)}")
    return n


def as_flag(name: str, value: Any) -> bool:
    """``value`` as a bool: ``True``/``False`` (or numpy's), nothing else (not ``1``, not
    ``"yes"``); ValueError naming ``name`` otherwise."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise ValueError(f"{name} must be True or False, got {_short(value)}")


def _real_array(name: str, value: Any) -> np.ndarray:
    """``value`` as a new float64 array of its own shape, by the rules of the docstring."""
    if isinstance(value, np.ndarray):
        arr = value
    else:
        try:
            arr = np.asarray(value)
        except (TypeError, ValueError, OverflowError) as exc:
            raise ValueError(f"{name} must be an array of real numbers: {exc}") from None
    kind = arr.dtype.kind
    if kind in _REAL_KINDS:
        return np.array(arr, dtype=np.float64)
    if kind == "c":
        raise ValueError(f"{name} is complex (dtype {arr.dtype}); pass real numbers")
    if kind == "O":
        flat = [_real(name, x) for x in arr.flat]
        return np.array(flat, dtype=np.float64).reshape(arr.shape)
    what = _DTYPE_WORDS.get(kind, f"dtype {arr.dtype}")
    raise ValueError(f"{name} must be an array of real numbers, got {what}")


def as_array(name: str, value: Any) -> np.ndarray:
    """Return ``value`` as a new float64 array of its own shape (any number of dimensions),
    by the rules of the module docstring; non-finite entries are left to the caller."""
    return _real_array(name, value)


def as_vector(name: str, value: Any, length: int | None = None, finite: bool = True) -> np.ndarray:
    """Return ``value`` as a fresh, C-contiguous float64 vector (finite unless
    ``finite=False``).

    Raises ValueError naming ``name`` (never a numpy broadcasting error deep inside an
    integrator, never a silent cast) when the value is not an array of real numbers (see the
    module docstring), is not one-dimensional, has the wrong length, or holds NaN/inf.
    """
    arr = _real_array(name, value)
    if arr.ndim == 0:
        arr = arr.reshape(1)
    if arr.ndim != 1:
        raise ValueError(f"{name} must be one-dimensional, got shape {arr.shape}")
    if length is not None and arr.shape[0] != length:
        raise ValueError(f"{name} has length {arr.shape[0]}, expected {length}")
    if finite and not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} contains NaN or infinity; pass finite numbers")
    return np.ascontiguousarray(arr)


def as_t_span(t_span: Any) -> tuple[float, float]:
    """Return ``(t0, t1)`` as finite floats; ValueError unless it is a pair of real numbers."""
    if isinstance(t_span, (str, bytes)) or _is_complex(t_span):
        raise ValueError(f"t_span must be a pair (t0, t1) of numbers, got {t_span!r}")
    try:
        t0, t1 = t_span
    except (TypeError, ValueError):
        raise ValueError(f"t_span must be a pair (t0, t1) of numbers, got {t_span!r}") from None
    return as_scalar("t_span[0]", t0), as_scalar("t_span[1]", t1)


def native(name: str):
    """The native constructor or function ``name`` of ``physicskit._core``."""
    fn = getattr(_core, name, None)
    if fn is None:  # pragma: no cover - only in a partial build
        raise NotImplementedError(f"{name} is not available in this build of physicskit._core")
    return fn
