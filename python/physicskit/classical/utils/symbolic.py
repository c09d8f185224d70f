"""``LagrangianEngine``: equations of motion from a SymPy Lagrangian, evaluated natively.

The SymPy expression ``L(q, qdot, t; params)`` is translated **once**, at construction, into
the Rust expression tree ``physicskit::classical::lagrangian::Expr`` (through its prefix
S-expression form). From then on the Rust Lagrangian engine differentiates it by automatic
differentiation: accelerations, canonical momenta, the inverse Legendre map and the
canonical vector field never call back into Python. SymPy is only needed to build the engine.
"""

from __future__ import annotations

import math
from typing import Any, Optional

import numpy as np

from .._native import as_scalar, as_vector, native
from ..core.base_system import LagrangianSystem

__all__ = ["LagrangianEngine"]

_FUNCS = {
    "sin": "sin", "cos": "cos", "tan": "tan", "exp": "exp", "log": "ln",
    "sinh": "sinh", "cosh": "cosh", "tanh": "tanh", "asin": "asin", "acos": "acos",
    "atan": "atan", "Abs": "abs",
}


def _number(x: float) -> str:
    if not math.isfinite(x):
        raise ValueError(f"the Lagrangian contains the non-finite number {x}")
    return repr(float(x))


class _Translator:
    """SymPy expression -> prefix S-expression of ``Expr::parse``."""

    def __init__(self, sp, names: dict):
        self.sp = sp
        self.names = names

    def __call__(self, e) -> str:
        sp = self.sp
        if e in self.names:
            return self.names[e]
        if isinstance(e, sp.Symbol):
            raise ValueError(
                f"symbol {e} is neither a coordinate in q, a velocity in qdot, t, nor a key of "
                "params: declare it"
            )
        if e is sp.pi:
            return "pi"
        if e is sp.E:
            return "(exp 1)"
        if isinstance(e, sp.Integer):
            return str(int(e))
        if e.is_Number:
            if not e.is_real:
                raise ValueError(f"the Lagrangian must be real; found {e}")
            return _number(float(e))
        if isinstance(e, sp.Add):
            return "(+ " + " ".join(self(a) for a in e.args) + ")"
        if isinstance(e, sp.Mul):
            return "(* " + " ".join(self(a) for a in e.args) + ")"
        if isinstance(e, sp.Pow):
            base, ex = e.args
            if ex == sp.Rational(1, 2):
                return f"(sqrt {self(base)})"
            if isinstance(ex, sp.Integer):
                return f"(^ {self(base)} {int(ex)})"
            if ex.is_Number:
                return f"(^ {self(base)} {_number(float(ex))})"
            return f"(^ {self(base)} {self(ex)})"
        if isinstance(e, sp.Function):
            name = type(e).__name__
            if name in _FUNCS and len(e.args) == 1:
                return f"({_FUNCS[name]} {self(e.args[0])})"
        if e.is_Number is False and e.is_constant() and e.free_symbols == set():
            value = complex(e.evalf())
            if value.imag == 0.0:
                return _number(value.real)
        raise ValueError(
            f"cannot translate {type(e).__name__} `{e}`: use +, *, powers, sin, cos, tan, exp, "
            "log, sqrt, sinh, cosh, tanh, asin, acos, atan, Abs"
        )


class LagrangianEngine:
    """Native equations of motion of a SymPy Lagrangian ``L(q, qdot, t)``.

    Parameters
    ----------
    q : sequence of sympy.Symbol
        Generalized coordinates.
    qdot : sequence of sympy.Symbol
        Their velocities, in the same order.
    L : sympy.Expr
        The Lagrangian.
    t : sympy.Symbol, optional
        The time symbol, if ``L`` depends explicitly on time.
    params : dict, optional
        Numerical values of the other symbols of ``L`` (keys: symbols or their names).

    Attributes
    ----------
    q, qdot, t, params, L
        As given; ``n`` is the number of degrees of freedom.
    sexpr : str
        The expression as handed to Rust (prefix form of ``physicskit::classical::lagrangian::Expr``).

    Raises
    ------
    ValueError
        If ``L`` uses an undeclared symbol or an unsupported function, if ``q`` and ``qdot``
        differ in length, or if a parameter value is not a finite number.
    """

    def __init__(self, q, qdot, L: Any, t: Any = None, params: Optional[dict] = None):
        import sympy as sp

        self.q = list(q)
        self.qdot = list(qdot)
        if len(self.q) != len(self.qdot) or not self.q:
            raise ValueError(
                f"q and qdot must be non-empty and of equal length, got {len(self.q)} and "
                f"{len(self.qdot)}"
            )
        self.n = len(self.q)
        self.t = t
        self.L = sp.sympify(L)
        params = dict(params or {})
        by_name = {s.name: s for s in self.L.free_symbols if isinstance(s, sp.Symbol)}
        self.params = {}
        for key, value in params.items():
            sym = key if isinstance(key, sp.Symbol) else by_name.get(str(key), sp.Symbol(str(key)))
            self.params[sym] = as_scalar(f"params[{sym}]", value)
        names = {}
        for i, s in enumerate(self.q):
            names[s] = f"q{i}"
        for i, s in enumerate(self.qdot):
            names[s] = f"qdot{i}"
        if t is not None:
            names[t] = "t"
        for j, s in enumerate(self.params):
            names[s] = f"param{j}"
        self._param_values = np.array(list(self.params.values()), dtype=np.float64)
        self.sexpr = _Translator(sp, names)(self.L)
        native("expr_validate")(self.sexpr, self.n, len(self._param_values))
    def _system(self, state):
        """A native Lagrangian system (``physicskit._core.NativeSystem``) at ``state``."""
        state = as_vector("state", state, 2 * self.n)
        return native("expr_lagrangian")(
            self.sexpr, self.n, self._param_values, state[: self.n], state[self.n :]
        )

    @property
    def mass_matrix(self):
        """The symbolic mass matrix ``d2L/dqdot2`` (a SymPy Matrix)."""
        import sympy as sp

        return sp.hessian(self.L, self.qdot)

    def system(self, q0, qdot0) -> "SymbolicLagrangianSystem":
        """A :class:`~physicskit.classical.LagrangianSystem` with this Lagrangian, started at
        ``(q0, qdot0)``; it integrates fully natively."""
        return SymbolicLagrangianSystem(self, q0, qdot0)

    def acceleration(self, q, qdot, t: float = 0.0) -> np.ndarray:
        """``qddot`` from the Euler-Lagrange equations at ``(q, qdot, t)``."""
        q = as_vector("q", q, self.n)
        qdot = as_vector("qdot", qdot, self.n)
        return self._system(np.concatenate([q, qdot])).acceleration(q, qdot, as_scalar("t", t))

    def momentum(self, q, qdot, t: float = 0.0) -> np.ndarray:
        """Canonical momentum ``p = dL/dqdot`` at ``(q, qdot, t)``."""
        q = as_vector("q", q, self.n)
        qdot = as_vector("qdot", qdot, self.n)
        return self._system(np.concatenate([q, qdot])).momentum(q, qdot, as_scalar("t", t))


class SymbolicLagrangianSystem(LagrangianSystem):
    """A LagrangianSystem defined by a :class:`LagrangianEngine`, integrated natively.

    Parameters
    ----------
    engine : LagrangianEngine
        The Lagrangian.
    q0, qdot0 : array-like, shape (engine.n,)
        Initial positions and velocities.
    """

    def __init__(self, engine: LagrangianEngine, q0, qdot0):
        super().__init__(as_vector("q0", q0, engine.n), as_vector("qdot0", qdot0, engine.n))
        self.engine = engine
        self._native = engine._system(self.state)

    def energy(self, state: Optional[np.ndarray] = None) -> float:
        """Energy ``sum qdot_i dL/dqdot_i - L`` of ``state`` (default: ``self.state``)."""
        return self._native.energy(self._state_arg(state))
