"""Axis labels with units, from the system catalogue (``physicskit.classical.catalog()``).

Everything a label says comes from the system's catalogue entry: the coordinates' symbols and
the unit of time from its ``presentation``, the state's units from its initial-state
parameters (``initial_state``: ``q0``/``theta0``/... and ``p0``/``thetadot0``/...) or, for an
entry without them, from ``presentation["state_units"]``. Nothing here names a system.
"""

from __future__ import annotations

from typing import Any, Optional

from ..listings import catalog, methods

_ENTRIES: dict[str, dict[str, Any]] = {}

#: The catalogue's units of time in the words the axes use.
_TIME_WORDS = {"s": "s", "time": "time", "": "dimensionless"}


def _entries() -> dict[str, dict[str, Any]]:
    """Catalogue entries by Python class name (the state-taking entry of each class), read
    once."""
    if not _ENTRIES:
        for entry in catalog():
            name = entry["python"]
            if name and "." not in name:
                _ENTRIES[name] = entry
    return _ENTRIES


def entry_of(system: Any) -> Optional[dict[str, Any]]:
    """The catalogue entry of ``system``'s class (or of its nearest built-in base class),
    or None for a system the catalogue does not hold (a user's own subclass)."""
    if system is None:
        return None
    entries = _entries()
    for cls in type(system).__mro__:
        if cls.__name__ in entries:
            return entries[cls.__name__]
    return None


def drawing_of(system: Any) -> Optional[dict[str, Any]]:
    """The catalogue's ``presentation["drawing"]`` of ``system`` (``{"kind": ...}``), or None."""
    entry = entry_of(system)
    return entry["presentation"]["drawing"] if entry is not None else None


def method_words(name: str) -> str:
    """A method's name in words (``"implicit midpoint"``), from ``methods()``; the name as
    given for one the table does not hold."""
    for m in methods():
        if m["name"] == name:
            return str(m["label"])
    return name


def _unit_words(unit: str, i: int) -> str:
    """The unit of component ``i`` (``"m, rad"`` lists one per component)."""
    parts = [u.strip() for u in unit.split(",")]
    u = parts[i] if i < len(parts) else parts[-1]
    return u if u else "dimensionless"


def _state_units(entry: dict[str, Any]) -> tuple[Optional[str], Optional[str]]:
    """Units of the coordinates and of the momenta (or velocities) of an entry's state."""
    units = [p["unit"] for p in entry["params"] if p["initial_state"]]
    if not units and entry["presentation"]["state_units"] is not None:
        units = list(entry["presentation"]["state_units"])
    q = units[0] if units else None
    p = units[1] if len(units) > 1 else None
    return q, p


class Labels:
    """Axis labels of one system (or of an unknown one: generic symbols, state units)."""

    def __init__(self, system: Any = None, ndof: int = 1) -> None:
        entry = entry_of(system)
        cls_names = [c.__name__ for c in type(system).__mro__] if system is not None else []
        self.known = entry is not None
        if entry is not None:
            lagrangian = entry["family"] == "lagrangian"
            self._q_unit, self._p_unit = _state_units(entry)
            symbols = entry["presentation"]["symbols"]
            self._symbols = list(symbols) if symbols else None
            drawing = entry["presentation"]["drawing"]["kind"]
            self.time_unit = _TIME_WORDS.get(entry["presentation"]["time_unit"], "time units")
        else:
            lagrangian = "LagrangianSystem" in cls_names
            self._q_unit = self._p_unit = None
            self._symbols = None
            drawing = None
            self.time_unit = "time units"
        #: A rigid body drawn as its inertia box (state = body rates, then the orientation
        #: quaternion).
        self.rigid_body = drawing == "inertia_box"
        self._dot = lagrangian
        self.ndof = ndof

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

    def _named(self) -> bool:
        """True when each coordinate has a symbol of its own (``\\theta_1``, ``\\theta_2``)."""
        return self._symbols is not None and 1 < self.ndof <= len(self._symbols)

    def q_all(self) -> str:
        """Label of all coordinates on one axis: the family's symbol (a chain's ``q``, a
        swarm's ``θ``), their own symbols (``θ₁, θ₂``), or the word."""
        unit = _unit_words(self._q_unit, 0) if self._q_unit is not None else "state units"
        sym = self._family()
        if sym:
            return f"${sym}$ ({unit})"
        if self._named():
            names = ", ".join(f"${self.symbol(i)}$" for i in range(self.ndof))
            return f"{names} ({unit})"
        return f"coordinates ({unit})"

    def p_all(self) -> str:
        """Label of all momenta / velocities on one axis, as :meth:`q_all`."""
        unit = _unit_words(self._p_unit, 0) if self._p_unit is not None else "state units"
        sym = self._family()
        if sym:
            return rf"$\dot{{{sym}}}$ ({unit})" if self._dot else f"$p_{{{sym}}}$ ({unit})"
        if self._named():
            if self._dot:
                names = ", ".join(rf"$\dot{{{self.symbol(i)}}}$" for i in range(self.ndof))
            else:
                names = ", ".join(f"$p_{{{self.symbol(i)}}}$" for i in range(self.ndof))
            return f"{names} ({unit})"
        word = "velocities" if self._dot else "momenta"
        return f"{word} ({unit})"

    @property
    def t(self) -> str:
        """Label of the time axis."""
        return f"$t$ ({self.time_unit})"


ENERGY_ERROR = r"$|E - E_0| \,/\, |E_0|$ (relative)"
