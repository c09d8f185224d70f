"""Plots and animations of physicskit runs, on matplotlib (``pip install physicskit[plot]``).

Importing this module imports matplotlib (``import physicskit.classical`` does not); without
matplotlib it raises ImportError naming the extra to install. Every function takes an optional
``ax`` (where to draw; a new figure otherwise) and returns what it drew. The numbers drawn are
the library's: energies from ``result.energy``; modal energies, the LRL vector, phase-space
areas, separatrix energies, bob positions, rotation matrices, the heavy top's symmetry axis,
the Euler top's body angular momentum and box shape from the system's own methods; Lyapunov
estimates, alignment indices, the chaos threshold and chaos maps from
``physicskit.classical.chaos``.

=========================  ===============================================================
``plot_result``            ``q(t)``, ``p(t)`` (or ``qdot``) and the relative energy error
                           (also ``result.plot(system)``)
``energy_error``           relative energy error of several runs (methods) compared
``phase_portrait``         orbits in ``(q, p)``; the separatrix of the pendulum family
``poincare``               Poincaré sections, one colour per orbit
``modal_energies``         a chain's normal-mode energies over time (lines or stacked)
``modal_heatmap``          the same as a heatmap (mode x time)
``swarm_patch``            a pendulum swarm's phase-space patch and its area over time
``kepler_orbit``           a Kepler orbit, its LRL vector and the perihelion precession
``top_axis``               the heavy top's axis tip on the unit sphere (3-D)
``polhodes``               the Euler top's polhodes on the angular-momentum sphere (3-D)
``plot_lyapunov``          running Lyapunov estimates against time (``lyapunov_spectrum``)
``plot_sali``              SALI / GALI_k against time, with the chaos threshold (``sali``,
                           ``gali``)
``plot_chaos_map``         a ``chaos_map`` on its grid of initial conditions, with colour bar
``animate``                a ``FuncAnimation`` of a run (pendulums, chains, swarm, orbits,
                           tops); ``save_animation`` writes it as GIF or MP4
=========================  ===============================================================
"""

from __future__ import annotations

from ._mpl import pyplot as _pyplot

_pyplot()  # ImportError naming physicskit[plot] before anything else needs matplotlib

from .animation import animate, save_animation  # noqa: E402
from .chaos import plot_chaos_map, plot_lyapunov, plot_sali  # noqa: E402
from .lattices import modal_energies, modal_heatmap  # noqa: E402
from .orbits import kepler_orbit  # noqa: E402
from .phase import phase_portrait, poincare  # noqa: E402
from .results import energy_error, plot_result  # noqa: E402
from .rigid import polhodes, top_axis  # noqa: E402
from .swarm import swarm_patch  # noqa: E402

__all__ = [
    "plot_result",
    "energy_error",
    "phase_portrait",
    "poincare",
    "modal_energies",
    "modal_heatmap",
    "swarm_patch",
    "kepler_orbit",
    "top_axis",
    "polhodes",
    "plot_lyapunov",
    "plot_sali",
    "plot_chaos_map",
    "animate",
    "save_animation",
]
