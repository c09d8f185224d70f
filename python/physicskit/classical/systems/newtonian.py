"""Newtonian systems: the planar Kepler problem, projectile motion and Foucault's pendulum."""

from __future__ import annotations

import numpy as np

from .._native import as_array, as_scalar, as_vector, native
from ..core.base_system import HamiltonianSystem, ODESystem, SimulationResult
from ._native_base import adopt, build, from_native, keep
from ._native_base import kinetic_energy as _kinetic_energy, potential_energy as _potential_energy

__all__ = ["ProjectileMotion", "KeplerSystem", "FoucaultPendulum"]


class KeplerSystem(HamiltonianSystem):
    """Planar two-body (Kepler) problem in relative coordinates, with optional perturbations.

    ``H = |p|^2/(2 mu) - k/r + c_eps / r^(1+eps) + c_pn / r^3`` with the Plummer-softened
    ``r = sqrt(|q|^2 + softening^2)``.

    Parameters
    ----------
    q0, p0 : array-like, shape (2,)
        Initial relative position and (reduced-mass) momentum.
    k : float
        Coupling ``G M mu``.
    mu : float
        Reduced mass (``T = |p|^2 / (2 mu)``).
    eps, c_eps : float
        Exponent and coefficient of the extra ``c_eps / r^(1+eps)`` potential.
    c_pn : float
        Coefficient of the post-Newtonian-like ``c_pn / r^3`` term (perihelion precession).
    softening : float
        Plummer softening length (0: exact point masses).
    """

    kinetic_energy = _kinetic_energy
    potential_energy = _potential_energy

    separable = True

    def __init__(self, q0, p0, k=1.0, mu=1.0, eps=0.0, c_eps=0.0, c_pn=0.0, softening=0.0):
        self._adopt(build("kepler-state", q0=q0, p0=p0, k=k, mu=mu, eps=eps, c_eps=c_eps,
                          c_pn=c_pn, softening=softening))

    def _adopt(self, nat) -> None:
        v = adopt(self, nat)
        keep(self, **{n: v[n] for n in ("k", "mu", "eps", "c_eps", "c_pn", "softening")},
             mass_inv=1.0 / v["mu"])

    @classmethod
    def from_orbital_elements(cls, a: float, e: float, k: float = 1.0, mu: float = 1.0, **kwargs):
        """Start at perihelion of the unperturbed orbit with semi-major axis ``a`` and
        eccentricity ``e``; ``kwargs`` (``eps``, ``c_eps``, ``c_pn``, ``softening``) are passed
        to ``__init__``."""
        return from_native(cls, build("kepler", a=a, e=e, k=k, mu=mu, **kwargs))

    def angular_momentum(self, q=None, p=None) -> float:
        """Out-of-plane angular momentum ``L = x p_y - y p_x`` (default: current state)."""
        return self._native.angular_momentum(*self._qp(q, p))

    def lrl_vector(self, q=None, p=None) -> np.ndarray:
        """Laplace-Runge-Lenz vector ``A = p x L - mu k r_hat``, shape (2,); conserved for the
        pure 1/r potential, it rotates (precesses) under the perturbations."""
        return self._native.lrl_vector(*self._qp(q, p))


class ProjectileMotion(HamiltonianSystem):
    """Projectile under constant gravity, ``H = |p|^2/(2m) + m g y``, optionally with quadratic
    air drag ``F = -drag_coeff |v| v``.

    With drag the system is dissipative: only ``rk4``, ``implicit_midpoint`` and ``dop853``
    (adaptive) are offered
    (``verlet``/``yoshida4`` would drop the drag and raise ValueError).

    Parameters
    ----------
    q0, p0 : array-like, shape (2,)
        Initial position ``(x, y)`` and momentum ``(px, py)``.
    m, g : float
        Mass and gravitational acceleration.
    drag_coeff : float
        Quadratic drag coefficient (0: vacuum, exact parabola).
    """

    kinetic_energy = _kinetic_energy
    potential_energy = _potential_energy

    separable = True

    def __init__(self, q0, p0, m: float = 1.0, g: float = 9.81, drag_coeff: float = 0.0):
        self._adopt(build("projectile-state", q0=q0, p0=p0, m=m, g=g, drag_coeff=drag_coeff))

    def _adopt(self, nat) -> None:
        v = adopt(self, nat)
        keep(self, m=v["m"], g=v["g"], drag_coeff=v["drag_coeff"], mass_inv=1.0 / v["m"])

    @classmethod
    def from_launch(cls, speed: float, angle_deg: float, m: float = 1.0, g: float = 9.81,
                    drag_coeff: float = 0.0, height: float = 0.0):
        """Launch from ``(0, height)`` at ``speed`` and ``angle_deg`` above the horizontal."""
        return from_native(cls, build("projectile", speed=speed, angle_deg=angle_deg, m=m, g=g,
                                      drag_coeff=drag_coeff, height=height))

    @staticmethod
    def analytic_trajectory(speed: float, angle_deg: float, g: float, t, height: float = 0.0):
        """Exact vacuum trajectory ``(x(t), y(t))`` (Galileo's parabola) at times ``t``."""
        t_arr = as_array("t", t)
        x, y = native("projectile_analytic_trajectory")(
            as_scalar("speed", speed), as_scalar("angle_deg", angle_deg), as_scalar("g", g),
            as_vector("t", t_arr.ravel()), as_scalar("height", height),
        )
        return x.reshape(t_arr.shape), y.reshape(t_arr.shape)

    @staticmethod
    def range_and_max_height(speed: float, angle_deg: float, g: float, height: float = 0.0):
        """Closed-form vacuum ``(range, max_height)`` of a launch from ``(0, height)``."""
        return native("projectile_range_and_max_height")(
            as_scalar("speed", speed), as_scalar("angle_deg", angle_deg), as_scalar("g", g),
            as_scalar("height", height),
        )

    def integrate(self, t_span, dt: float, method: str = "yoshida4") -> SimulationResult:
        """Integrate with fixed step ``dt``; with ``drag_coeff > 0`` use ``"rk4"`` or
        ``"implicit_midpoint"``."""
        return super().integrate(t_span, dt, method)


#: Earth's sidereal rotation rate ``2 pi / 86164.0905 s`` in rad/s (the catalogue's default
#: ``omega_earth``, repeated here because a signature's default must be a literal value; the
#: catalogue test checks that the two agree).
_OMEGA_EARTH = 7.292115857915991e-05


class FoucaultPendulum(ODESystem):
    """A long pendulum swinging near the vertical, seen from the rotating Earth; state
    ``[x, y, vx, vy]`` (``x`` east, ``y`` north, the bob's horizontal displacement).

    Small swings at ``omega0 = sqrt(g / length)`` plus the Coriolis acceleration of the
    ground's rotation about the local vertical, ``omega_z = omega_earth sin(latitude)``::

        x'' = -omega0^2 x + 2 omega_z y'
        y'' = -omega0^2 y - 2 omega_z x'

    The Coriolis force does no work: the energy per unit mass ``|v|^2/2 + omega0^2 |q|^2/2``
    is conserved (``energy``), while the swing plane turns once in ``2 pi / omega_z``
    (``precession_period``). The default ``implicit_midpoint`` keeps that energy to rounding
    (a quadratic invariant of a linear equation).

    Parameters
    ----------
    q0, v0 : array-like, shape (2,)
        Initial horizontal displacement ``(x, y)`` (m) and velocity ``(vx, vy)`` (m/s).
    length, g : float
        Pendulum length and gravitational acceleration (``omega0 = sqrt(g / length)``).
    latitude_deg : float
        Latitude in degrees, in ``[-90, 90]`` (default: the Panthéon in Paris, where Foucault
        showed it in 1851).
    omega_earth : float
        Earth's rotation rate in rad/s (default: the sidereal rate ``2 pi / 86164.0905``).
    """

    #: Vertical component of the Earth's rotation rate at the latitude, ``Omega sin(phi)`` (rad/s).
    omega_z: float

    def __init__(self, q0, v0, length: float = 67.0, g: float = 9.81,
                 latitude_deg: float = 48.85, omega_earth: float = _OMEGA_EARTH):
        self._adopt(build("foucault-pendulum", q0=q0, v0=v0, length=length, g=g,
                          latitude_deg=latitude_deg, omega_earth=omega_earth))

    def _adopt(self, nat) -> None:
        v = adopt(self, nat)
        omega0 = float(np.sqrt(v["g"] / v["length"]))
        omega_z = v["omega_earth"] * float(np.sin(np.deg2rad(v["latitude_deg"])))
        keep(self, length=v["length"], g=v["g"], latitude_deg=v["latitude_deg"],
             omega_earth=v["omega_earth"], omega0=omega0, omega_z=omega_z)

    @classmethod
    def from_deflection(cls, amplitude: float, angle_deg: float = 0.0, length: float = 67.0,
                        g: float = 9.81, latitude_deg: float = 48.85,
                        omega_earth: float = _OMEGA_EARTH):
        """Released from rest at displacement ``amplitude`` (m) in the direction ``angle_deg``
        (degrees counterclockwise from east), as a real Foucault pendulum is started."""
        a = as_scalar("amplitude", amplitude)
        angle = np.deg2rad(as_scalar("angle_deg", angle_deg))
        return cls([a * np.cos(angle), a * np.sin(angle)], [0.0, 0.0], length=length, g=g,
                   latitude_deg=latitude_deg, omega_earth=omega_earth)

    @property
    def position(self) -> np.ndarray:
        """Current horizontal displacement ``(x, y)``, shape (2,)."""
        return self.state[:2]

    @property
    def velocity(self) -> np.ndarray:
        """Current horizontal velocity ``(vx, vy)``, shape (2,)."""
        return self.state[2:4]

    def energy(self, state=None) -> float:
        """Energy per unit mass ``|v|^2/2 + omega0^2 |q|^2/2`` of ``state`` (default: the
        current state); conserved."""
        return self._native.energy(self._state_arg(state))

    def precession_period(self) -> float:
        """Time for the swing plane to turn once, ``2 pi / |omega_z|`` (s): the sidereal day
        over ``|sin(latitude)|``, about 32 hours in Paris (infinite on the equator)."""
        return float(2.0 * np.pi / abs(self.omega_z)) if self.omega_z != 0.0 else float("inf")

    @staticmethod
    def analytic_solution(q0, v0, omega0: float, omega_z: float, t):
        """The exact ``(x(t), y(t))`` of the equations of motion from ``q0``, ``v0`` at
        ``t = 0``: with ``w = x + i y``, ``w = exp(-i omega_z t) u`` where ``u`` is a plain
        harmonic swing at ``sqrt(omega0^2 + omega_z^2)``. Arrays of ``t``'s shape."""
        t_arr = as_array("t", t)
        x, y = native("foucault_analytic_solution")(
            as_vector("q0", q0, 2), as_vector("v0", v0, 2), as_scalar("omega0", omega0),
            as_scalar("omega_z", omega_z), as_vector("t", t_arr.ravel()),
        )
        return x.reshape(t_arr.shape), y.reshape(t_arr.shape)

    @staticmethod
    def to_corotating_frame(x, y, t, omega_z: float):
        """``(x, y)`` turned by ``+omega_z t``: the frame turning with the swing plane, in
        which the pendulum swings in a fixed plane. Arrays of the inputs' broadcast shape."""
        x, y, t = as_array("x", x), as_array("y", y), as_array("t", t)
        angle = as_scalar("omega_z", omega_z) * t
        c, s = np.cos(angle), np.sin(angle)
        return c * x - s * y, s * x + c * y

    def integrate(self, t_span, dt: float, method: str = "implicit_midpoint") -> SimulationResult:
        """Integrate with fixed step ``dt`` (``"dop853"``: adaptive, ``dt`` the spacing of the
        samples)."""
        return super().integrate(t_span, dt, method)
