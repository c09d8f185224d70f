"""Reference systems of the Rust core (not part of the spec), used by the tests.

``Pendulum`` and ``HarmonicOscillator`` wrap ``physicskit::classical::examples``; they are the
smallest built-in systems and so the cleanest probes of the binding layer itself.
"""

from __future__ import annotations

import numpy as np

from ._native import as_vector, native
from .core.base_system import HamiltonianSystem

__all__ = ["Pendulum", "HarmonicOscillator"]


class _NativeHamiltonian(HamiltonianSystem):
    """A HamiltonianSystem whose numerics are a native Rust object in ``self._native``."""

    def _adopt(self, nat) -> None:
        self._native = nat
        self.state = nat.state
        self.t = 0.0
        self.ndof = nat.ndof

    def kinetic_energy(self, p: np.ndarray) -> float:
        """Return T(p)."""
        return self._native.kinetic_energy(as_vector("p", p, self.ndof))

    def potential_energy(self, q: np.ndarray) -> float:
        """Return V(q)."""
        return self._native.potential_energy(as_vector("q", q, self.ndof))


class Pendulum(_NativeHamiltonian):
    """Simple pendulum ``H = p^2/2 - (g/l) cos q`` (one degree of freedom)."""

    def __init__(self, q0, p0, g_over_l=1.0):
        self._adopt(native("pendulum")(as_vector("q0", q0, 1), as_vector("p0", p0, 1), float(g_over_l)))
        self.g_over_l = float(g_over_l)


class HarmonicOscillator(_NativeHamiltonian):
    """Harmonic oscillator ``H = p^2/(2m) + k q^2/2`` (one degree of freedom)."""

    def __init__(self, q0, p0, m=1.0, k=1.0):
        self._adopt(
            native("harmonic_oscillator")(
                as_vector("q0", q0, 1), as_vector("p0", p0, 1), float(m), float(k)
            )
        )
        self.m = float(m)
        self.k = float(k)
        self.mass_inv = 1.0 / self.m
