"""Axis labels with units, from the system catalogue (``physicskit.classical.catalog()``).

A system's state units are those the catalogue gives its initial-condition parameters (its
class's entry's ``q0``/``theta0``/``angles0`` and ``p0``/``thetadot0``/...); the symbols are
presentation only and live here.
"""

from __future__ import annotations

from typing import Any, Optional

from ..listings import catalog

#: Coordinate symbols (mathtext) of the systems whose coordinates have names.
_Q_SYMBOLS: dict[str, list[str]] = {
    "KeplerSystem": ["x", "y"],
    "HenonHeilesSystem": ["x", "y"],
    "ProjectileMotion": ["x", "y"],
    "DoublePendulum": [r"\theta_1", r"\theta_2"],
    "BeadOnRotatingHoop": [r"\theta"],
    "ElasticPendulum": ["r", r"\theta"],
    "HeavySymmetricTop": [r"\phi", r"\theta", r"\psi"],
    "PendulumSwarm": [r"\theta"],
    "SineGordonChain": [r"\phi"],
}

#: Names of the initial-condition parameters, whose catalogue units are the state's.
_Q_PARAMS = ("q0", "theta0", "angles0", "omega0")
_P_PARAMS = ("p0", "thetadot0", "qdot0", "angledots0")

#: Classes whose catalogue entry has no state-vector parameters, and the entry that has them.
_STATE_ENTRY_OF = {"FPUTChain": "HarmonicChain"}


_ENTRIES: dict[str, dict[str, Any]] = {}


def _entries() -> dict[str, dict[str, Any]]:
    """Catalogue entries by Python class name (the state-taking entry of each class), read
    once."""
    if not _ENTRIES:
        for entry in catalog():
            name = entry["python"]
            if name and "." not in name:
                _ENTRIES[name] = entry
    return _ENTRIES


def _entry(system: Any) -> Optional[dict[str, Any]]:
    entries = _entries()
    for cls in type(system).__mro__:
        name = _STATE_ENTRY_OF.get(cls.__name__, cls.__name__)
        if name in entries:
            return entries[name]
    return None


def _unit_words(unit: str, i: int) -> str:
    """The unit of component ``i`` (``"m, rad"`` lists one per component)."""
    parts = [u.strip() for u in unit.split(",")]
    u = parts[i] if i < len(parts) else parts[-1]
    return u if u else "dimensionless"


class Labels:
    """Axis labels of one system (or of an unknown one: generic symbols, state units)."""

    def __init__(self, system: Any = None, ndof: int = 1) -> None:
        entry = _entry(system) if system is not None else None
        cls_names = [c.__name__ for c in type(system).__mro__] if system is not None else []
        lagrangian = any(n == "LagrangianSystem" for n in cls_names)
        self.known = entry is not None
        params = {p["name"]: p["unit"] for p in entry["params"]} if entry else {}
        self._q_unit = next((params[n] for n in _Q_PARAMS if n in params), None)
        self._p_unit = next((params[n] for n in _P_PARAMS if n in params), None)
        symbols = next((_Q_SYMBOLS[n] for n in cls_names if n in _Q_SYMBOLS), None)
        self._symbols = symbols
        #: An Euler top (state = body rates, then the orientation quaternion).
        self.rigid_body = "EulerTop" in cls_names
        self._dot = lagrangian
        self.ndof = ndof
        units = " ".join(p["unit"] for p in entry["params"]) if entry else ""
        if "/s" in units or "s^" in units:
            self.time_unit = "s"
        elif "time" in units:
            self.time_unit = "time"
        elif entry is not None:
            self.time_unit = "dimensionless"
        else:
            self.time_unit = "time units"

    def symbol(self, i: int) -> str:
        """Mathtext symbol (no dollars) of coordinate ``i``."""
        if self._symbols is not None and self.ndof <= len(self._symbols):
            return self._symbols[i]
        if self._symbols is not None and len(self._symbols) == 1:
            return f"{self._symbols[0]}_{{{i + 1}}}"
        return f"q_{{{i + 1}}}" if self.ndof > 1 else "q"

    @property
    def q_unit(self) -> str:
        """Unit of the first coordinate."""
        return _unit_words(self._q_unit, 0) if self._q_unit is not None else "state units"

    def q(self, i: int) -> str:
        """Label of coordinate ``i``."""
        unit = _unit_words(self._q_unit, i) if self._q_unit is not None else "state units"
        return f"${self.symbol(i)}$ ({unit})"

    def p(self, i: int) -> str:
        """Label of momentum (Hamiltonian) or velocity (Lagrangian) ``i``."""
        unit = _unit_words(self._p_unit, i) if self._p_unit is not None else "state units"
        sym = self.symbol(i)
        if self._dot:
            return rf"$\dot{{{sym}}}$ ({unit})"
        if sym in ("x", "y"):
            return f"$p_{sym}$ ({unit})"
        return f"$p_{{{sym}}}$ ({unit})"

    def state(self, i: int) -> str:
        """Label of state component ``i``: coordinate ``i`` below ``ndof``, else momentum (or
        velocity) ``i - ndof``."""
        return self.q(i) if i < self.ndof else self.p(i - self.ndof)

    def _family(self) -> str | None:
        """The one symbol every coordinate shares (a swarm's or a chain's), else None."""
        if self._symbols is not None and len(self._symbols) == 1:
            return self._symbols[0]
        return None

    def q_all(self) -> str:
        """Label of all coordinates on one axis."""
        unit = _unit_words(self._q_unit, 0) if self._q_unit is not None else "state units"
        sym = self._family()
        return f"${sym}$ ({unit})" if sym else f"coordinates ({unit})"

    def p_all(self) -> str:
        """Label of all momenta / velocities on one axis."""
        unit = _unit_words(self._p_unit, 0) if self._p_unit is not None else "state units"
        sym = self._family()
        if sym:
            return rf"$\dot{{{sym}}}$ ({unit})" if self._dot else f"$p_{{{sym}}}$ ({unit})"
        word = "velocities" if self._dot else "momenta"
        return f"{word} ({unit})"

    @property
    def t(self) -> str:
        """Label of the time axis."""
        return f"$t$ ({self.time_unit})"


ENERGY_ERROR = r"$|E - E_0| \,/\, |E_0|$ (relative)"
