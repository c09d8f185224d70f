"""What the native core offers, read from its catalogue: the integrators and the built-in
systems with their typed parameters (not in the spec)."""

from __future__ import annotations

from typing import Any

from ._native import _core

__all__ = ["methods", "catalog"]


def methods() -> list[dict[str, Any]]:
    """Every integrator as a dict: ``name`` (the ``method`` argument of ``integrate``),
    ``order`` (of the global error), ``symplectic``, ``separable_only`` (needs ``H = T(p) +
    V(q)``), ``adaptive`` (its step follows ``rtol``/``atol`` and ``dt`` is the output
    spacing), ``needs_taylor_form`` (runs only on the systems of the SymPy engines, whose
    equations are expressions: ``taylor``), ``evaluations_per_step`` (force or vector-field evaluations per step: exact for
    explicit methods, typical for implicit ones), ``evaluations`` (what that count counts),
    ``reference`` (the method's source) and ``summary``. The same table as ``physicskit
    list``."""
    return [dict(m) for m in _core.methods()]


def catalog() -> list[dict[str, Any]]:
    """Every built-in system of the native catalogue as a dict: ``name``, ``python`` (the class
    or ``"Class.classmethod"`` that builds it), ``summary``, ``family``, ``separable``,
    ``methods``, ``default_method``, ``note``, ``physics`` (the paragraph on the system's physics
    that the gallery and ``physicskit list --json`` show, or None) and ``params`` (each with
    ``name``, ``kind``, ``default``, ``default_kind``, ``spec_default``, ``unit``, ``range``,
    ``length``, ``choices``, ``expectation``, ``help`` and ``initial_state``: part of the
    initial state, not a constant of the system)."""
    return [dict(e) for e in _core.catalog()]
