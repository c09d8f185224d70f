"""Utilities: :mod:`physicskit.classical.utils.symbolic` (``LagrangianEngine``)."""

from .symbolic import LagrangianEngine

__all__ = ["LagrangianEngine"]
