"""Rigid bodies rolling without slipping on a horizontal plane under gravity, from the
Newton–Euler equations with the no-slip constraint (no reduced model): the rattleback
(``RollingRattleback``) and the thin disk rolling on its rim (``RollingDisk``).

State ``[w1, w2, w3, qw, qx, qy, qz, x, y]``: the angular velocity in the body frame, the
body-to-world orientation quaternion and the contact point on the plane. The equations, the
quaternion policy (never renormalized; every evaluation uses ``q / |q|``) and the parameter
checks live in the native catalogue (``crates/physicskit/src/classical/systems/rolling.rs``);
these classes pass their arguments to it.
"""

from __future__ import annotations

from typing import Optional

import numpy as np

from ..core.base_system import ODESystem, SimulationResult
from ._native_base import adopt, build, energy as _energy, from_native

__all__ = ["RollingRattleback", "RollingDisk"]


class _Rolling(ODESystem):
    """What both rolling bodies share: the state's parts, the orientation, the vertical spin,
    and ``dop853`` as the default method (the energy is not a quadratic invariant, so
    ``implicit_midpoint`` has no advantage here)."""

    def energy(self, state: Optional[np.ndarray] = None) -> float:
        """Kinetic energy of the rolling body plus ``m g`` times the height of its centre of
        mass (J); conserved: the contact force does no work."""
        return _energy(self, state)

    @property
    def omega(self) -> np.ndarray:
        """Body-frame angular velocity (rad/s), the first three entries of ``state``."""
        return self.state[:3]

    @property
    def quaternion(self) -> np.ndarray:
        """Orientation quaternion ``(w, x, y, z)``, entries 3 to 6 of ``state``."""
        return self.state[3:7]

    @property
    def contact_point(self) -> np.ndarray:
        """The contact point ``(x, y)`` on the plane (m), the last two entries of ``state``."""
        return self.state[7:9]

    def rotation_matrix(self, state: Optional[np.ndarray] = None) -> np.ndarray:
        """Body-to-world rotation matrix, shape (3, 3), of ``state``'s normalized quaternion."""
        return self._native.rotation_matrix(self._state_arg(state))

    def vertical_spin(self, state: Optional[np.ndarray] = None) -> float:
        """The spin about the vertical, ``omega . gamma`` (rad/s), ``gamma`` the world's up
        axis seen from the body (the last row of the rotation matrix)."""
        s = self._state_arg(state)
        return float(self.rotation_matrix(s)[2] @ s[:3])

    def vertical_spins(self, result: SimulationResult) -> np.ndarray:
        """:meth:`vertical_spin` of every sample of ``result``, shape (n_samples,)."""
        return np.array([self.vertical_spin(row) for row in np.asarray(result.y)])

    def integrate(self, t_span, dt: float, method: str = "dop853") -> SimulationResult:
        """Integrate over ``t_span`` (``dt``: the step, or ``dop853``'s output spacing)."""
        return super().integrate(t_span, dt, method)


class RollingRattleback(_Rolling):
    """A rattleback rolling without slipping: an ellipsoid ``x^2/a^2 + y^2/b^2 + (z-h)^2/c^2 =
    1`` around its centre of mass, whose principal inertia axes are turned by ``delta`` about
    the vertical from the geometric axes. The defaults are Kane & Levinson's body (1982): spun
    at ``omega0 = (0, 0, -3)`` it reverses within seconds; at ``+3`` it keeps its sense far
    longer.

    Parameters
    ----------
    omega0 : array-like, shape (3,)
        Initial body-frame angular velocity (rad/s).
    a, b, c : float
        Semi-axes (m), ``a`` along the long axis ``x``, ``c`` along the vertical.
    h : float
        Height of the ellipsoid's centre above the centre of mass (m), in ``(-c, c)``.
    m : float
        Mass (kg).
    I1, I2, I3 : float
        Principal moments of inertia (kg m^2); no one above the sum of the other two.
    delta : float
        Angle (rad) about ``z`` from the geometric to the principal inertia axes.
    g : float
        Gravitational acceleration (m/s^2).
    quat0 : array-like, shape (4,), optional
        Initial orientation ``(w, x, y, z)``; default tilted by 0.5 degrees in roll and pitch.
    """

    def __init__(self, omega0, a=0.2, b=0.03, c=0.02, h=0.01, m=1.0,
                 I1=1.9971434399953625e-4, I2=1.600285656000464e-3, I3=1.7e-3,
                 delta=0.01428182891938, g=9.81, quat0=None):
        v = adopt(self, build("rolling-rattleback", omega0=omega0, a=a, b=b, c=c, h=h, m=m,
                              I1=I1, I2=I2, I3=I3, delta=delta, g=g, quat0=quat0))
        self.a, self.b, self.c, self.h, self.m = v["a"], v["b"], v["c"], v["h"], v["m"]
        self.I1, self.I2, self.I3 = v["I1"], v["I2"], v["I3"]
        self.delta, self.g = v["delta"], v["g"]


class RollingDisk(_Rolling):
    """A thin uniform disk (radius ``a``, mass ``m``) rolling without slipping on its rim:
    Euler's disk with no dissipation. ``RollingDisk.steady(theta, precession)`` starts it on a
    steady rolling circle.

    Parameters
    ----------
    omega0 : array-like, shape (3,)
        Initial body-frame angular velocity (rad/s); body ``z`` is the disk's normal.
    a, m, g : float
        Radius (m), mass (kg) and gravitational acceleration (m/s^2).
    quat0 : array-like, shape (4,), optional
        Initial orientation ``(w, x, y, z)``; default the disk 1 rad from the table.
    """

    def __init__(self, omega0, a=0.05, m=1.0, g=9.81, quat0=None):
        self._adopt(build("rolling-disk", omega0=omega0, a=a, m=m, g=g, quat0=quat0))

    def _adopt(self, nat) -> None:
        v = adopt(self, nat)
        self.a, self.m, self.g = v["a"], v["m"], v["g"]

    @classmethod
    def steady(cls, theta: float, precession: float, a: float = 0.05, m: float = 1.0,
               g: float = 9.81) -> "RollingDisk":
        """The disk rolling steadily, tilted at ``theta`` (rad, in ``(0, pi/2]``) from the
        table, its normal precessing about the vertical at ``precession`` (rad/s, non-zero),
        with the spin about its normal from Routh's condition
        ``w3 = cos(theta) (I1 precession^2 sin(theta) - m g a) / ((I3 + m a^2) precession
        sin(theta))``."""
        return from_native(cls, build("rolling-disk-steady", theta=theta,
                                      precession=precession, a=a, m=m, g=g))
