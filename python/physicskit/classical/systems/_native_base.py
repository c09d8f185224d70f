"""Shared plumbing of the built-in systems: adopt a native Rust object as ``self._native``."""

from __future__ import annotations

from typing import Optional

import numpy as np

from .._native import as_int, as_vector

__all__ = ["as_int", "adopt", "kinetic_energy", "potential_energy", "energy"]


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
