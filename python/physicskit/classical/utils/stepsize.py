"""The largest step that keeps a run's energy drift below a tolerance (the physicskit 0.4.0
peer's ``utils.stepsize``), searched with the native integrators.

:func:`estimate_dt` brackets and bisects ``dt`` on short probe runs, then verifies the
candidate on a run of the full length it is meant for, shrinking it until that run also
meets the tolerance: on a chaotic or slowly drifting system a step that holds for a few
periods need not hold for many. Every trial is a fresh system from ``system_factory`` run by
its own ``integrate``, so each costs what a run of that length costs natively.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from ..._core import ConvergenceError
from .._native import as_int, as_scalar

__all__ = ["StepSizeEstimate", "estimate_dt"]


@dataclass
class StepSizeEstimate:
    """What :func:`estimate_dt` found."""

    dt: float
    """The recommended step, verified over ``verified_at_steps`` steps."""
    achieved_drift: float
    """``max |E(t) - E(0)| / |E(0)|`` of the verification run at ``dt``."""
    verified_at_steps: int
    """Steps of the verification run (``target_steps``)."""
    n_evaluations: int
    """Trial runs made by the search, verification included."""


def _positive(name: str, value) -> float:
    x = as_scalar(name, value)
    if not x > 0.0:
        raise ValueError(f"{name} must be > 0, got {value!r}")
    return x


def estimate_dt(system_factory: Callable[[], object], method: str, tol: float = 1e-06,
                target_steps: int = 100000, probe_steps: int = 2000, dt_initial: float = 0.01,
                growth: float = 2.0, rel_precision: float = 0.05,
                max_iter: int = 40) -> StepSizeEstimate:
    """The largest ``dt`` (to ``rel_precision``) whose ``target_steps`` steps of ``method``
    keep the relative energy drift ``max |E(t) - E(0)| / |E(0)|`` at or below ``tol``.

    Parameters
    ----------
    system_factory : callable
        ``() -> system``: a fresh system in its initial state at each call (``integrate``
        moves a system on).
    method : str
        The integrator, as for ``system.integrate``.
    tol : float
        Largest relative energy drift accepted (> 0).
    target_steps : int
        Steps of the run the step is meant for; the answer is verified over that many.
    probe_steps : int
        Steps of each bracketing and bisection trial (a few periods at least).
    dt_initial : float
        First trial step (> 0).
    growth : float
        Factor (> 1) by which the bracketing grows or shrinks ``dt``, and the verification
        shrinks it.
    rel_precision : float
        Bisection stops once ``(dt_fail - dt_pass) / dt_pass`` is below this (> 0).
    max_iter : int
        Most trials in each of the three stages (bracket, bisect, verify).

    Returns
    -------
    StepSizeEstimate

    Raises
    ------
    ValueError
        A bad argument, a system whose initial energy is zero (no relative drift), or no step
        found within ``max_iter`` trials of a stage.
    """
    if not callable(system_factory):
        raise TypeError("system_factory must be a callable returning a fresh system")
    tol = _positive("tol", tol)
    target_steps = as_int("target_steps", target_steps, minimum=1)
    probe_steps = as_int("probe_steps", probe_steps, minimum=1)
    dt = _positive("dt_initial", dt_initial)
    growth = as_scalar("growth", growth)
    if not growth > 1.0:
        raise ValueError(f"growth must be > 1, got {growth!r}")
    rel_precision = _positive("rel_precision", rel_precision)
    max_iter = as_int("max_iter", max_iter, minimum=1)
    evaluations = 0

    def drift(step: float, n: int) -> float:
        nonlocal evaluations
        evaluations += 1
        system: Any = system_factory()
        t0 = float(getattr(system, "t", 0.0))
        try:
            result = system.integrate_sampled((t0, t0 + n * step), step, method)
        except ConvergenceError:
            return np.inf  # an implicit solve that fails at this step: too large
        energy = result.energy
        if energy is None:
            raise ValueError(f"{type(system).__name__} records no energy to measure drift by")
        if energy[0] == 0.0:
            raise ValueError(
                f"{type(system).__name__} starts at energy 0: its relative drift is undefined"
            )
        worst = float(np.max(np.abs(energy - energy[0])) / abs(energy[0]))
        return worst if np.isfinite(worst) else np.inf

    # Bracket [good, bad] on probe runs.
    good = bad = None
    if drift(dt, probe_steps) <= tol:
        good = dt
        for _ in range(max_iter):
            dt *= growth
            if drift(dt, probe_steps) > tol:
                bad = dt
                break
            good = dt
        else:
            raise ValueError(f"every probe step up to dt = {dt!r} met tol; raise dt_initial")
    else:
        bad = dt
        for _ in range(max_iter):
            dt /= growth
            if drift(dt, probe_steps) <= tol:
                good = dt
                break
            bad = dt
        else:
            raise ValueError(f"no probe step down to dt = {dt!r} met tol = {tol!r}")
    # Bisect on probe runs.
    for _ in range(max_iter):
        if (bad - good) / good < rel_precision:
            break
        mid = 0.5 * (good + bad)
        if drift(mid, probe_steps) <= tol:
            good = mid
        else:
            bad = mid
    # Verify over the full length, shrinking until it holds.
    dt = good
    for _ in range(max_iter):
        achieved = drift(dt, target_steps)
        if achieved <= tol:
            return StepSizeEstimate(float(dt), float(achieved), target_steps, evaluations)
        dt /= growth
    raise ValueError(
        f"no step down to dt = {dt * growth!r} met tol = {tol!r} over {target_steps} steps"
    )
