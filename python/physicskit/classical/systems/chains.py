"""Lattice chains: the harmonic chain, the FPUT-beta chain and the sine-Gordon
(Frenkel-Kontorova) chain, with their fixed-end normal-mode analysis."""

from __future__ import annotations

import operator

import numpy as np

from .._native import as_scalar, as_vector, native
from ..core.base_system import HamiltonianSystem
from ._native_base import adopt, as_int, build, keep

__all__ = ["HarmonicChain", "FPUTChain", "SineGordonChain", "TodaLattice"]


class _ChainBase(HamiltonianSystem):
    """Common base of the chains: ``N`` equal masses ``m`` coupled by springs ``k``, with the
    normal modes of the fixed-end harmonic chain, ``omega_j = 2 sqrt(k/m) sin(j pi / (2(N+1)))``.

    Parameters
    ----------
    q0, p0 : array-like, shape (n,)
        Initial displacements and momenta.
    m, k : float
        Mass and linear spring constant.
    """

    separable = True

    def __init__(self, q0, p0, m=1.0, k=1.0):
        self._adopt(build("harmonic-chain", q0=q0, p0=p0, m=m, k=k))

    def _adopt(self, nat) -> dict:
        v = adopt(self, nat)
        keep(self, m=v["m"], k=v["k"], mass_inv=1.0 / v["m"])
        return v

    def kinetic_energy(self, p: np.ndarray) -> float:
        """Return ``T(p) = |p|^2 / (2m)``."""
        return self._native.kinetic_energy(as_vector("p", p, self.ndof))

    def normal_mode_frequencies(self) -> np.ndarray:
        """Angular frequencies ``omega_j``, ``j = 1..N``, shape (n,)."""
        return self._native.normal_mode_frequencies()

    def normal_mode_coords(self, q=None, p=None):
        """Modal amplitudes ``(Q, P)`` (sine transform) of a state; default: current state."""
        return self._native.normal_mode_coordinates(*self._qp(q, p))

    def modal_energies(self, q=None, p=None) -> np.ndarray:
        """Harmonic energy in each normal mode, ``E_j = P_j^2/(2m) + m omega_j^2 Q_j^2/2``."""
        return self._native.modal_energies(*self._qp(q, p))


class HarmonicChain(_ChainBase):
    """Linear chain of ``N`` masses and identical springs, both ends fixed to walls: the
    exactly solvable reference lattice.

    Parameters
    ----------
    q0, p0 : array-like, shape (n,)
        Initial displacements and momenta.
    m, k : float
        Mass and spring constant.
    """

    def __init__(self, q0, p0, m=1.0, k=1.0):
        super().__init__(q0, p0, m=m, k=k)

    def potential_energy(self, q: np.ndarray) -> float:
        """Return ``V(q) = (k/2) sum (q_{i+1} - q_i)^2`` with fixed walls."""
        return self._native.potential_energy(as_vector("q", q, self.ndof))


class FPUTChain(_ChainBase):
    """Fermi-Pasta-Ulam-Tsingou beta chain, ``V(r) = (k/2) r^2 + (beta/4) r^4`` per bond,
    started in one normal mode (the FPUT recurrence).

    Parameters
    ----------
    n : int
        Number of masses.
    m, k : float
        Mass and linear spring constant.
    beta : float
        Quartic coupling.
    mode : int
        Normal mode excited at t = 0 (1..n).
    amplitude : float
        Its initial amplitude.
    """

    def __init__(self, n=32, m=1.0, k=1.0, beta=0.0, mode=1, amplitude=1.0):
        v = self._adopt(build("fput", n=n, m=m, k=k, beta=beta, mode=mode, amplitude=amplitude))
        keep(self, beta=v["beta"], mode=v["mode"], amplitude=v["amplitude"])

    def potential_energy(self, q: np.ndarray) -> float:
        """Return ``V(q) = sum_bonds (k/2) r^2 + (beta/4) r^4``."""
        return self._native.potential_energy(as_vector("q", q, self.ndof))


class SineGordonChain(_ChainBase):
    """Chain of pendulums (Frenkel-Kontorova), ``V = sum (k/2)(q_{i+1} - q_i)^2 + (1 - cos
    q_i)``, free ends; carries sine-Gordon kinks (see :meth:`kink`).

    Parameters
    ----------
    n : int
        Number of pendulums.
    m, k : float
        Mass and coupling constant.
    q0, p0 : array-like, shape (n,), optional
        Initial displacements and momenta (default zeros).
    """

    def __init__(self, n=200, m=1.0, k=1.0, q0=None, p0=None):
        self._adopt(build("sine-gordon-state", n=n, m=m, k=k, q0=q0, p0=p0))

    @staticmethod
    def kink(n: int, center: float, width: float = 1.0, velocity: float = 0.0,
             polarity: int = 1) -> tuple:
        """Lorentz-boosted single-kink (``polarity=+1``) or antikink (``-1``) initial data
        ``(q0, p0)``; ``|velocity| < 1`` (the wave speed for m = k = 1).

        Raises
        ------
        ValueError
            If ``abs(velocity) >= 1``.
        """
        # Any other integer reaches the native check, which names the two valid values.
        pol = as_int("polarity", polarity, minimum=-(2**31), maximum=2**31 - 1)
        return native("sine_gordon_kink")(
            as_int("n", n), as_scalar("center", center), as_scalar("width", width),
            as_scalar("velocity", velocity), pol,
        )

    def potential_energy(self, q: np.ndarray) -> float:
        """Return ``V(q) = sum (k/2)(q_{i+1} - q_i)^2 + (1 - cos q_i)``."""
        return self._native.potential_energy(as_vector("q", q, self.ndof))


class TodaLattice(HamiltonianSystem):
    """Periodic Toda lattice, ``H = sum p_i^2/2 + (a/b) sum exp(-b (q_{i+1} - q_i))`` with
    ``q_{n+1} = q_1``: ``n`` unit masses on a ring joined by exponential springs, completely
    integrable. The ``n`` eigenvalues of Flaschka's Lax matrix are conserved
    (:meth:`conserved_quantities`) while the energy moves between the particles
    (:meth:`per_particle_energy`).

    Parameters
    ----------
    q0, p0 : array-like, shape (n,)
        Initial positions and momenta, ``n >= 2``.
    a, b : float
        Bond strength and anharmonicity (both > 0): small oscillations have stiffness ``a b``.
    """

    separable = True

    def __init__(self, q0, p0, a=1.0, b=1.0):
        v = adopt(self, build("toda", q0=q0, p0=p0, a=a, b=b))
        keep(self, a=v["a"], b=v["b"], mass_inv=1.0)

    def kinetic_energy(self, p: np.ndarray) -> float:
        """Return ``T(p) = |p|^2 / 2``."""
        return self._native.kinetic_energy(as_vector("p", p, self.ndof))

    def potential_energy(self, q: np.ndarray) -> float:
        """Return ``V(q) = (a/b) sum exp(-b (q_{i+1} - q_i))`` around the ring."""
        return self._native.potential_energy(as_vector("q", q, self.ndof))

    def conserved_quantities(self, state=None) -> np.ndarray:
        """The ``n`` eigenvalues of Flaschka's Lax matrix of ``state`` (default: the current
        state), ascending; ``sum = total momentum`` and ``sum of squares = 2 H`` (``2 H + 4 a/b``
        for ``n = 2``)."""
        return self._native.conserved_quantities(self._state_arg(state))

    def per_particle_energy(self, q=None, p=None) -> np.ndarray:
        """Energy of each particle, ``p_i^2/2`` plus half of each of its two bonds; sums to
        ``H``."""
        return self._native.per_particle_energy(*self._qp(q, p))
