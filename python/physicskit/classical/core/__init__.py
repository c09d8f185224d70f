"""Base classes (:mod:`physicskit.classical.core.base_system`)."""

from .base_system import (
    DynamicalSystem,
    HamiltonianSystem,
    LagrangianSystem,
    ODESystem,
    SimulationResult,
)

__all__ = ["DynamicalSystem", "ODESystem", "HamiltonianSystem", "LagrangianSystem", "SimulationResult"]
