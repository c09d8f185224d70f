"""Utilities: :mod:`physicskit.classical.utils.symbolic` (``LagrangianEngine``,
``HamiltonianEngine``, ``ODEEngine``)."""

from .symbolic import HamiltonianEngine, LagrangianEngine, ODEEngine

__all__ = ["LagrangianEngine", "HamiltonianEngine", "ODEEngine"]
