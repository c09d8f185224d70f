"""Rigid bodies: the torque-free Euler top and the heavy symmetric top, with the heavy top's
effective-potential analysis; the reduced (phenomenological) Euler's disk and rattleback."""

from __future__ import annotations

from typing import Optional

import numpy as np

from .._native import as_array, as_scalar, as_vector, native
from ..core.base_system import LagrangianSystem, ODESystem, SimulationResult
from ._native_base import adopt, build, energy as _energy, keep

__all__ = [
    "EulerTop",
    "HeavySymmetricTop",
    "EulersDisk",
    "Rattleback",
    "eulers_disk_theta_analytic",
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
        keep(self, I1=v["I1"], I2=v["I2"], I3=v["I3"])

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
        keep(self, **{n: v[n] for n in ("I1", "I3", "M", "l", "g")})

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


class EulersDisk(ODESystem):
    """A reduced, phenomenological model of Euler's disk running down; state
    ``[theta, phi]``: the disk's inclination to the table and the contact point's azimuth.

    Not rolling mechanics: the two rates diverge as the disk flattens, which drives ``theta``
    to zero in finite time (Moffatt's finite-time singularity, Nature 404 (2000) 833)::

        theta' = -decay_rate / max(theta, theta_floor)
        phi'   = precession_const / max(theta, theta_floor)

    Above the floor ``theta(t) = sqrt(theta0^2 - 2 decay_rate t)``
    (:func:`eulers_disk_theta_analytic`), zero at ``theta0^2 / (2 decay_rate)``.

    There is no conserved energy: :meth:`energy` returns ``theta`` itself (as the peer
    package, physicskit 0.4.0, does), a quantity that decays to zero at the collapse.

    Parameters
    ----------
    theta0 : float
        Initial inclination (rad).
    phi0 : float
        Initial azimuth of the contact point (rad).
    decay_rate : float
        ``>= 0``: sets the collapse time ``theta0^2 / (2 decay_rate)``.
    precession_const : float
        Precession rate times ``theta``.
    theta_floor : float
        ``> 0``: the smallest ``theta`` the rates divide by.
    """

    def __init__(self, theta0: float, phi0: float = 0.0, decay_rate: float = 0.05,
                 precession_const: float = 1.0, theta_floor: float = 1e-3):
        v = adopt(self, build("eulers-disk", theta0=theta0, phi0=phi0, decay_rate=decay_rate,
                              precession_const=precession_const, theta_floor=theta_floor))
        keep(self, decay_rate=v["decay_rate"], precession_const=v["precession_const"],
             theta_floor=v["theta_floor"])

    @property
    def theta(self) -> float:
        """Current inclination (rad)."""
        return float(self.state[0])

    @property
    def phi(self) -> float:
        """Current azimuth of the contact point (rad)."""
        return float(self.state[1])

    def energy(self, state: Optional[np.ndarray] = None) -> float:
        """``theta`` of ``state`` (default: the current state): not an energy (the model is
        dissipative by design) but the inclination, which decreases to zero at the collapse;
        it stands in the ``energy`` slot as in the peer package."""
        return self._native.energy(self._state_arg(state))

    def integrate(self, t_span, dt: float, method: str = "implicit_midpoint") -> SimulationResult:
        """Integrate with fixed step ``dt`` (``"dop853"``: adaptive)."""
        return super().integrate(t_span, dt, method)


def eulers_disk_theta_analytic(t, theta0: float, decay_rate: float) -> np.ndarray:
    """``theta(t) = sqrt(theta0^2 - 2 decay_rate t)`` of :class:`EulersDisk` (the floor
    ignored), zero from the collapse time ``theta0^2 / (2 decay_rate)`` on; array of ``t``'s
    shape."""
    t_arr = as_array("t", t)
    theta = native("eulers_disk_theta_analytic")(
        as_vector("t", t_arr.ravel()), as_scalar("theta0", theta0),
        as_scalar("decay_rate", decay_rate),
    )
    return theta.reshape(t_arr.shape)


class Rattleback(ODESystem):
    """A reduced, phenomenological model of the rattleback's spin reversal; state
    ``[n1, n2, n3]``: two rocking rates and the spin.

    Not rolling mechanics (a real rattleback reverses through its rolling contact and
    misaligned inertia axes: Garcia & Hubbard, Proc. R. Soc. Lond. A 418 (1988)). The peer
    package's (physicskit 0.4.0) equations: Euler's equations of a free body, a term even in
    the spin added to the first rocking mode, linear damping ``mu`` and cubic saturation
    ``eta``::

        n1' = (I2 - I3)/I1 n2 n3 + gamma n3^2 - mu n1 - eta n1^3
        n2' = (I3 - I1)/I2 n3 n1             - mu n2 - eta n2^3
        n3' = (I1 - I2)/I3 n1 n2             - mu n3

    A strong spin pumps the rocking, which brakes the spin until it reverses. The equations
    are unchanged by ``(n1, n2, n3) -> (n1, -n2, -n3)``, so a spin of either sense reverses
    (the run from ``(n1, -n2, -n3)`` mirrors the run from ``(n1, n2, n3)`` exactly). With
    ``gamma = 0`` it is a damped Euler top and never reverses.

    Parameters
    ----------
    n0 : array-like, shape (3,)
        Initial ``(n1, n2, n3)``, e.g. ``[0.01, 0.01, 3.0]``: a hard spin, a little rocking.
    I1, I2, I3 : float
        Moments of inertia (> 0).
    gamma : float
        Coupling of the spin into the first rocking mode.
    mu : float
        Linear damping rate (>= 0).
    eta : float
        Cubic saturation of the rocking (>= 0).
    """

    def __init__(self, n0, I1: float = 1.0, I2: float = 1.5, I3: float = 2.0,
                 gamma: float = 1.0, mu: float = 0.01, eta: float = 0.01):
        v = adopt(self, build("rattleback", n0=n0, I1=I1, I2=I2, I3=I3, gamma=gamma, mu=mu,
                              eta=eta))
        keep(self, **{n: v[n] for n in ("I1", "I2", "I3", "gamma", "mu", "eta")})

    def energy(self, state: Optional[np.ndarray] = None) -> float:
        """Kinetic energy ``(I1 n1^2 + I2 n2^2 + I3 n3^2)/2`` of ``state`` (default: the
        current state); not conserved (the model is dissipative and pumped)."""
        return self._native.energy(self._state_arg(state))

    def integrate(self, t_span, dt: float, method: str = "implicit_midpoint") -> SimulationResult:
        """Integrate with fixed step ``dt`` (``"dop853"``: adaptive)."""
        return super().integrate(t_span, dt, method)
