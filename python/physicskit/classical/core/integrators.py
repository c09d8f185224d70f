"""The functional integrator API of the physicskit 0.4.0 peer, on plain callables.

``rk4_integrate(deriv_func, y0, t0, n_steps, dt)`` and its companions take any Python
callable (a plain function, a bound method, a Numba ``@njit`` dispatcher) and run it on the
same Rust integrators as every system: the callable is wrapped in a minimal
:class:`~physicskit.classical.core.base_system.ODESystem`-like object (``derivatives``) or
:class:`~physicskit.classical.core.base_system.HamiltonianSystem`-like object (``force``) and
handed to the native drivers, which call it back once per evaluation. For the same callable,
step and span the trajectory is bit for bit that of ``integrate`` on a Python subclass whose
``derivatives`` (or ``force``) is that callable.

Signatures, return shapes and tuple orders are the peer's:

======================================  =========================================
``rk4_step(deriv_func, t, y, dt)``       ``y`` at ``t + dt``
``rk4_integrate(...)``                   ``(t, y)``, shapes ``(n+1,)``, ``(n+1, dim)``
``velocity_verlet_step(...)``            ``(q, p)`` at ``t + dt``
``velocity_verlet_integrate(...)``       ``(t, q, p)``
``yoshida4_step`` / ``_integrate``       as velocity Verlet
``implicit_midpoint_step`` / ``_integrate``  as RK4
``make_separable_derivatives``           ``(t, y) -> dy/dt`` of ``y = [q, p]``
======================================  =========================================

``force_func(q, t)`` returns ``-dV/dq``; ``mass_inv`` (a float or one value per coordinate)
gives ``dq/dt = mass_inv * p``. Velocity Verlet is the ``verlet`` method (kick-drift-kick).
"""

from __future__ import annotations

from typing import Any, Callable

import numpy as np

from .._native import _core, as_int, as_scalar, as_vector

__all__ = [
    "rk4_step",
    "rk4_integrate",
    "velocity_verlet_step",
    "velocity_verlet_integrate",
    "yoshida4_step",
    "yoshida4_integrate",
    "implicit_midpoint_step",
    "implicit_midpoint_integrate",
    "make_separable_derivatives",
]

#: What the native drivers are asked to store: every sample, no energy (a bare right-hand
#: side has none).
_EVERY: dict[str, Any] = dict(stride=1, final_only=False, energy=False, progress=None, rtol=None, atol=None,
              max_steps=None)
_LAST: dict[str, Any] = dict(_EVERY, final_only=True)


class _Field:
    """``dy/dt = deriv_func(t, y)`` as the object the native ODE driver calls back."""

    __slots__ = ("derivatives",)

    def __init__(self, deriv_func: Callable[[float, np.ndarray], Any]):
        if not callable(deriv_func):
            raise TypeError(f"deriv_func must be callable, got {type(deriv_func).__name__}")
        self.derivatives = deriv_func

    def energy(self, state: np.ndarray) -> float:  # pragma: no cover - energy is off
        return float("nan")


class _Separable:
    """``H = T(p) + V(q)`` known only by its force: what the native Hamiltonian driver calls
    back (``force(q, t)``)."""

    __slots__ = ("force",)

    def __init__(self, force_func: Callable[[np.ndarray, float], Any]):
        if not callable(force_func):
            raise TypeError(f"force_func must be callable, got {type(force_func).__name__}")
        self.force = force_func

    def kinetic_energy(self, p: np.ndarray) -> float:  # pragma: no cover - energy is off
        return float("nan")

    def potential_energy(self, q: np.ndarray) -> float:  # pragma: no cover - energy is off
        return float("nan")


def _mass_inv(mass_inv: Any, ndof: int) -> np.ndarray:
    """``mass_inv`` (a number or one per coordinate) as a float64 vector of length ``ndof``."""
    arr = np.asarray(mass_inv)
    if arr.ndim == 0:
        return np.full(ndof, as_scalar("mass_inv", mass_inv))
    return as_vector("mass_inv", mass_inv, ndof)


def _span(t0: Any, n_steps: Any, dt: Any) -> tuple[float, int, float, tuple[float, float]]:
    t0 = as_scalar("t0", t0)
    n_steps = as_int("n_steps", n_steps, minimum=0)
    dt = as_scalar("dt", dt)
    return t0, n_steps, dt, (t0, t0 + n_steps * dt)


def _checked_steps(t: np.ndarray, n_steps: int, dt: float) -> None:
    # The native grid has round((t1 - t0) / dt) steps; t1 = t0 + n_steps dt gives n_steps
    # unless t0 is so large against dt that t0 + n dt is not representable near enough.
    if len(t) != n_steps + 1:
        raise ValueError(
            f"t0 + n_steps * dt rounds to {len(t) - 1} steps of dt = {dt!r}, not {n_steps}: "
            "t0 is too large against dt to represent the grid"
        )


def _ode_run(deriv_func, y0, t0, n_steps, dt, method: str):
    field = _Field(deriv_func)
    y0 = as_vector("y0", y0)
    t0, n_steps, dt, span = _span(t0, n_steps, dt)
    if n_steps == 0:
        return np.array([t0]), y0.reshape(1, -1)
    t, y, _ndof, _e, _m, _x = _core.integrate_ode(field, y0, t0, span, dt, method, **_EVERY)
    _checked_steps(t, n_steps, dt)
    return t, y


def _ode_step(deriv_func, t, y, dt, method: str) -> np.ndarray:
    field = _Field(deriv_func)
    y = as_vector("y", y)
    t, dt = as_scalar("t", t), as_scalar("dt", dt)
    _t, ys, _ndof, _e, _m, _x = _core.integrate_ode(field, y, t, (t, t + dt), dt, method,
                                                     **_LAST)
    return ys[-1].copy()


def _separable_run(force_func, mass_inv, q0, p0, t0, n_steps, dt, method: str):
    system = _Separable(force_func)
    q0 = as_vector("q0", q0)
    ndof = len(q0)
    p0 = as_vector("p0", p0, ndof)
    minv = _mass_inv(mass_inv, ndof)
    t0, n_steps, dt, span = _span(t0, n_steps, dt)
    if n_steps == 0:
        return np.array([t0]), q0.reshape(1, -1), p0.reshape(1, -1)
    state = np.concatenate([q0, p0])
    t, y, _ndof, _e, _m, _x = _core.integrate_hamiltonian(
        system, state, t0, span, dt, method, ndof, True, minv, **_EVERY
    )
    _checked_steps(t, n_steps, dt)
    return t, np.ascontiguousarray(y[:, :ndof]), np.ascontiguousarray(y[:, ndof:])


def _separable_step(force_func, mass_inv, q, p, dt, t, method: str):
    system = _Separable(force_func)
    q = as_vector("q", q)
    ndof = len(q)
    p = as_vector("p", p, ndof)
    minv = _mass_inv(mass_inv, ndof)
    t, dt = as_scalar("t", t), as_scalar("dt", dt)
    _t, y, _ndof, _e, _m, _x = _core.integrate_hamiltonian(
        system, np.concatenate([q, p]), t, (t, t + dt), dt, method, ndof, True, minv, **_LAST
    )
    return y[-1, :ndof].copy(), y[-1, ndof:].copy()


def _solver_settings(tol: Any, max_iter: Any) -> None:
    """Checks the peer's solver arguments. The native implicit solve iterates to the rounding
    floor of the state (so it meets any ``tol`` a float64 run can), with its own iteration
    budget and a Newton fallback; it raises ``ConvergenceError`` where it does not converge."""
    tol = as_scalar("tol", tol)
    if not tol > 0.0:
        raise ValueError(f"tol must be > 0, got {tol!r}")
    as_int("max_iter", max_iter, minimum=1)


def rk4_step(deriv_func, t, y, dt):
    """One classical Runge–Kutta step of ``dy/dt = deriv_func(t, y)`` from ``(t, y)``; the
    state at ``t + dt``, shape of ``y``."""
    return _ode_step(deriv_func, t, y, dt, "rk4")


def rk4_integrate(deriv_func, y0, t0, n_steps, dt):
    """``n_steps`` RK4 steps of ``dt`` from ``y0`` at ``t0``; ``(t, y)`` of shapes
    ``(n_steps + 1,)`` and ``(n_steps + 1, len(y0))``."""
    return _ode_run(deriv_func, y0, t0, n_steps, dt, "rk4")


def velocity_verlet_step(force_func, mass_inv, q, p, dt, t=0.0):
    """One velocity-Verlet (kick-drift-kick) step of ``dq/dt = mass_inv p``,
    ``dp/dt = force_func(q, t)``; ``(q, p)`` at ``t + dt``."""
    return _separable_step(force_func, mass_inv, q, p, dt, t, "verlet")


def velocity_verlet_integrate(force_func, mass_inv, q0, p0, t0, n_steps, dt):
    """``n_steps`` velocity-Verlet steps; ``(t, q, p)`` of shapes ``(n_steps + 1,)``,
    ``(n_steps + 1, len(q0))`` and ``(n_steps + 1, len(q0))``."""
    return _separable_run(force_func, mass_inv, q0, p0, t0, n_steps, dt, "verlet")


def yoshida4_step(force_func, mass_inv, q, p, dt, t=0.0):
    """One fourth-order Yoshida step (three Verlet sub-steps); ``(q, p)`` at ``t + dt``."""
    return _separable_step(force_func, mass_inv, q, p, dt, t, "yoshida4")


def yoshida4_integrate(force_func, mass_inv, q0, p0, t0, n_steps, dt):
    """``n_steps`` fourth-order Yoshida steps; ``(t, q, p)`` as
    :func:`velocity_verlet_integrate`."""
    return _separable_run(force_func, mass_inv, q0, p0, t0, n_steps, dt, "yoshida4")


def implicit_midpoint_step(deriv_func, t, y, dt, tol=1e-12, max_iter=100):
    """One implicit-midpoint step ``y1 = y + dt f(t + dt/2, (y + y1)/2)``; the state at
    ``t + dt``. ``tol`` (> 0) and ``max_iter`` (>= 1) are checked; the native solve iterates
    to the rounding floor, which meets ``tol``, and raises ``ConvergenceError`` where it does
    not converge."""
    _solver_settings(tol, max_iter)
    return _ode_step(deriv_func, t, y, dt, "implicit_midpoint")


def implicit_midpoint_integrate(deriv_func, y0, t0, n_steps, dt, tol=1e-12, max_iter=100):
    """``n_steps`` implicit-midpoint steps; ``(t, y)`` as :func:`rk4_integrate` (``tol`` and
    ``max_iter`` as in :func:`implicit_midpoint_step`)."""
    _solver_settings(tol, max_iter)
    return _ode_run(deriv_func, y0, t0, n_steps, dt, "implicit_midpoint")


def make_separable_derivatives(force_func, mass_inv, ndof: int):
    """``deriv_func(t, y)`` of the stacked state ``y = [q, p]`` (``len(y) == 2 ndof``):
    ``(mass_inv * p, force_func(q, t))``, for :func:`rk4_integrate` and
    :func:`implicit_midpoint_integrate`. A plain Python function (the peer returns a Numba
    dispatcher; both are called the same way)."""
    if not callable(force_func):
        raise TypeError(f"force_func must be callable, got {type(force_func).__name__}")
    ndof = as_int("ndof", ndof, minimum=1)
    minv = _mass_inv(mass_inv, ndof)

    def deriv_func(t, y):
        y = np.asarray(y, dtype=np.float64)
        out = np.empty(2 * ndof)
        out[:ndof] = minv * y[ndof:]
        out[ndof:] = force_func(y[:ndof], t)
        return out

    return deriv_func
