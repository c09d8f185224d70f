"""Drifts of conserved quantities along a stored trajectory (the physicskit 0.4.0 peer's
``utils.conservation``): energy, planar angular momentum and the Laplace–Runge–Lenz vector.

Each takes the arrays of a :class:`~physicskit.classical.core.base_system.SimulationResult`
(``result.energy``, ``result.q``, ``result.p``) and returns one value per sample.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "energy_drift",
    "relative_energy_drift",
    "angular_momentum_2d",
    "angular_momentum_drift",
    "lrl_drift",
]


def _series(name: str, value) -> np.ndarray:
    arr = np.asarray(value, dtype=np.float64)
    if arr.ndim != 1 or len(arr) == 0:
        raise ValueError(f"{name} must be a non-empty 1-D array, got shape {arr.shape}")
    return arr


def _planar(q, p) -> tuple[np.ndarray, np.ndarray]:
    q = np.asarray(q, dtype=np.float64)
    p = np.asarray(p, dtype=np.float64)
    if q.ndim != 2 or q.shape[1] != 2 or q.shape != p.shape or len(q) == 0:
        raise ValueError(
            f"q and p must both have shape (n_samples, 2), n_samples >= 1; got {q.shape} and "
            f"{p.shape}"
        )
    return q, p


def energy_drift(energy: np.ndarray) -> np.ndarray:
    """``|E(t) - E(0)|`` at each sample of ``energy`` (shape ``(n_samples,)``)."""
    e = _series("energy", energy)
    return np.abs(e - e[0])


def relative_energy_drift(energy: np.ndarray) -> np.ndarray:
    """``|E(t) - E(0)| / |E(0)|`` at each sample; ``inf`` everywhere if ``E(0) == 0`` (no
    scale to measure against)."""
    e = _series("energy", energy)
    if e[0] == 0.0:
        return np.full(len(e), np.inf)
    return np.abs(e - e[0]) / abs(e[0])


def angular_momentum_2d(q: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Out-of-plane angular momentum ``L = x p_y - y p_x`` at each sample of a planar
    trajectory (``q``, ``p`` of shape ``(n_samples, 2)``)."""
    q, p = _planar(q, p)
    return q[:, 0] * p[:, 1] - q[:, 1] * p[:, 0]


def angular_momentum_drift(q: np.ndarray, p: np.ndarray) -> np.ndarray:
    """``|L(t) - L(0)|`` of :func:`angular_momentum_2d` at each sample."""
    ell = angular_momentum_2d(q, p)
    return np.abs(ell - ell[0])


def lrl_drift(system, q: np.ndarray, p: np.ndarray) -> np.ndarray:
    """``||A(t)| - |A(0)||``: the change of the magnitude of the Laplace–Runge–Lenz vector
    ``system.lrl_vector(q, p)`` (e.g. a :class:`KeplerSystem`'s) at each sample. Conserved by
    the pure ``1/r`` potential; under a perturbation the vector turns (apsidal precession)
    while its magnitude stays nearly constant."""
    lrl = getattr(system, "lrl_vector", None)
    if not callable(lrl):
        raise TypeError(f"{type(system).__name__} has no lrl_vector(q, p)")
    q, p = _planar(q, p)
    mags = np.array([np.linalg.norm(lrl(qi, pi)) for qi, pi in zip(q, p)])
    return np.abs(mags - mags[0])
