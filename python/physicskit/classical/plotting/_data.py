"""Reading results: the few checks every plotting function makes on its inputs."""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np

from .._native import as_int


def as_results(results: Any) -> list[Any]:
    """One result or a sequence of them, as a list (ValueError if empty)."""
    if hasattr(results, "t") and hasattr(results, "y"):
        return [results]
    out = list(results)
    if not out:
        raise ValueError("results is empty; pass a SimulationResult or a list of them")
    for r in out:
        if not (hasattr(r, "t") and hasattr(r, "y")):
            raise ValueError(f"expected SimulationResult objects, got {type(r).__name__}")
    return out


def has_qp(result: Any) -> bool:
    """Whether ``result`` has ``q`` and ``p`` (Hamiltonian and Lagrangian runs)."""
    return getattr(result, "q", None) is not None


def relative_energy_error(result: Any) -> tuple[np.ndarray, bool]:
    """``|E - E0| / |E0|`` of the run's stored energies (``|E - E0|`` when ``E0 = 0``, flagged
    by the second value being False); exact zeros become NaN so a log axis leaves them out.

    The energies are the library's (``result.energy``, computed by the integrator's system);
    this is only their display form.
    """
    energy = getattr(result, "energy", None)
    if energy is None:
        raise ValueError(
            "this result has no energy (integrate_sampled(..., energy=False)); rerun with "
            "energy=True to plot the energy error"
        )
    e = np.asarray(energy, dtype=float)
    e0 = e[0]
    relative = e0 != 0.0
    err = np.abs(e - e0) / (abs(e0) if relative else 1.0)
    err[err == 0.0] = np.nan
    return err, relative


#: More frames than any animation should hold (a 10^5-frame GIF is gigabytes).
_MAX_FRAMES = 100_000


def frame_indices(n_samples: int, stride: int, frames: int | None) -> np.ndarray:
    """Sample indices of an animation: every ``stride``-th sample, or ``frames`` evenly spaced
    ones."""
    if frames is not None:
        count = as_int("frames", frames, minimum=1, maximum=_MAX_FRAMES)
        return np.unique(np.linspace(0, n_samples - 1, count).round().astype(int))
    return np.arange(0, n_samples, as_int("stride", stride, minimum=1))


def given_labels(labels: Sequence[str] | None, n: int) -> list[str] | None:
    """The legend labels given for ``n`` runs, as a list (None when none were given).

    ValueError unless ``labels`` is a sequence of exactly ``n`` strings: a single string is
    refused rather than split into characters.
    """
    if labels is None:
        return None
    if isinstance(labels, (str, bytes)) or not hasattr(labels, "__iter__"):
        raise ValueError(f"labels must be a sequence of strings, one per run, got {labels!r}")
    out = list(labels)
    if len(out) != n:
        raise ValueError(f"labels has {len(out)} entries for {n} results")
    for i, label in enumerate(out):
        if not isinstance(label, str):
            raise ValueError(f"labels[{i}] must be a string, got {label!r}")
    return out


def labels_for(results: Sequence[Any], labels: Sequence[str] | None) -> list[str]:
    """Legend labels: the given ones (see ``given_labels``), else each run's method in words
    (``"implicit midpoint"``)."""
    from ._labels import method_words

    given = given_labels(labels, len(results))
    if given is None:
        return [method_words(getattr(r, "method", "")) or f"run {i}"
                for i, r in enumerate(results)]
    return given
