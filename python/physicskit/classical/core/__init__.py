"""Base classes (:mod:`physicskit.classical.core.base_system`) and the functional integrator
API on plain callables (:mod:`physicskit.classical.core.integrators`)."""

from . import integrators
from .base_system import (
    DynamicalSystem,
    HamiltonianSystem,
    LagrangianSystem,
    ODESystem,
    SimulationResult,
)

__all__ = [
    "DynamicalSystem",
    "ODESystem",
    "HamiltonianSystem",
    "LagrangianSystem",
    "SimulationResult",
    "integrators",
]
