"""``LagrangianEngine``: equations of motion from a SymPy Lagrangian, evaluated natively.

The SymPy expression ``L(q, qdot, t; params)`` is translated **once**, at construction, into
the Rust expression tree ``physicskit::classical::lagrangian::Expr`` (through its prefix
S-expression form). From then on the Rust Lagrangian engine differentiates it by automatic
differentiation: accelerations, canonical momenta, the inverse Legendre map and the
canonical vector field never call back into Python. SymPy is only needed to build the engine.

What the engine evaluates, with ``M = d2L/dqdot2`` the mass matrix:

* ``acceleration(q, qdot, t)``: ``qddot = M^-1 (dL/dq - d2L/(dqdot dq) qdot - d2L/(dqdot dt))``
  (the Euler-Lagrange equations solved for ``qddot``);
* ``momentum(q, qdot, t)``: ``p = dL/dqdot``;
* ``velocity(q, p, t)``: the ``qdot`` with ``dL/dqdot(q, qdot, t) = p`` (the inverse Legendre
  map; Newton's method when ``L`` is not quadratic in ``qdot``);
* ``hamiltonian(q, p, t)``: ``H = p . qdot - L`` at ``qdot = velocity(q, p, t)``;
* ``canonical_derivatives(t, [q, p])``: Hamilton's equations ``dq/dt = dH/dp = qdot(q, p, t)``,
  ``dp/dt = -dH/dq = dL/dq(q, qdot(q, p, t), t)``.

The Numba peer's names ``acceleration_njit``, ``momentum_njit``, ``hamiltonian_njit`` and
``canonical_deriv_njit`` are aliases of these (same arguments as the peer's), so code
written against it runs unchanged.
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
        self._probe: Any = None

    def __repr__(self) -> str:
        fields = [("q", self.q), ("qdot", self.qdot), ("L", self.L)]
        if self.t is not None:
            fields.append(("t", self.t))
        if self.params:
            fields.append(("params", self.params))
        return "LagrangianEngine(" + ", ".join(f"{k}={v!r}" for k, v in fields) + ")"

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

    def _evaluator(self, q: np.ndarray, qdot: np.ndarray):
        """The native system the pointwise methods evaluate with (its state is never used):
        built at the first query, where the mass matrix must be regular, then kept."""
        if self._probe is None:
            self._probe = self._system(np.concatenate([q, qdot]))
        return self._probe

    def _args(self, a: str, av, b: str, bv, t) -> tuple[np.ndarray, np.ndarray, float]:
        """Two vectors of length ``n`` named ``a`` and ``b`` and the time, converted."""
        return as_vector(a, av, self.n), as_vector(b, bv, self.n), as_scalar("t", t)

    def acceleration(self, q, qdot, t: float = 0.0) -> np.ndarray:
        """``qddot`` from the Euler-Lagrange equations at ``(q, qdot, t)``.

        Raises
        ------
        ValueError
            Wrong lengths, non-finite values, or a singular mass matrix ``d2L/dqdot2``.
        """
        q, qdot, t = self._args("q", q, "qdot", qdot, t)
        return self._evaluator(q, qdot).acceleration(q, qdot, t)

    def momentum(self, q, qdot, t: float = 0.0) -> np.ndarray:
        """Canonical momentum ``p = dL/dqdot`` at ``(q, qdot, t)``."""
        q, qdot, t = self._args("q", q, "qdot", qdot, t)
        return self._evaluator(q, qdot).momentum(q, qdot, t)

    def velocity(self, q, p, t: float = 0.0) -> np.ndarray:
        """The velocity ``qdot`` with ``dL/dqdot(q, qdot, t) = p``: the inverse Legendre map.

        Exact (one linear solve) when ``L`` is quadratic in ``qdot``; Newton's method
        otherwise.

        Raises
        ------
        ValueError
            Wrong lengths, non-finite values, or a singular mass matrix.
        ConvergenceError
            If Newton's method does not converge (``L`` not quadratic in ``qdot``).
        """
        q, p, t = self._args("q", q, "p", p, t)
        return self._evaluator(q, np.zeros(self.n)).velocity(q, p, t)

    def hamiltonian(self, q, p, t: float = 0.0) -> float:
        """The Hamiltonian ``H(q, p, t) = p . qdot - L(q, qdot, t)`` at ``qdot =
        velocity(q, p, t)``.

        Raises
        ------
        ValueError, ConvergenceError
            As :meth:`velocity`.
        """
        q, p, t = self._args("q", q, "p", p, t)
        qdot = self._evaluator(q, np.zeros(self.n)).velocity(q, p, t)
        state = np.concatenate([q, qdot])
        # The native energy is p . qdot - L at the system's clock: a system of its own, so
        # that setting the clock changes nothing shared.
        at_t = self._system(state)
        at_t.reset(state, t)
        return at_t.energy(state)

    def canonical_derivatives(self, t: float, y) -> np.ndarray:
        """Hamilton's equations at the canonical state ``y = [q, p]``: ``[dq/dt, dp/dt] =
        [qdot(q, p, t), dL/dq(q, qdot(q, p, t), t)]`` (what ``implicit_midpoint`` integrates).

        Raises
        ------
        ValueError, ConvergenceError
            As :meth:`velocity`; ``y`` not of length ``2 n``.
        """
        t = as_scalar("t", t)
        y = as_vector("y", y, 2 * self.n)
        return self._evaluator(y[: self.n], np.zeros(self.n)).canonical_derivatives(t, y)

    # -- the Numba peer's names --------------------------------------------------------
    def acceleration_njit(self, q, qdot, t) -> np.ndarray:
        """Alias of :meth:`acceleration` under the Numba peer's name (``t`` required)."""
        return self.acceleration(q, qdot, t)

    def momentum_njit(self, q, qdot) -> np.ndarray:
        """Alias of :meth:`momentum` at ``t = 0`` under the Numba peer's name."""
        return self.momentum(q, qdot)

    def hamiltonian_njit(self, q, p, t) -> float:
        """Alias of :meth:`hamiltonian` under the Numba peer's name (``t`` required)."""
        return self.hamiltonian(q, p, t)

    def canonical_deriv_njit(self, t, y) -> np.ndarray:
        """Alias of :meth:`canonical_derivatives` under the Numba peer's name."""
        return self.canonical_derivatives(t, y)


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

    def _repr_fields(self) -> list[tuple[str, Any]]:
        return [("L", str(self.engine.L))] + super()._repr_fields()
