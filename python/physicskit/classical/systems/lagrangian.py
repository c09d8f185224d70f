"""Lagrangian systems: the double and triple pendulums, the bead on a rotating hoop, coupled
oscillators, the elastic pendulum.

Their equations of motion are derived natively by the Rust Lagrangian engine (automatic
differentiation of L), including the canonical form used by ``implicit_midpoint``.
"""

from __future__ import annotations

from typing import Optional

import numpy as np

from .._native import as_vector
from ..core.base_system import LagrangianSystem
from ._native_base import adopt, build, energy as _energy, keep

__all__ = [
    "DoublePendulum", "TriplePendulum", "BeadOnRotatingHoop", "CoupledOscillators",
    "ElasticPendulum",
]


class DoublePendulum(LagrangianSystem):
    """Planar double pendulum (point masses on massless rods); ``q = (theta1, theta2)`` from
    the downward vertical. Chaotic, and non-separable in canonical form.

    Parameters
    ----------
    theta0, thetadot0 : array-like, shape (2,)
        Initial angles and angular velocities.
    m1, m2 : float
        Bob masses.
    l1, l2 : float
        Rod lengths.
    g : float
        Gravitational acceleration.
    """

    def __init__(self, theta0, thetadot0, m1=1.0, m2=1.0, l1=1.0, l2=1.0, g=9.81):
        v = adopt(self, build("double-pendulum", theta0=theta0, thetadot0=thetadot0, m1=m1,
                              m2=m2, l1=l1, l2=l2, g=g))
        keep(self, **{n: v[n] for n in ("m1", "m2", "l1", "l2", "g")})

    def energy(self, state: Optional[np.ndarray] = None) -> float:
        """Return ``T + V`` of ``state`` (default: ``self.state``)."""
        return _energy(self, state)

    def positions(self, q=None) -> np.ndarray:
        """Bob positions ``(x1, y1, x2, y2)`` for angles ``q`` (default: current angles)."""
        q = self.q if q is None else q
        return self._native.positions(as_vector("q", q, self.ndof))


class TriplePendulum(LagrangianSystem):
    """Planar triple pendulum (three point masses on massless rods hanging one below the
    other from a fixed pivot); ``q = (theta1, theta2, theta3)`` from the downward vertical.
    Chaotic when released from high up, and non-separable in canonical form.

    Parameters
    ----------
    theta0, thetadot0 : array-like, shape (3,)
        Initial angles and angular velocities.
    m1, m2, m3 : float
        Bob masses, top to bottom.
    l1, l2, l3 : float
        Rod lengths, top to bottom.
    g : float
        Gravitational acceleration.
    """

    def __init__(self, theta0, thetadot0, m1=1.0, m2=1.0, m3=1.0, l1=1.0, l2=1.0, l3=1.0,
                 g=9.81):
        v = adopt(self, build("triple-pendulum", theta0=theta0, thetadot0=thetadot0, m1=m1,
                              m2=m2, m3=m3, l1=l1, l2=l2, l3=l3, g=g))
        keep(self, **{n: v[n] for n in ("m1", "m2", "m3", "l1", "l2", "l3", "g")})

    def energy(self, state: Optional[np.ndarray] = None) -> float:
        """Return ``T + V`` of ``state`` (default: ``self.state``)."""
        return _energy(self, state)

    def positions(self, q=None) -> np.ndarray:
        """Bob positions ``(x1, y1, x2, y2, x3, y3)`` for angles ``q`` (default: current
        angles); pivot at the origin, ``y`` up."""
        q = self.q if q is None else q
        return self._native.positions(as_vector("q", q, self.ndof))


class BeadOnRotatingHoop(LagrangianSystem):
    """Bead on a frictionless hoop of radius ``R`` spinning at fixed ``omega`` about its
    vertical diameter; ``q = (theta,)``. Above ``omega_c = sqrt(g/R)`` the bottom equilibrium
    splits (pitchfork bifurcation). ``energy`` is the conserved Jacobi integral.

    Parameters
    ----------
    theta0, thetadot0 : float
        Initial angle and angular velocity.
    R : float
        Hoop radius.
    omega : float
        Rotation rate.
    g : float
        Gravitational acceleration.
    """

    def __init__(self, theta0, thetadot0, R=1.0, omega=2.0, g=9.81):
        v = adopt(self, build("hoop", theta0=theta0, thetadot0=thetadot0, R=R, omega=omega, g=g))
        keep(self, R=v["R"], omega=v["omega"], g=v["g"])

    def energy(self, state: Optional[np.ndarray] = None) -> float:
        """Return the conserved energy (Jacobi integral) of ``state``."""
        return _energy(self, state)

    def positions(self, q=None) -> np.ndarray:
        """Bead position ``(x, y) = (R sin theta, -R cos theta)`` in the hoop's rotating plane
        for ``q = (theta,)`` (default: the current ``q``); hoop centre at the origin, ``y``
        up."""
        q = self.q if q is None else q
        return self._native.positions(as_vector("q", q, self.ndof))

    def separatrix_energies(self) -> np.ndarray:
        """Energies of the separatrices, lowest first: the levels of the saddle equilibria
        (the top, ``2 g R``, while ``R omega^2 + g > 0``; the bottom, ``0``, above the
        critical rate ``omega_c = sqrt(g/R)``)."""
        return self._native.separatrix_energies()


class CoupledOscillators(LagrangianSystem):
    """``N`` equal masses joined by equal linear springs between two fixed walls.

    Parameters
    ----------
    q0, qdot0 : array-like, shape (n,)
        Initial displacements and velocities.
    n : int
        Number of masses.
    m, k : float
        Mass and spring constant.
    """

    def __init__(self, q0, qdot0, n=3, m=1.0, k=1.0):
        v = adopt(self, build("coupled-oscillators", q0=q0, qdot0=qdot0, n=n, m=m, k=k))
        keep(self, n_masses=v["n"], m=v["m"], k=v["k"])

    def energy(self, state: Optional[np.ndarray] = None) -> float:
        """Return ``T + V`` of ``state`` (default: ``self.state``)."""
        return _energy(self, state)


class ElasticPendulum(LagrangianSystem):
    """Spring pendulum: a bob of mass ``m`` on a spring of stiffness ``k`` and rest length
    ``L0``; ``q = (s, theta)``, ``s`` the spring's stretch beyond ``L0`` (the bob is
    ``r = L0 + s`` from the pivot) and ``theta`` from the downward vertical,
    ``L = m (sdot^2 + r^2 thetadot^2)/2 + m g r cos(theta) - k s^2/2``. The bob hangs at
    rest at ``s = m g / k``. At the 2:1 resonance (bounce frequency twice the swing's,
    ``k = 3 m g / L0`` exactly, the swing seeing the stretched length ``L0 + m g / k``) energy
    trades between the bounce and the swing. The default ``k = 39.24`` is ``4 m g / L0``, the
    condition usually quoted, which neglects that stretch: a frequency ratio of ``sqrt(5)``,
    near the resonance.

    Parameters
    ----------
    q0, qdot0 : array-like, shape (2,)
        Initial ``(s, theta)`` and ``(sdot, thetadot)``; ``s > -L0`` (a positive length).
    m : float
        Bob mass.
    k : float
        Spring constant.
    L0 : float
        Rest length of the spring.
    g : float
        Gravitational acceleration.
    """

    def __init__(self, q0, qdot0, m=1.0, k=39.24, L0=1.0, g=9.81):
        v = adopt(self, build("elastic-pendulum", q0=q0, qdot0=qdot0, m=m, k=k, L0=L0, g=g))
        keep(self, m=v["m"], k=v["k"], L0=v["L0"], g=v["g"])

    def energy(self, state: Optional[np.ndarray] = None) -> float:
        """Return ``T + V`` of ``state`` (default: ``self.state``)."""
        return _energy(self, state)

    def positions(self, q=None) -> np.ndarray:
        """Bob position ``(x, y) = (r sin theta, -r cos theta)``, ``r = L0 + s``, for
        ``q = (s, theta)`` (default: the current ``q``); pivot at the origin, ``y`` up."""
        q = self.q if q is None else q
        return self._native.positions(as_vector("q", q, self.ndof))

    def mode_energies(self, state=None) -> np.ndarray:
        """``(E_bounce, E_swing)`` of ``state`` (default: the current state); they sum to the
        energy above the hanging equilibrium."""
        s = self._state_arg(state)
        return self._native.modal_energies(s[: self.ndof], s[self.ndof:])
