"""Hamiltonian systems: Hénon–Heiles, the pendulum swarm, the pendulum's action-angle map."""

from __future__ import annotations

import numpy as np

from .._native import as_scalar, native
from ..core.base_system import HamiltonianSystem
from ._native_base import adopt, build, from_native, keep
from ._native_base import kinetic_energy as _kinetic_energy, potential_energy as _potential_energy

__all__ = ["HenonHeilesSystem", "PendulumSwarm", "pendulum_action_angle"]


class HenonHeilesSystem(HamiltonianSystem):
    """``H = (px^2 + py^2)/2 + (x^2 + y^2)/2 + x^2 y - y^3/3``: a non-integrable 2-DOF
    oscillator; KAM tori dominate below ``E ~ 1/6`` and break into chaos above.

    Parameters
    ----------
    q0, p0 : array-like, shape (2,)
        Initial position ``(x, y)`` and momentum ``(px, py)``.
    """

    kinetic_energy = _kinetic_energy
    potential_energy = _potential_energy

    separable = True
    mass_inv = 1.0

    def __init__(self, q0, p0):
        adopt(self, build("henon-heiles", q0=q0, p0=p0))


class PendulumSwarm(HamiltonianSystem):
    """``N`` independent identical pendulums ``H_i = p_i^2/2 - (g/l) cos q_i`` integrated as
    one separable N-DOF system (Liouville's theorem: the occupied phase-space area is kept).

    Parameters
    ----------
    q0, p0 : array-like, shape (n,)
        Initial angles and momenta, one pair per pendulum.
    g_over_l : float
        Ratio ``g/l`` shared by every pendulum.
    """

    kinetic_energy = _kinetic_energy
    potential_energy = _potential_energy

    separable = True

    def __init__(self, q0, p0, g_over_l: float = 1.0):
        self._adopt(build("pendulum-swarm-state", q0=q0, p0=p0, g_over_l=g_over_l))

    def _adopt(self, nat) -> None:
        keep(self, g_over_l=adopt(self, nat)["g_over_l"], mass_inv=1.0)

    @classmethod
    def from_box(cls, q_center: float, p_center: float, dq: float, dp: float, n: int = 1000,
                 g_over_l: float = 1.0, seed: int = 0):
        """Seed ``n`` points uniformly in the ``dq x dp`` box centred at ``(q_center,
        p_center)``, reproducibly from ``seed``."""
        return from_native(cls, build("pendulum-swarm", q_center=q_center, p_center=p_center,
                                      dq=dq, dp=dp, n=n, g_over_l=g_over_l, seed=seed))

    def per_particle_energy(self, q=None, p=None) -> np.ndarray:
        """Energy of each pendulum, shape (n,); each is conserved (the ensemble is decoupled)."""
        return self._native.per_particle_energy(*self._qp(q, p))

    def phase_space_area(self, q=None, p=None) -> float:
        """Convex-hull area of the ``(q, p)`` point cloud: a proxy of the occupied area."""
        return self._native.phase_space_area(*self._qp(q, p))

    def separatrix_energies(self) -> np.ndarray:
        """Energy of each pendulum's separatrix, ``[g/l]``: the level of the inverted
        pendulum at rest (the saddle), between libration below and rotation above."""
        return self._native.separatrix_energies()


def pendulum_action_angle(E: float, g_over_l: float = 1.0):
    """Action ``J(E)`` and period ``T(E)`` of a librating pendulum orbit
    (``-g/l < E < g/l``), from complete elliptic integrals.

    Raises
    ------
    ValueError
        If ``E`` is outside the librating range.
    """
    return native("pendulum_action_angle")(as_scalar("E", E), as_scalar("g_over_l", g_over_l))
