"""The chaos toolkit's results drawn: Lyapunov running estimates, SALI / GALI histories and
chaos maps.

The numbers are those of ``physicskit.classical.chaos``: the running estimates are the
spectrum's ``history``, the alignment indices the result's ``index``, the chaos threshold the
library's ``CHAOS_THRESHOLD`` and a map's values what ``chaos_map`` returned. What is done here
is display only: leaving out the points a log axis cannot show (``t = 0``, an index of exactly
zero) and putting a map's values on the user's grid.
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np

from ..chaos import _INDICATORS, CHAOS_THRESHOLD
from ._labels import Labels
from ._mpl import new_axes, pyplot


def _as_list(results: Any, attribute: str, what: str) -> list[Any]:
    """One result or a sequence of them (each with ``t`` and ``attribute``), as a list."""
    # A list has an ``index`` method: sequences first.
    out = list(results) if isinstance(results, (list, tuple)) else [results]
    if not out or not all(hasattr(r, "t") and hasattr(r, attribute) for r in out):
        raise ValueError(f"expected a {what} or a non-empty list of them, got "
                         f"{type(results).__name__}")
    return out


def _check_labels(labels: Sequence[str] | None, n: int) -> list[str] | None:
    if labels is None:
        return None
    labels = list(labels)
    if len(labels) != n:
        raise ValueError(f"labels has {len(labels)} entries for {n} results")
    return labels


def _rate_unit(lab: Labels) -> str:
    """The unit of an exponent: one over the system's time unit."""
    return "dimensionless" if lab.time_unit == "dimensionless" else f"1/{lab.time_unit}"


def _positive(values: np.ndarray) -> np.ndarray:
    """``values`` with what a log axis cannot show (``<= 0``) as NaN."""
    out = np.array(values, dtype=float)
    out[~(out > 0.0)] = np.nan
    return out


def _threshold_label() -> str:
    return f"chaos threshold ({CHAOS_THRESHOLD:g})"


def plot_lyapunov(spectra: Any, system: Any = None, *, labels: Sequence[str] | None = None,
                  yscale: str = "linear", ax: Any = None) -> list[Any]:
    """The running Lyapunov estimates ``lambda_i(t)`` against time on a log time axis, one line
    per exponent (``lyapunov_spectrum`` or ``max_lyapunov``): a chaotic orbit's settle on a
    positive value, a regular orbit's fall towards zero.

    Parameters
    ----------
    spectra : LyapunovSpectrum or sequence of them
        Several runs (a chaotic and a regular orbit, say) share the axes.
    system : optional
        The system (time unit of the axes, from the catalogue).
    labels : sequence of str, optional
        One per run, prefixed to its lines' legend entries.
    yscale : ``"linear"`` or ``"log"``
        ``"log"`` shows the decay of positive estimates (a regular orbit's ``lambda_1``);
        non-positive values are left out.
    ax : Axes, optional

    Returns
    -------
    list of Line2D
        One per exponent of each run, in the history's (Gram-Schmidt) order. A thin grey line
        at zero is drawn too on a linear axis (not returned).
    """
    runs = _as_list(spectra, "history", "LyapunovSpectrum")
    names = _check_labels(labels, len(runs))
    if yscale not in ("linear", "log"):
        raise ValueError(f"yscale must be 'linear' or 'log', got {yscale!r}")
    ax = new_axes(ax)
    lab = Labels(system)
    lines = []
    for k, run in enumerate(runs):
        t = np.asarray(run.t, dtype=float)
        hist = np.asarray(run.history, dtype=float).reshape(len(t), -1)
        shown = t > 0.0  # the log time axis starts after the first renormalization
        for j in range(hist.shape[1]):
            column = hist[shown, j]
            if yscale == "log":
                column = _positive(column)
            name = rf"$\lambda_{{{j + 1}}}$"
            if names is not None:
                name = f"{names[k]}: {name}"
            if len(column):
                name += f" = {hist[-1, j]:.3g}"
            (line,) = ax.plot(t[shown], column, lw=1.0, label=name)
            lines.append(line)
    ax.set_xscale("log")
    ax.set_yscale(yscale)
    if yscale == "linear":
        ax.axhline(0.0, color="0.6", lw=0.6, zorder=0)
    ax.set_xlabel(lab.t)
    ax.set_ylabel(rf"running estimate $\lambda_i(t)$ ({_rate_unit(lab)})")
    ax.legend(fontsize="small", ncol=2 if len(lines) > 4 else 1)
    return lines


def _index_symbol(name: str) -> str:
    """``"GALI_3"`` as mathtext (``GALI$_{3}$``); ``"SALI"`` unchanged."""
    head, _, k = name.partition("_")
    return f"{head}$_{{{k}}}$" if k else head


def plot_sali(indices: Any, system: Any = None, *, labels: Sequence[str] | None = None,
              threshold: bool = True, ax: Any = None) -> list[Any]:
    """SALI or GALI_k (``sali``, ``gali``) against time on log-log axes, one line per run,
    with the library's chaos threshold ``CHAOS_THRESHOLD`` dashed: a chaotic orbit's index
    falls exponentially through it, a regular orbit's stays near a positive value (SALI) or
    decays as a power law (GALI_k with ``k`` above the degrees of freedom).

    Parameters
    ----------
    indices : AlignmentIndex or sequence of them
    system : optional
        The system (time unit of the axis).
    labels : sequence of str, optional
        Legend labels, one per run; default: the index's name and verdict.
    threshold : bool
        Draw the threshold line.
    ax : Axes, optional

    Returns
    -------
    list of Line2D
        One per run, then the threshold line if drawn.
    """
    runs = _as_list(indices, "index", "AlignmentIndex")
    names = _check_labels(labels, len(runs))
    ax = new_axes(ax)
    lines = []
    for k, run in enumerate(runs):
        t = np.asarray(run.t, dtype=float)
        shown = t > 0.0  # at t = 0 the vectors are orthonormal, and a log axis has no 0
        index_name = getattr(run, "name", "SALI")
        label = (names[k] if names is not None
                 else f"{_index_symbol(index_name)} ({getattr(run, 'verdict', '')})")
        (line,) = ax.plot(t[shown], _positive(np.asarray(run.index)[shown]), lw=1.0,
                          label=label)
        lines.append(line)
    if threshold:
        lines.append(ax.axhline(CHAOS_THRESHOLD, color="k", ls="--", lw=0.8,
                                label=_threshold_label()))
    ax.set_xscale("log")
    ax.set_yscale("log")
    kinds = {getattr(r, "name", "SALI") for r in runs}
    ax.set_xlabel(Labels(system).t)
    ax.set_ylabel(_index_symbol(kinds.pop()) if len(kinds) == 1 else "alignment index")
    ax.legend(fontsize="small")
    return lines


def _grid_label(given: str | None, system: Any, component: int | None, axis: str) -> str:
    if given is not None:
        return given
    if system is not None and component is not None:
        state = np.asarray(getattr(system, "state", ()))
        return Labels(system, max(state.size // 2, 1)).state(component)
    return f"{axis} (grid units)"


def _components(components: Any, system: Any) -> tuple[int | None, int | None]:
    if components is None:
        return None, None
    def index(c: Any) -> bool:
        return isinstance(c, (int, np.integer)) and not isinstance(c, (bool, np.bool_))

    if index(components):
        pair = [components]
    else:
        pair = list(np.asarray(components, dtype=object).ravel())
    if not 1 <= len(pair) <= 2 or not all(index(c) for c in pair):
        raise ValueError(f"components must be one or two state indices, got {components!r}")
    if system is None:
        raise ValueError("components names state components: pass the system too")
    dim = np.asarray(system.state).size
    for c in pair:
        if not 0 <= c < dim:
            raise ValueError(f"component {c} is out of range for states of length {dim}")
    return int(pair[0]), (int(pair[1]) if len(pair) == 2 else None)


def _axis(name: str, values: Any) -> np.ndarray:
    a = np.asarray(values, dtype=float)
    if a.ndim != 1 or a.size == 0 or not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be a non-empty 1-D array of finite grid values")
    return a


def plot_chaos_map(values: Any, x: Any, y: Any = None, *, indicator: str = "lyapunov",
                   system: Any = None, components: Any = None, xlabel: str | None = None,
                   ylabel: str | None = None, log: bool | None = None, cmap: str | None = None,
                   ax: Any = None) -> Any:
    """A chaos map (``chaos_map``'s values) on the grid of initial conditions it was computed
    on: a colour mesh with a colour bar for a 2-D grid, a line for a 1-D one.

    Parameters
    ----------
    values : array
        ``chaos_map``'s output: shape ``(len(y) * len(x),)`` in the order of
        ``np.meshgrid(x, y)`` raveled (``x`` varying fastest), or ``(len(y), len(x))``; for a
        1-D grid (``y=None``) shape ``(len(x),)``. NaN marks points not computed (initial
        conditions outside the energy surface, say) and is left blank.
    x, y : 1-D arrays
        The grid values along each axis.
    indicator : ``"lyapunov"``, ``"sali"`` or ``"crossings"``
        What ``values`` are (``chaos_map``'s ``indicator``): names the colour bar (with the
        unit of an exponent, one over the system's time unit); for ``"sali"`` the library's
        ``CHAOS_THRESHOLD`` is marked on it.
    system, components : optional
        When the grid varies state components (``components=(i, j)``, ``i`` along ``x``), the
        axis labels are those components' symbols with their units.
    xlabel, ylabel : str, optional
        The axis labels, with units (what the grid values are, when they are parameters of a
        function passed to ``chaos_map``); they take precedence over ``components``.
    log : bool, optional
        Logarithmic colour scale (default: for ``"sali"`` only).
    cmap : str, optional
        Colour map (default ``"magma"``; for ``"sali"`` reversed, chaos bright).
    ax : Axes, optional

    Returns
    -------
    QuadMesh (2-D; its ``colorbar`` attribute is the colour bar) or Line2D (1-D).
    """
    from matplotlib.colors import LogNorm, Normalize

    if indicator not in _INDICATORS:
        raise ValueError(f"indicator must be one of {_INDICATORS}, got {indicator!r}")
    xs = _axis("x", x)
    ys = None if y is None else _axis("y", y)
    cx, cy = _components(components, system)
    vals = np.asarray(values, dtype=float)
    shape = (len(xs),) if ys is None else (len(ys), len(xs))
    if vals.size != int(np.prod(shape)) or vals.ndim not in (1, len(shape)):
        raise ValueError(f"values has shape {vals.shape}; the grid needs {shape} "
                         f"(or {int(np.prod(shape))} values in meshgrid order)")
    vals = vals.reshape(shape)
    lab = Labels(system)
    log = indicator == "sali" if log is None else bool(log)
    what = {
        "lyapunov": rf"largest exponent $\lambda_1$ ({_rate_unit(lab)})",
        "sali": "SALI",
        "crossings": "crossings of the section (count)",
    }[indicator]
    if log:
        vals = _positive(vals)
    ax = new_axes(ax)
    ax.set_xlabel(_grid_label(xlabel, system, cx, "x"))
    if ys is None:
        (line,) = ax.plot(xs, vals, "o-", ms=3, lw=1.0)
        ax.set_ylabel(what)
        if log:
            ax.set_yscale("log")
        if indicator == "sali":
            ax.axhline(CHAOS_THRESHOLD, color="k", ls="--", lw=0.8, label=_threshold_label())
            ax.legend(fontsize="small")
        return line
    ax.set_ylabel(_grid_label(ylabel, system, cy, "y"))
    finite = vals[np.isfinite(vals)]
    if finite.size == 0:
        raise ValueError("values has no finite entry to draw")
    lo, hi = float(finite.min()), float(finite.max())
    norm = LogNorm(vmin=lo, vmax=hi) if log else Normalize(vmin=lo, vmax=hi)
    default_cmap = "magma_r" if indicator == "sali" else "magma"
    mesh = ax.pcolormesh(xs, ys, np.ma.masked_invalid(vals), norm=norm, shading="nearest",
                         cmap=cmap or default_cmap)
    bar = pyplot().colorbar(mesh, ax=ax, label=what)
    if indicator == "sali" and lo <= CHAOS_THRESHOLD <= hi:
        bar.ax.axhline(CHAOS_THRESHOLD, color="w", ls="--", lw=1.0)
    return mesh
