"""Rigid bodies: the torque-free Euler top and the heavy symmetric top, with the heavy top's
effective-potential analysis."""

from __future__ import annotations

from typing import Optional

import numpy as np

from .._native import as_array, as_scalar, as_vector, native
from ..core.base_system import LagrangianSystem, ODESystem
from ._native_base import adopt, build, energy as _energy

__all__ = [
    "EulerTop",
    "HeavySymmetricTop",
    "effective_potential_symmetric_top",
    "find_theta_equilibrium",
    "nutation_frequency",
    "precession_frequency",
]


class EulerTop(ODESystem):
    """Torque-free rigid body: Euler's equations for the body-frame ``omega`` coupled to the
    orientation quaternion; state ``[w1, w2, w3, qw, qx, qy, qz]``. The default
    ``implicit_midpoint`` conserves energy, ``|L|^2`` and the quaternion norm exactly (they are
    quadratic invariants).

    Parameters
    ----------
    omega0 : array-like, shape (3,)
        Initial body-frame angular velocity.
    I1, I2, I3 : float
        Principal moments of inertia.
    quat0 : array-like, shape (4,), optional
        Initial orientation ``(w, x, y, z)``, normalized; default the identity.
    """

    def __init__(self, omega0, I1=1.0, I2=2.0, I3=3.0, quat0=None):
        v = adopt(self, build("euler-top", omega0=omega0, I1=I1, I2=I2, I3=I3, quat0=quat0))
        self.I1, self.I2, self.I3 = v["I1"], v["I2"], v["I3"]

    @property
    def omega(self) -> np.ndarray:
        """Body-frame angular velocity (the first three entries of ``state``)."""
        return self.state[:3]

    @property
    def quaternion(self) -> np.ndarray:
        """Orientation quaternion ``(w, x, y, z)`` (the last four entries of ``state``)."""
        return self.state[3:7]

    def energy(self, state: Optional[np.ndarray] = None) -> float:
        """Rotational kinetic energy ``(I1 w1^2 + I2 w2^2 + I3 w3^2)/2``."""
        return self._native.energy(self._state_arg(state))

    def angular_momentum_squared(self, state: Optional[np.ndarray] = None) -> float:
        """``|L|^2`` in the body frame."""
        return self._native.angular_momentum_squared(self._state_arg(state))

    def rotation_matrix(self, state: Optional[np.ndarray] = None) -> np.ndarray:
        """Body-to-world rotation matrix, shape (3, 3), from the state's quaternion."""
        return self._native.rotation_matrix(self._state_arg(state))

    def body_angular_momentum(self, state: Optional[np.ndarray] = None) -> np.ndarray:
        """Body-frame angular momentum ``L = (I1 w1, I2 w2, I3 w3)``, shape (3,), of ``state``
        (default: the current state). Its tip traces a polhode on the sphere ``|L|^2 =
        const``; ``rotation_matrix(state) @ L`` is the conserved space-frame vector."""
        return self._native.body_angular_momentum(self._state_arg(state))

    def inertia_box(self, mass: float = 1.0) -> np.ndarray:
        """Half-extents ``(a1, a2, a3)``, shape (3,), of the uniform box of mass ``mass`` with
        the principal moments ``I1, I2, I3`` (``a1^2 = 3 (I2 + I3 - I1) / (2 mass)``): the
        shape to draw the body as. ValueError for moments no rigid body has (one above the
        sum of the other two)."""
        return self._native.inertia_box(as_scalar("mass", mass))


class HeavySymmetricTop(LagrangianSystem):
    """Symmetric top with a fixed point, under gravity; ``q = (phi, theta, psi)`` z-x-z Euler
    angles, ``L = (I1/2)(thetadot^2 + phidot^2 sin^2 theta) + (I3/2)(psidot + phidot cos
    theta)^2 - M g l cos theta``. Non-separable: integrated by ``implicit_midpoint``.

    Parameters
    ----------
    angles0, angledots0 : array-like, shape (3,)
        Initial ``(phi, theta, psi)`` and their rates.
    I1, I3 : float
        Transverse (about the fixed point) and axial moments of inertia.
    M : float
        Mass.
    l : float
        Pivot to centre-of-mass distance.
    g : float
        Gravitational acceleration.
    """

    def __init__(self, angles0, angledots0, I1=1.0, I3=0.5, M=1.0, l=1.0, g=9.81):  # noqa: E741
        v = adopt(self, build("heavy-top", angles0=angles0, angledots0=angledots0, I1=I1, I3=I3,
                              M=M, l=l, g=g))
        self.I1, self.I3, self.M, self.l, self.g = (v[n] for n in ("I1", "I3", "M", "l", "g"))

    def energy(self, state: Optional[np.ndarray] = None) -> float:
        """Return ``T + V`` of ``state`` (default: ``self.state``)."""
        return _energy(self, state)

    def precession_nutation_rate(self, state: Optional[np.ndarray] = None):
        """Instantaneous ``(phidot, thetadot)``: precession and nutation rates."""
        return self._native.precession_nutation_rate(self._state_arg(state))

    def symmetry_axis(self, q=None) -> np.ndarray:
        """Unit vector along the symmetry axis in space (z up), shape (3,), for the Euler
        angles ``q = (phi, theta, psi)`` (default: the current ``q``):
        ``(sin theta sin phi, -sin theta cos phi, cos theta)``."""
        q = self.q if q is None else q
        return self._native.symmetry_axis(as_vector("q", q, self.ndof))


def effective_potential_symmetric_top(theta, p_phi: float, p_psi: float, I1: float, I3: float,
                                      Mgl: float):
    """``V_eff(theta) = (p_phi - p_psi cos theta)^2 / (2 I1 sin^2 theta) + p_psi^2/(2 I3) +
    Mgl cos theta`` for the conserved momenta ``p_phi``, ``p_psi``; array of theta's shape."""
    th = as_array("theta", theta)
    v = native("effective_potential_symmetric_top")(
        as_vector("theta", th.ravel()), as_scalar("p_phi", p_phi), as_scalar("p_psi", p_psi),
        as_scalar("I1", I1), as_scalar("I3", I3), as_scalar("Mgl", Mgl),
    )
    return v.reshape(th.shape)


def find_theta_equilibrium(p_phi: float, p_psi: float, I1: float, I3: float, Mgl: float,
                           bracket=(0.001, 3.1405926535897932)) -> float:
    """The angle minimizing ``V_eff`` inside ``bracket``: steady precession's nutation angle.

    Found as the root of the analytic ``V_eff'(theta)``, bisected to adjacent floats (a few
    ulps); ``ValueError`` naming ``bracket`` if ``V_eff`` has no interior minimum there."""
    try:
        lo, hi = bracket
    except (TypeError, ValueError):
        raise ValueError(f"bracket must be a pair (lo, hi), got {bracket!r}") from None
    return native("find_theta_equilibrium")(
        as_scalar("p_phi", p_phi), as_scalar("p_psi", p_psi), as_scalar("I1", I1),
        as_scalar("I3", I3), as_scalar("Mgl", Mgl), (as_scalar("bracket[0]", lo),
                                                      as_scalar("bracket[1]", hi)),
    )


def nutation_frequency(p_phi: float, p_psi: float, I1: float, I3: float, Mgl: float,
                       theta_eq: Optional[float] = None, dtheta: float = 1e-05) -> float:
    """Small-oscillation nutation frequency ``sqrt(V_eff''(theta_eq) / I1)`` (central
    difference of step ``dtheta``); ``theta_eq`` defaults to :func:`find_theta_equilibrium`."""
    return native("nutation_frequency")(
        as_scalar("p_phi", p_phi), as_scalar("p_psi", p_psi), as_scalar("I1", I1),
        as_scalar("I3", I3), as_scalar("Mgl", Mgl),
        None if theta_eq is None else as_scalar("theta_eq", theta_eq), as_scalar("dtheta", dtheta),
    )


def precession_frequency(p_phi: float, p_psi: float, I1: float, theta_eq: float) -> float:
    """Steady precession rate ``(p_phi - p_psi cos theta_eq) / (I1 sin^2 theta_eq)``."""
    return native("precession_frequency")(
        as_scalar("p_phi", p_phi), as_scalar("p_psi", p_psi), as_scalar("I1", I1),
        as_scalar("theta_eq", theta_eq),
    )
