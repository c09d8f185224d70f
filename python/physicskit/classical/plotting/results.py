"""A run at a glance (``result.plot()``) and the energy error of several runs compared."""

from __future__ import annotations

from typing import Any, Sequence

from ._data import as_results, has_qp, labels_for, relative_energy_error
from ._labels import ENERGY_ERROR, Labels, method_words
from ._mpl import pyplot


def _energy_label(relative: bool) -> str:
    return ENERGY_ERROR if relative else r"$|E - E_0|$ (absolute: $E_0 = 0$)"


def plot_result(result: Any, system: Any = None, *, ax: Any = None, max_lines: int = 8) -> Any:
    """Three stacked panels of one run: coordinates ``q(t)``, momenta ``p(t)`` (or velocities
    ``qdot(t)`` for a Lagrangian system) and the relative energy error on a log scale.

    Parameters
    ----------
    result : SimulationResult
    system : optional
        The system that produced it; gives the axes their symbols and units (from the
        catalogue). Without it the labels are generic.
    ax : sequence of 3 Axes, optional
        Where to draw (2 for a run without ``q``/``p``: the state, or the Euler top's body
        rates ``omega``, and the energy error).
    max_lines : int
        At most this many coordinates are drawn per panel (a 1000-pendulum swarm is not drawn
        as 1000 lines).

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = pyplot()
    split = has_qp(result)
    n_panels = 3 if split else 2
    if ax is None:
        fig, axes = plt.subplots(n_panels, 1, sharex=True, figsize=(7.0, 2.2 * n_panels + 0.6))
        axes = list(axes)
    else:
        axes = list(ax)
        if len(axes) != n_panels:
            raise ValueError(f"ax must hold {n_panels} axes for this result, got {len(axes)}")
        fig = axes[0].figure
    t = result.t
    if split:
        ndof = result.q.shape[1]
        lab = Labels(system, ndof)
        shown = range(min(ndof, max_lines))
        for i in shown:
            axes[0].plot(t, result.q[:, i], lw=1.0, label=f"${lab.symbol(i)}$")
            axes[1].plot(t, result.p[:, i], lw=1.0)
        axes[0].set_ylabel(lab.q(0) if ndof == 1 else lab.q_all())
        axes[1].set_ylabel(lab.p(0) if ndof == 1 else lab.p_all())
        if 1 < ndof <= max_lines:
            axes[0].legend(loc="upper right", fontsize="small", ncol=min(ndof, 4))
    else:
        lab = Labels(system, 1)
        if lab.rigid_body:
            # The Euler top's state is [w1, w2, w3, quaternion]: the body rates are the story.
            for i in range(3):
                axes[0].plot(t, result.y[:, i], lw=1.0, label=rf"$\omega_{i + 1}$")
            axes[0].set_ylabel(rf"body $\omega$ ({lab.q_unit})")
        else:
            for i in range(min(result.y.shape[1], max_lines)):
                axes[0].plot(t, result.y[:, i], lw=1.0, label=f"$y_{{{i}}}$")
            axes[0].set_ylabel("state (state units)")
        axes[0].legend(loc="upper right", fontsize="small", ncol=4)
    if getattr(result, "energy", None) is not None:
        err, relative = relative_energy_error(result)
        axes[-1].plot(t, err, lw=1.0, color="C3")
        axes[-1].set_yscale("log")
        axes[-1].set_ylabel(_energy_label(relative))
    else:
        axes[-1].text(0.5, 0.5, "no energy stored (energy=False)", ha="center",
                      va="center", transform=axes[-1].transAxes)
    axes[-1].set_xlabel(lab.t)
    method = getattr(result, "method", "")
    axes[0].set_title(method_words(method) if method else "")
    fig.align_ylabels(axes)
    return fig


def energy_error(results: Any, labels: Sequence[str] | None = None, system: Any = None, *,
                 ax: Any = None) -> list[Any]:
    """The relative energy error ``|E - E0|/|E0|`` of several runs against time, log scale,
    one line per run (labelled by method unless ``labels`` is given).

    Returns the list of ``Line2D``.
    """
    runs = as_results(results)
    names = labels_for(runs, labels)
    ax = ax if ax is not None else pyplot().figure(figsize=(6.4, 4.0)).add_subplot()
    lines = []
    relative_all = True
    for r, name in zip(runs, names):
        err, relative = relative_energy_error(r)
        relative_all &= relative
        (line,) = ax.plot(r.t, err, lw=1.0, label=name)
        lines.append(line)
    ax.set_yscale("log")
    ax.set_xlabel(Labels(system).t)
    ax.set_ylabel(_energy_label(relative_all))
    ax.legend(fontsize="small")
    return lines
