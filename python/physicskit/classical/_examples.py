"""Reference systems of the Rust core (not part of the spec), used by the tests.

``Pendulum`` and ``HarmonicOscillator`` wrap ``physicskit::classical::examples``; they are the
smallest built-in systems and so the cleanest probes of the binding layer itself.
"""

from __future__ import annotations

from ._native import as_vector, native
from .core.base_system import HamiltonianSystem
from .systems._native_base import adopt, kinetic_energy as _kinetic_energy, potential_energy as _potential_energy

__all__ = ["Pendulum", "HarmonicOscillator"]


class Pendulum(HamiltonianSystem):
    """Simple pendulum ``H = p^2/2 - (g/l) cos q`` (one degree of freedom)."""

    kinetic_energy = _kinetic_energy
    potential_energy = _potential_energy

    def __init__(self, q0, p0, g_over_l=1.0):
        adopt(self, native("pendulum")(as_vector("q0", q0, 1), as_vector("p0", p0, 1), float(g_over_l)))
        self.g_over_l = float(g_over_l)


class HarmonicOscillator(HamiltonianSystem):
    """Harmonic oscillator ``H = p^2/(2m) + k q^2/2`` (one degree of freedom)."""

    kinetic_energy = _kinetic_energy
    potential_energy = _potential_energy

    def __init__(self, q0, p0, m=1.0, k=1.0):
        adopt(self, 
            native("harmonic_oscillator")(
                as_vector("q0", q0, 1), as_vector("p0", p0, 1), float(m), float(k)
            )
        )
        self.m = float(m)
        self.k = float(k)
        self.mass_inv = 1.0 / self.m
