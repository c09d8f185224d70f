"""Shared plumbing of the built-in systems: build one from the catalogue and adopt it as
``self._native``.

Every built-in class constructs through :func:`build`, which hands all of its arguments to
``physicskit._core.build`` under the catalogue entry's name. The catalogue converts and checks
every value (kind, finiteness, range, vector lengths) and fills in defaults; the classes check
nothing themselves and take the attributes they expose (``self.m1`` ...) from the checked
values, through :func:`keep`, which makes them read-only: the native system was built from
them, so assigning a new value could only make the attribute lie about the numerics.
"""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from .._native import _core, as_int, as_vector


def build(entry: str, /, **params: Any):
    """The native system of the catalogue entry ``entry`` built from ``params`` (a value of
    ``None`` leaves a parameter to the catalogue)."""
    return _core.build(entry, params)


def adopt(system, nat) -> dict[str, Any]:
    """Make ``nat`` the numerics of ``system``, copy its validated initial state, and return
    the catalogue's checked parameter values."""
    system._native = nat
    system.state = nat.state
    system.t = 0.0
    if nat.ndof is not None:
        system.ndof = nat.ndof
    return nat.params


def keep(system, **values: Any) -> None:
    """Set ``values`` (constructor arguments as the catalogue checked them, and quantities
    derived from them) as read-only attributes of ``system``: assigning or deleting one later
    raises ``AttributeError`` (``DynamicalSystem.__setattr__``)."""
    system.__dict__.update(values)
    system.__dict__["_readonly"] = system.__dict__.get("_readonly", frozenset()) | set(values)


def from_native(cls, nat):
    """An instance of ``cls`` adopting ``nat`` (alternate constructors: the catalogue entry
    already built and checked the system, so ``__init__`` does not run again)."""
    system = cls.__new__(cls)
    system._adopt(nat)
    return system


def kinetic_energy(self, p: np.ndarray) -> float:
    """Return the kinetic energy T(p)."""
    return self._native.kinetic_energy(as_vector("p", p, self.ndof))


def potential_energy(self, q: np.ndarray) -> float:
    """Return the potential energy V(q)."""
    return self._native.potential_energy(as_vector("q", q, self.ndof))


def energy(self, state: Optional[np.ndarray] = None) -> float:
    """Return the total mechanical energy of ``state`` (default: ``self.state``)."""
    return self._native.energy(self._state_arg(state))
