"""Newtonian systems: the planar Kepler problem and projectile motion."""

from __future__ import annotations

import numpy as np

from .._native import as_array, as_scalar, as_vector, native
from ..core.base_system import HamiltonianSystem, SimulationResult
from ._native_base import adopt, build, from_native
from ._native_base import kinetic_energy as _kinetic_energy, potential_energy as _potential_energy

__all__ = ["ProjectileMotion", "KeplerSystem"]


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
        self.k, self.mu = v["k"], v["mu"]
        self.eps, self.c_eps, self.c_pn = v["eps"], v["c_eps"], v["c_pn"]
        self.softening = v["softening"]
        self.mass_inv = 1.0 / self.mu

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
        self.m, self.g, self.drag_coeff = v["m"], v["g"], v["drag_coeff"]
        self.mass_inv = 1.0 / self.m

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
