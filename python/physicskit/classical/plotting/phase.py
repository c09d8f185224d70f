"""Phase portraits (with the separatrix of the pendulum family) and Poincaré sections."""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np

from ._data import as_results, given_labels, has_qp
from ._labels import Labels, drawing_of
from ._mpl import new_axes, orbit_colours

#: Grid of the separatrix contour (its level set is drawn by matplotlib's contouring): fine
#: where the energy is one vectorized call (the swarm), coarser where it is one call per point.
_GRID = (241, 161)
_GRID_PER_POINT = (121, 81)


def _pendulum_energy_grid(system: Any, qq: np.ndarray, pp: np.ndarray) -> np.ndarray | None:
    """The system's energy on the ``(q, p)`` grid, for the one-degree-of-freedom pendulum
    family (the swarm's pendulum, the bead on the hoop); None for other systems."""
    kind = (drawing_of(system) or {}).get("kind")
    if kind == "swarm":
        # One library call for the whole grid: a swarm of one pendulum per grid point.
        grid = type(system)(qq.ravel(), pp.ravel(), g_over_l=system.g_over_l)
        return grid.per_particle_energy().reshape(qq.shape)
    if kind == "hoop":
        e = np.empty(qq.size)
        for i, (q, p) in enumerate(zip(qq.ravel(), pp.ravel())):
            e[i] = system.energy(np.array([q, p]))
        return e.reshape(qq.shape)
    return None


def _separatrix_levels(system: Any) -> list[float]:
    """The system's ``separatrix_energies`` (the levels of its saddle equilibria), or none
    for a system without them."""
    if not hasattr(system, "separatrix_energies"):
        return []
    return [float(v) for v in system.separatrix_energies()]


def draw_separatrix(ax: Any, system: Any, linewidth: float = 1.0) -> Any:
    """Contour the separatrix of a pendulum-family system over ``ax``'s current window
    (dashed black, labelled "separatrix"); the ``ContourSet``, or None for other systems or
    when no separatrix crosses the window."""
    levels = _separatrix_levels(system)
    if not levels:
        return None
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    swarm = (drawing_of(system) or {}).get("kind") == "swarm"
    nx, ny = _GRID if swarm else _GRID_PER_POINT
    qq, pp = np.meshgrid(np.linspace(x0, x1, nx), np.linspace(y0, y1, ny))
    e = _pendulum_energy_grid(system, qq, pp)
    if e is None:  # a separatrix, but no vectorized energy to contour it with
        return None
    inside = [v for v in levels if e.min() < v < e.max()]
    cs = None
    if inside:
        cs = ax.contour(qq, pp, e, levels=inside, colors="k", linestyles="--",
                        linewidths=linewidth)
        ax.plot([], [], "k--", lw=linewidth, label="separatrix")
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    return cs


def phase_portrait(results: Any, system: Any = None, *, dof: int | Sequence[int] | None = 0,
                   separatrix: bool = True, labels: Sequence[str] | None = None,
                   ax: Any = None) -> list[Any]:
    """Orbits in the ``(q_i, p_i)`` plane (``p`` is ``qdot`` for a Lagrangian system).

    Parameters
    ----------
    results : SimulationResult or sequence of them
        Each run draws one line per selected degree of freedom.
    system : optional
        The system (labels with units; the separatrix).
    dof : int, sequence of int, or None
        Which degree(s) of freedom: ``None`` draws every one (a swarm's pendulums, each its own
        orbit).
    separatrix : bool
        For the pendulum family (``PendulumSwarm``, ``BeadOnRotatingHoop``), draw the
        separatrix: the energy level of the unstable equilibria, contoured from the system's
        own energy function over the visible window.
    labels : sequence of str, optional
        Legend labels, one per run.
    ax : Axes, optional

    Returns
    -------
    list
        The orbit ``Line2D`` objects, then the separatrix ``ContourSet`` if drawn.
    """
    runs = as_results(results)
    for r in runs:
        if not has_qp(r):
            raise ValueError("phase_portrait needs a run with q and p (not a general ODE)")
    ndof = runs[0].q.shape[1]
    if dof is None:
        dofs = list(range(ndof))
    elif isinstance(dof, (int, np.integer)):
        dofs = [int(dof)]
    else:
        dofs = [int(d) for d in dof]
    for d in dofs:
        if not 0 <= d < ndof:
            raise ValueError(f"dof = {d} is out of range for {ndof} degrees of freedom")
    ax = new_axes(ax)
    lab = Labels(system, ndof)
    names = given_labels(labels, len(runs))
    artists: list[Any] = []
    many = len(runs) * len(dofs) > 12
    for k, r in enumerate(runs):
        for j, d in enumerate(dofs):
            kw: dict[str, Any] = {"lw": 0.6 if many else 1.0}
            if names is not None and j == 0:
                kw["label"] = names[k]
            (line,) = ax.plot(r.q[:, d], r.p[:, d], **kw)
            artists.append(line)
    ax.set_xlabel(lab.q(dofs[0]) if len(dofs) == 1 else lab.q_all())
    ax.set_ylabel(lab.p(dofs[0]) if len(dofs) == 1 else lab.p_all())
    if separatrix and system is not None:
        cs = draw_separatrix(ax, system)
        if cs is not None:
            artists.append(cs)
    if names is not None or any(a.get_label() == "separatrix" for a in ax.lines):
        ax.legend(fontsize="small", loc="upper right")
    return artists


def poincare(sections: Any, *, x: int = 0, y: int | None = None,
             labels: Sequence[str] | None = None, system: Any = None, s: float = 2.0,
             ax: Any = None) -> list[Any]:
    """Poincaré sections, one colour per orbit: a scatter of the crossing states' components
    ``x`` and ``y``.

    Parameters
    ----------
    sections : sequence
        One entry per orbit: an object with a 2-D ``y`` of crossing states (what a section
        function returns), or a 2-D array of them, rows = crossings.
    x, y : int
        State components on the axes; ``y`` defaults to the momentum conjugate to ``x``
        (``x + dim/2``).
    labels : sequence of str, optional
        One legend label per orbit.
    system : optional
        The system (axis labels with units).
    s : float
        Marker size.
    ax : Axes, optional

    Returns
    -------
    list of PathCollection, one per orbit.
    """
    if hasattr(sections, "y") or (isinstance(sections, np.ndarray) and sections.ndim == 2):
        sections = [sections]
    pts = [np.asarray(getattr(sec, "y", sec), dtype=float) for sec in sections]
    if not pts:
        raise ValueError("sections is empty")
    for a in pts:
        if a.ndim != 2:
            raise ValueError(f"each section must be 2-D (crossings x state), got {a.shape}")
    dim = pts[0].shape[1]
    yi = x + dim // 2 if y is None else y
    for i in (x, yi):
        if not 0 <= i < dim:
            raise ValueError(f"component {i} is out of range for states of length {dim}")
    if labels is not None and len(labels) != len(pts):
        raise ValueError(f"labels has {len(labels)} entries for {len(pts)} sections")
    ax = new_axes(ax)
    colours = orbit_colours(len(pts))
    out = []
    for k, a in enumerate(pts):
        colour = colours[k]
        kw: dict[str, Any] = {"s": s, "color": colour, "linewidths": 0}
        if labels is not None:
            kw["label"] = labels[k]
        out.append(ax.scatter(a[:, x], a[:, yi], **kw))
    lab = Labels(system, dim // 2)
    ax.set_xlabel(lab.state(x))
    ax.set_ylabel(lab.state(yi))
    if labels is not None:
        ax.legend(fontsize="small", markerscale=3)
    return out
