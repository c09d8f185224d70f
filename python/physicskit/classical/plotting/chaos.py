"""The chaos toolkit's results drawn: Lyapunov running estimates, SALI / GALI histories and
chaos maps.

The numbers are those of ``physicskit.classical.chaos``: the running estimates are the
spectrum's ``history``, the alignment indices the result's ``index``, the chaos threshold the
library's ``CHAOS_THRESHOLD`` and a map's values what ``chaos_map`` returned. What is done here
is display only: leaving out the points a log axis cannot show (``t = 0``, an index of exactly
zero) and putting a map's values on the user's grid.

Every argument is checked before anything is drawn, by the package's converters
(``physicskit.classical._native``): a result's arrays, a map's values and grid, component
indices and flags that are not what the docstrings say are a ``ValueError`` naming the
argument, never a numpy or matplotlib error from inside the drawing.
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np

from .._native import as_array, as_flag, as_int, as_vector
from ..chaos import _INDICATORS, CHAOS_THRESHOLD
from ..core.base_system import DynamicalSystem
from ._data import given_labels
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


def _run_arrays(run: Any, name: str, attribute: str, columns: bool) -> tuple[np.ndarray,
                                                                              np.ndarray]:
    """``run.t`` and ``run.<attribute>`` (one row per time; a column per exponent when
    ``columns``) as float arrays; ValueError naming ``name`` (``spectra[1]``, say) unless they
    are finite real numbers of matching lengths."""
    t = as_vector(f"{name}.t", run.t)
    data = as_array(f"{name}.{attribute}", getattr(run, attribute))
    if columns and data.ndim == 1:
        data = data.reshape(-1, 1)
    expected = "(len(t), k)" if columns else "(len(t),)"
    if data.ndim != (2 if columns else 1) or data.shape[0] != t.size:
        raise ValueError(f"{name}.{attribute} has shape {data.shape} for {t.size} times; "
                         f"expected {expected}")
    if not np.all(np.isfinite(data)):
        raise ValueError(f"{name}.{attribute} contains NaN or infinity; a run of the library "
                         "never does: pass its result unchanged")
    return t, data


def _runs_arrays(runs: list[Any], what: str, attribute: str,
                 columns: bool) -> list[tuple[np.ndarray, np.ndarray]]:
    """``_run_arrays`` of each run (named ``what`` or ``what[k]``); ValueError unless at least
    one run has a sample after ``t = 0``, where the log time axis starts."""
    out = [_run_arrays(run, what if len(runs) == 1 else f"{what}[{k}]", attribute, columns)
           for k, run in enumerate(runs)]
    if not any(np.any(t > 0.0) for t, _ in out):
        raise ValueError(f"{what} has no sample after t = 0 to draw on the log time axis")
    return out


def _nothing_positive(columns: list[np.ndarray], what: str, why: str = "") -> None:
    """ValueError when none of ``columns`` (as ``_positive`` left them) has a point a log axis
    can show: the axes would be empty, and matplotlib would only warn."""
    if not any(np.any(np.isfinite(c)) for c in columns):
        raise ValueError(f"no {what} is positive after t = 0: nothing can be drawn on a log "
                         f"axis{why}")


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
        non-positive values are left out (none positive at all: ValueError).
    ax : Axes, optional

    Returns
    -------
    list of Line2D
        One per exponent of each run, in the history's (Gram-Schmidt) order. A thin grey line
        at zero is drawn too on a linear axis (not returned).
    """
    runs = _as_list(spectra, "history", "LyapunovSpectrum")
    names = given_labels(labels, len(runs))
    if not isinstance(yscale, str) or yscale not in ("linear", "log"):
        raise ValueError(f"yscale must be 'linear' or 'log', got {yscale!r}")
    data = _runs_arrays(runs, "spectra", "history", columns=True)
    # The log time axis starts after the first renormalization.
    shown = [(t[t > 0.0], hist[t > 0.0]) for t, hist in data]
    if yscale == "log":
        shown = [(t, _positive(hist)) for t, hist in shown]
        _nothing_positive([hist for _, hist in shown], "running estimate")
    ax = new_axes(ax)
    lab = Labels(system)
    lines = []
    for k, ((t, hist), (_, full)) in enumerate(zip(shown, data)):
        for j in range(hist.shape[1]):
            name = rf"$\lambda_{{{j + 1}}}$"
            if names is not None:
                name = f"{names[k]}: {name}"
            if len(t):
                name += f" = {full[-1, j]:.3g}"
            (line,) = ax.plot(t, hist[:, j], lw=1.0, label=name)
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

    An index of exactly 0 (the deviation vectors aligned to the last bit, as a strongly
    chaotic orbit's soon are) has no place on a log axis: those points are left out, a run
    with no other point after ``t = 0`` says so in its legend entry, and when no run has a
    positive index after ``t = 0`` (nothing could be drawn) it is a ValueError.
    """
    runs = _as_list(indices, "index", "AlignmentIndex")
    names = given_labels(labels, len(runs))
    threshold = as_flag("threshold", threshold)
    # At t = 0 the vectors are orthonormal, and a log axis has no 0.
    shown = [(t[t > 0.0], _positive(index[t > 0.0]))
             for t, index in _runs_arrays(runs, "indices", "index", columns=False)]
    _nothing_positive([index for _, index in shown], "index",
                      " (an index of exactly 0: the deviation vectors aligned to rounding, as a "
                      "chaotic orbit's soon are)")
    ax = new_axes(ax)
    lines = []
    for k, (run, (t, index)) in enumerate(zip(runs, shown)):
        index_name = str(getattr(run, "name", "SALI"))
        label = (names[k] if names is not None
                 else f"{_index_symbol(index_name)} ({getattr(run, 'verdict', '')})")
        if not np.any(np.isfinite(index)):
            label += " (0 after t = 0: not drawn)"
        (line,) = ax.plot(t, index, lw=1.0, label=label)
        lines.append(line)
    if threshold:
        lines.append(ax.axhline(CHAOS_THRESHOLD, color="k", ls="--", lw=0.8,
                                label=_threshold_label()))
    ax.set_xscale("log")
    ax.set_yscale("log")
    kinds = {str(getattr(r, "name", "SALI")) for r in runs}
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


def _components(components: Any, system: Any, grid_dims: int) -> tuple[int | None, int | None]:
    """The state indices ``components`` names (one per grid axis), checked against the
    system's state length."""
    if components is None:
        return None, None
    if isinstance(components, np.ndarray) and components.ndim == 0:
        components = components[()]
    pair = list(components) if isinstance(components, (list, tuple, np.ndarray)) else [components]
    if not 1 <= len(pair) <= grid_dims:
        axes = "one index (1-D grid)" if grid_dims == 1 else "one or two state indices"
        raise ValueError(f"components must be {axes}, got {components!r}")
    if system is None:
        raise ValueError("components names state components: pass the system too")
    if not isinstance(system, DynamicalSystem):
        raise ValueError(f"components names state components of a physicskit system, got "
                         f"system = {type(system).__name__}")
    last = np.asarray(system.state).size - 1
    cx, *rest = [as_int(f"components[{i}]", c, maximum=last) for i, c in enumerate(pair)]
    return cx, (rest[0] if rest else None)


def _grid_axis(name: str, values: Any) -> np.ndarray:
    """One axis of the grid: a non-empty, strictly monotonic vector of finite values."""
    a = as_vector(name, values)
    if a.size == 0:
        raise ValueError(f"{name} is empty; pass the grid values along that axis")
    steps = np.diff(a)
    if not (np.all(steps > 0.0) or np.all(steps < 0.0)):
        raise ValueError(f"{name} must be strictly increasing or decreasing: the values of the "
                         "grid along that axis")
    return a


def _grid_values(values: Any, shape: tuple[int, ...]) -> np.ndarray:
    """``values`` as an array of the grid's ``shape`` (``(len(y), len(x))``: one row per
    ``y``), from that shape or raveled in meshgrid order; never silently re-ordered."""
    vals = as_array("values", values)
    size = int(np.prod(shape))
    if vals.shape != shape and not (vals.ndim == 1 and vals.size == size):
        if len(shape) == 1:
            need = f"({size},) for the {size} grid points"
        else:
            need = (f"(len(y), len(x)) = {shape}, one row per y value, or ({size},) in the "
                    "order of np.meshgrid(x, y) raveled")
        hint = " (transposed? pass values.T)" if vals.shape == shape[::-1] else ""
        raise ValueError(f"values has shape {vals.shape}; the grid needs {need}{hint}")
    if np.any(np.isinf(vals)):
        raise ValueError("values contains infinity; NaN marks a point not computed, every "
                         "other value must be finite")
    return vals.reshape(shape)


def _text(name: str, value: Any) -> str | None:
    """An optional string argument (a label, a colour map's name)."""
    if value is not None and not isinstance(value, str):
        raise ValueError(f"{name} must be a string, got {value!r}")
    return value


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
        ``np.meshgrid(x, y)`` raveled (``x`` varying fastest), or ``(len(y), len(x))`` (one
        row per ``y`` value, as ``np.meshgrid(x, y)`` lays them out); for a 1-D grid
        (``y=None``) shape ``(len(x),)``. Any other shape is a ValueError, a transposed
        ``(len(x), len(y))`` too (when ``len(x) != len(y)``: a square grid's orientation
        cannot be told from its shape). NaN marks points not computed (initial conditions
        outside the energy surface, say) and is left blank; infinity is refused.
    x, y : 1-D arrays
        The grid values along each axis: finite, strictly increasing or decreasing.
    indicator : ``"lyapunov"``, ``"sali"`` or ``"crossings"``
        What ``values`` are (``chaos_map``'s ``indicator``): names the colour bar (with the
        unit of an exponent, one over the system's time unit); for ``"sali"`` the library's
        ``CHAOS_THRESHOLD`` is marked on it.
    system, components : optional
        When the grid varies state components (``components=(i, j)``, ``i`` along ``x``; one
        index for a 1-D grid), the axis labels are those components' symbols with their
        units.
    xlabel, ylabel : str, optional
        The axis labels, with units (what the grid values are, when they are parameters of a
        function passed to ``chaos_map``); they take precedence over ``components``.
    log : bool, optional
        Logarithmic colour scale (default: for ``"sali"`` only); values ``<= 0`` are left
        blank, and a map with no positive value is a ValueError.
    cmap : str, optional
        Colour map (default ``"magma"``; for ``"sali"`` reversed, chaos bright).
    ax : Axes, optional

    Returns
    -------
    QuadMesh (2-D; its ``colorbar`` attribute is the colour bar) or Line2D (1-D).
    """
    import matplotlib
    from matplotlib.colors import LogNorm, Normalize

    if not isinstance(indicator, str) or indicator not in _INDICATORS:
        raise ValueError(f"indicator must be one of {_INDICATORS}, got {indicator!r}")
    xs = _grid_axis("x", x)
    ys = None if y is None else _grid_axis("y", y)
    cx, cy = _components(components, system, 1 if ys is None else 2)
    vals = _grid_values(values, (len(xs),) if ys is None else (len(ys), len(xs)))
    xlabel, ylabel = _text("xlabel", xlabel), _text("ylabel", ylabel)
    if _text("cmap", cmap) is not None and cmap not in matplotlib.colormaps:
        raise ValueError(f"cmap must name a matplotlib colour map, got {cmap!r}")
    lab = Labels(system)
    log = indicator == "sali" if log is None else as_flag("log", log)
    what = {
        "lyapunov": rf"largest exponent $\lambda_1$ ({_rate_unit(lab)})",
        "sali": "SALI",
        "crossings": "crossings of the section (count)",
    }[indicator]
    if log:
        vals = _positive(vals)
    finite = vals[np.isfinite(vals)]
    if finite.size == 0:
        raise ValueError("values has no positive entry to draw on a log scale" if log else
                         "values has no finite entry to draw (NaN marks points not computed)")
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
    lo, hi = float(finite.min()), float(finite.max())
    norm = LogNorm(vmin=lo, vmax=hi) if log else Normalize(vmin=lo, vmax=hi)
    default_cmap = "magma_r" if indicator == "sali" else "magma"
    mesh = ax.pcolormesh(xs, ys, np.ma.masked_invalid(vals), norm=norm, shading="nearest",
                         cmap=cmap or default_cmap)
    bar = pyplot().colorbar(mesh, ax=ax, label=what)
    if indicator == "sali" and lo <= CHAOS_THRESHOLD <= hi:
        bar.ax.axhline(CHAOS_THRESHOLD, color="w", ls="--", lw=1.0)
    return mesh
