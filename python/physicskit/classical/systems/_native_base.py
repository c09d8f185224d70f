"""Shared plumbing of the built-in systems: adopt a native Rust object as ``self._native``."""

from __future__ import annotations

import operator
from typing import Optional

import numpy as np

from .._native import as_vector


def as_int(name: str, value, minimum: int = 0) -> int:
    """``value`` as an int >= ``minimum``; ValueError saying what to change otherwise."""
    try:
        n = operator.index(value)
    except TypeError:
        if isinstance(value, float) and value.is_integer():
            n = int(value)
        else:
            raise ValueError(f"{name} must be an integer, got {value!r}") from None
    if n < minimum:
        raise ValueError(f"{name} must be >= {minimum}, got {n}")
    return n


def adopt(system, nat) -> None:
    """Make ``nat`` the numerics of ``system`` and copy its validated initial state."""
    system._native = nat
    system.state = nat.state
    system.t = 0.0
    if nat.ndof is not None:
        system.ndof = nat.ndof


def kinetic_energy(self, p: np.ndarray) -> float:
    """Return the kinetic energy T(p)."""
    return self._native.kinetic_energy(as_vector("p", p, self.ndof))


def potential_energy(self, q: np.ndarray) -> float:
    """Return the potential energy V(q)."""
    return self._native.potential_energy(as_vector("q", q, self.ndof))


def energy(self, state: Optional[np.ndarray] = None) -> float:
    """Return the total mechanical energy of ``state`` (default: ``self.state``)."""
    return self._native.energy(self._state_arg(state))
