"""How results and systems show themselves: short text reprs and a notebook HTML card.

``repr(result)`` is one line (method, steps, span, shapes, the largest relative energy error);
``result._repr_html_()`` (what Jupyter shows) is a small table of the same facts plus an inline
SVG sparkline of the relative energy error ``|E(t) - E(t0)| / |E(t0)|`` over the run. Systems
show their class name and parameters. Nothing here imports anything beyond numpy and the
standard library, and nothing here raises: a repr that fails hides the object it describes.
"""

from __future__ import annotations

import html
from typing import Any, Iterable, Optional

import numpy as np

__all__ = [
    "energy_error", "format_value", "format_call", "result_repr", "result_html",
    "sparkline_svg",
]

#: Entries of a vector shown in full; longer vectors show their ends and their length.
_VECTOR_ITEMS = 6
#: Points of the sparkline: enough for the eye, small enough for a notebook (about 4 kB).
_SPARK_POINTS = 120
_SPARK_WIDTH, _SPARK_HEIGHT = 240, 40


def energy_error(energy: Optional[np.ndarray]) -> tuple[Optional[np.ndarray], str]:
    """The energy error of each sample against the first, and what kind it is.

    ``|E - E0| / |E0|`` (``"relative"``) when ``E0 != 0``, else ``|E - E0|``
    (``"absolute"``); ``(None, "")`` when no energy was stored or there are no samples.
    """
    if energy is None:
        return None, ""
    e = np.asarray(energy, dtype=np.float64).ravel()
    if e.size == 0:
        return None, ""
    e0 = e[0]
    if e0 != 0.0 and np.isfinite(e0):
        return np.abs(e - e0) / abs(e0), "relative"
    return np.abs(e - e0), "absolute"


def _max_error(err: np.ndarray) -> float:
    """The largest entry, NaN if any entry is NaN (a blown-up run must not look perfect)."""
    return float(np.max(err)) if err.size else 0.0


def _number(x: Any) -> str:
    if isinstance(x, (bool, np.bool_)):
        return repr(bool(x))
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    if isinstance(x, (float, np.floating)):
        return repr(float(x))
    return repr(x)


def format_value(value: Any) -> str:
    """A parameter value for a repr: numbers as Python writes them, vectors as lists (the ends
    and the length of long ones)."""
    if isinstance(value, (list, tuple, np.ndarray)):
        try:
            items = np.asarray(value).ravel().tolist()
        except (TypeError, ValueError):
            return repr(value)
        if len(items) <= _VECTOR_ITEMS:
            return "[" + ", ".join(_number(v) for v in items) + "]"
        half = _VECTOR_ITEMS // 2
        ends = [_number(v) for v in items[:half]] + ["..."]
        ends += [_number(v) for v in items[-half:]]
        return "[" + ", ".join(ends) + f"] ({len(items)} values)"
    return _number(value)


def format_call(name: str, fields: Iterable[tuple[str, Any]]) -> str:
    """``name(a=1.0, b=[1.0, 2.0])``."""
    return f"{name}(" + ", ".join(f"{k}={format_value(v)}" for k, v in fields) + ")"


def _shape(a: Any) -> Optional[tuple]:
    return None if a is None else tuple(np.shape(a))


def _facts(result) -> dict[str, Any]:
    """The facts both displays show, read without splitting ``q``/``p`` off ``y``."""
    t = np.asarray(result.t)
    y_shape = _shape(result.y)
    ndof = getattr(result, "_ndof", None)
    q_shape: Optional[tuple]
    p_shape: Optional[tuple]
    if ndof is not None and y_shape is not None:
        q_shape = p_shape = (y_shape[0], ndof)
    else:
        q_shape = _shape(result.__dict__.get("q"))
        p_shape = _shape(result.__dict__.get("p"))
    extra = result.extra if isinstance(result.extra, dict) else {}
    n_steps = extra.get("n_steps", max(t.size - 1, 0))
    err, kind = energy_error(result.energy)
    return {
        "method": result.method or "?",
        "n_steps": int(n_steps) if np.isfinite(n_steps) else n_steps,
        "dt": extra.get("dt"),
        "stride": extra.get("stride"),
        "span": (float(t[0]), float(t[-1])) if t.size else None,
        "samples": int(t.size),
        "shapes": {
            "t": _shape(result.t), "y": y_shape, "q": q_shape, "p": p_shape,
            "energy": _shape(result.energy),
        },
        "error": err,
        "error_kind": kind,
        "max_error": None if err is None else _max_error(err),
    }


def _span(span) -> str:
    return "empty" if span is None else f"[{span[0]:.6g}, {span[1]:.6g}]"


def _error_label(kind: str) -> str:
    return f"max {kind} energy error"


def result_repr(result) -> str:
    """One line: ``SimulationResult(method='yoshida4', steps=1000, dt=0.01, t=[0, 10],
    samples=1001, y=(1001, 2), max relative energy error=3.1e-09)``."""
    try:
        f = _facts(result)
    except Exception:  # noqa: BLE001  (a repr must not raise)
        return f"<SimulationResult, unreadable: {type(result).__name__}>"
    parts = [f"method={f['method']!r}", f"steps={f['n_steps']}"]
    if f["dt"] is not None:
        parts.append(f"dt={f['dt']:.6g}")
    parts.append(f"t={_span(f['span'])}")
    parts.append(f"samples={f['samples']}")
    parts.append(f"y={f['shapes']['y']}")
    if f["max_error"] is None:
        parts.append("energy not stored")
    else:
        parts.append(f"{_error_label(f['error_kind'])}={f['max_error']:.3g}")
    return "SimulationResult(" + ", ".join(parts) + ")"


def _bins_max(err: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """At most ``n`` points ``(first sample index of the bin, largest error in the bin)``: the
    peaks survive; a bin holding a NaN is NaN."""
    if err.size <= n:
        return np.arange(err.size), err
    starts = np.linspace(0, err.size, n + 1).astype(int)[:-1]
    return starts, np.maximum.reduceat(err, starts)


def sparkline_svg(err: np.ndarray, kind: str) -> str:
    """An inline SVG polyline of the energy error over the run (x: sample index, y: from 0 at
    the bottom to the largest error at the top); a run that turned non-finite is drawn up to
    there, with a red bar at the right end."""
    err = np.asarray(err, dtype=np.float64)
    index, pts = _bins_max(err, _SPARK_POINTS)
    finite = np.isfinite(pts)
    top = float(np.max(pts[finite])) if finite.any() else 0.0
    w, h, pad = _SPARK_WIDTH, _SPARK_HEIGHT, 2
    last = max(err.size - 1, 1)
    coords = []
    for i, v in zip(index, pts):
        if not np.isfinite(v):
            break
        x = pad + (w - 2 * pad) * i / last
        y = h - pad - ((h - 2 * pad) * v / top if top > 0 else 0.0)
        coords.append(f"{x:.2f},{y:.2f}")
    title = html.escape(f"{kind} energy error over the run, 0 to {top:.3g}")
    body = (
        f'<polyline fill="none" stroke="#1f77b4" stroke-width="1.2" '
        f'points="{" ".join(coords)}"/>'
    )
    if not finite.all():
        body += f'<rect x="{w - 4}" y="0" width="4" height="{h}" fill="#d62728"/>'
    return (
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" '
        f'viewBox="0 0 {w} {h}" role="img" aria-label="{title}">'
        f"<title>{title}</title>{body}</svg>"
    )


def result_html(result) -> str:
    """The notebook card: a table of the run's facts and the energy-error sparkline."""
    try:
        f = _facts(result)
    except Exception:  # noqa: BLE001  (a display must not raise)
        return "<pre>" + html.escape(result_repr(result)) + "</pre>"
    rows = [("method", f["method"]), ("steps", str(f["n_steps"]))]
    if f["dt"] is not None:
        rows.append(("dt", f"{f['dt']:.6g}"))
    rows.append(("t span", _span(f["span"])))
    stride = f["stride"]
    rows.append(("samples", f"{f['samples']}" + (f" (every {stride} steps)" if stride else "")))
    for name, shape in f["shapes"].items():
        if shape is not None:
            rows.append((f"{name} shape", str(shape)))
    spark = ""
    if f["max_error"] is None:
        rows.append(("energy", "not stored"))
    else:
        rows.append((_error_label(f["error_kind"]), f"{f['max_error']:.3g}"))
        spark = sparkline_svg(f["error"], f["error_kind"])
    cells = "".join(
        f'<tr><th style="text-align:left">{html.escape(k)}</th>'
        f'<td style="text-align:left">{html.escape(v)}</td></tr>'
        for k, v in rows
    )
    if spark:
        cells += (
            '<tr><th style="text-align:left">energy error</th>'
            f'<td style="text-align:left">{spark}</td></tr>'
        )
    return (
        '<div class="physicskit-result"><strong>SimulationResult</strong>'
        f"<table>{cells}</table></div>"
    )
