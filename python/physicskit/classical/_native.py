"""Helpers shared by the Python layer: input validation and access to the native module."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .. import _core

__all__ = ["_core", "as_vector", "as_scalar", "as_t_span", "native"]


def as_vector(name: str, value: Any, length: int | None = None, finite: bool = True) -> np.ndarray:
    """Return ``value`` as a fresh, finite, C-contiguous float64 vector.

    Raises ValueError (never a numpy broadcasting error deep inside an integrator) when the
    value is not one-dimensional, has the wrong length, or holds NaN/inf.
    """
    try:
        arr = np.array(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be an array of real numbers: {exc}") from None
    if arr.ndim == 0:
        arr = arr.reshape(1)
    if arr.ndim != 1:
        raise ValueError(f"{name} must be one-dimensional, got shape {arr.shape}")
    if length is not None and arr.shape[0] != length:
        raise ValueError(f"{name} has length {arr.shape[0]}, expected {length}")
    if finite and not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} contains NaN or infinity; pass finite numbers")
    return np.ascontiguousarray(arr)


def as_scalar(name: str, value: Any) -> float:
    """Return ``value`` as a finite float, or raise ValueError saying what is wrong."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None
    if not math.isfinite(x):
        raise ValueError(f"{name} must be finite, got {x}")
    return x


def as_t_span(t_span: Any) -> tuple[float, float]:
    """Return ``(t0, t1)`` as floats; ValueError unless it is a pair of numbers."""
    try:
        t0, t1 = t_span
        return float(t0), float(t1)
    except (TypeError, ValueError):
        raise ValueError(f"t_span must be a pair (t0, t1) of numbers, got {t_span!r}") from None


def native(name: str):
    """The native constructor or function ``name`` of ``physicskit._core``."""
    fn = getattr(_core, name, None)
    if fn is None:  # pragma: no cover - only in a partial build
        raise NotImplementedError(f"{name} is not available in this build of physicskit._core")
    return fn

