"""The physicskit 0.4.0 peer's visualizers, as thin adapters over
:mod:`physicskit.classical.plotting` (matplotlib) and, for :mod:`.interactive`, plotly.

=====================  =================================================================
``phase_space``        ``plot_phase_portrait``, ``plot_phase_swarm``, ``poincare_section``
                       (crossings of stored arrays), ``plot_poincare_section``,
                       ``plot_so3_momentum_sphere``
``modal_analysis``     ``plot_modal_energy_bars``, ``animate_modal_energies``
``animations``         ``SideBySideAnimator``, ``pendulum_animation``,
                       ``orbit_trace_animation``, ``animate_elastic_pendulum``,
                       ``animate_rigid_body_tumble``, ``animate_eulers_disk``,
                       ``animate_rattleback``
``interactive``        ``interactive_orbit``, ``interactive_so3_momentum_sphere`` (plotly
                       figures; ``pip install physicskit[interactive]``)
=====================  =================================================================

Names are resolved on first use: importing this package imports neither matplotlib nor
plotly, and each submodule needs only its own library.
"""

from __future__ import annotations

import importlib
from typing import Any

_WHERE = {
    "plot_phase_portrait": "phase_space",
    "plot_phase_swarm": "phase_space",
    "poincare_section": "phase_space",
    "plot_poincare_section": "phase_space",
    "plot_so3_momentum_sphere": "phase_space",
    "plot_modal_energy_bars": "modal_analysis",
    "animate_modal_energies": "modal_analysis",
    "SideBySideAnimator": "animations",
    "pendulum_animation": "animations",
    "orbit_trace_animation": "animations",
    "animate_elastic_pendulum": "animations",
    "animate_rigid_body_tumble": "animations",
    "animate_eulers_disk": "animations",
    "animate_rattleback": "animations",
    "interactive_orbit": "interactive",
    "interactive_so3_momentum_sphere": "interactive",
}

__all__ = list(_WHERE)


def __getattr__(name: str) -> Any:
    module = _WHERE.get(name)
    if module is None:
        if name in ("phase_space", "modal_analysis", "animations", "interactive"):
            return importlib.import_module(f".{name}", __name__)
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(importlib.import_module(f".{module}", __name__), name)


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
