"""Utilities: :mod:`~physicskit.classical.utils.symbolic` (``LagrangianEngine``,
``HamiltonianEngine``, ``ODEEngine``), :mod:`~physicskit.classical.utils.conservation`
(drifts of conserved quantities) and :mod:`~physicskit.classical.utils.stepsize`
(``estimate_dt``)."""

from .conservation import (
    angular_momentum_2d,
    angular_momentum_drift,
    energy_drift,
    lrl_drift,
    relative_energy_drift,
)
from .stepsize import StepSizeEstimate, estimate_dt
from .symbolic import HamiltonianEngine, LagrangianEngine, ODEEngine

__all__ = [
    "LagrangianEngine",
    "HamiltonianEngine",
    "ODEEngine",
    "energy_drift",
    "relative_energy_drift",
    "angular_momentum_2d",
    "angular_momentum_drift",
    "lrl_drift",
    "StepSizeEstimate",
    "estimate_dt",
]
