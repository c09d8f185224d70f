"""SymPy engines: users' own systems, written symbolically, integrated natively.

* ``LagrangianEngine(q, qdot, L)``: equations of motion from a Lagrangian;
* ``HamiltonianEngine(q, p, H)``: Hamilton's equations from a Hamiltonian (separable
  ``H = T(p) + V(q)`` detected, so ``yoshida4``/``verlet`` apply);
* ``ODEEngine(y, f)``: a first-order system ``dy/dt = f(t, y)``.

Each SymPy expression is translated **once**, at construction, into the Rust expression tree
``physicskit::classical::lagrangian::Expr`` (through its prefix S-expression form). From then
on everything runs in Rust, never calling back into Python: the Lagrangian engine
differentiates ``L`` by automatic differentiation; a Hamiltonian's derivatives are derived
symbolically in Rust and compiled, with ``f``, into straight-line programs. Jacobians (for
the implicit-midpoint Newton solve and for tangent dynamics) come from automatic
differentiation of the same programs. SymPy is only needed to build an engine.

What the Lagrangian engine evaluates, with ``M = d2L/dqdot2`` the mass matrix:

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
from collections.abc import Mapping
from typing import Any, Optional

import numpy as np

from .._native import as_scalar, as_vector, native
from ..core.base_system import (
    _EVERY_SAMPLE,
    HamiltonianSystem,
    LagrangianSystem,
    ODESystem,
    SimulationResult,
)

__all__ = ["LagrangianEngine", "HamiltonianEngine", "ODEEngine"]

_FUNCS = {
    "sin": "sin", "cos": "cos", "tan": "tan", "exp": "exp", "log": "ln",
    "sinh": "sinh", "cosh": "cosh", "tanh": "tanh", "asin": "asin", "acos": "acos",
    "atan": "atan", "Abs": "abs",
}


def _number(x: float, what: str = "the Lagrangian") -> str:
    if not math.isfinite(x):
        raise ValueError(f"{what} contains the non-finite number {x}")
    return repr(float(x))


def _symbols(name: str, values, sp) -> list:
    """``values`` as a non-empty list of distinct SymPy symbols (ValueError naming ``name``)."""
    if isinstance(values, sp.Symbol):
        values = [values]
    try:
        out = list(values)
    except TypeError:
        raise ValueError(f"{name} must be a sequence of sympy Symbols, got {values!r}") from None
    if not out:
        raise ValueError(f"{name} must not be empty")
    for v in out:
        if not isinstance(v, sp.Symbol):
            raise ValueError(f"{name} must hold sympy Symbols, got {v!r}")
    return out


def _resolve_params(params, exprs, sp) -> dict:
    """``params`` keyed by symbols (a name key is matched to the expressions' free symbol of
    that name); values converted by ``as_scalar`` (finite reals only)."""
    if params is None:
        params = {}
    if not isinstance(params, Mapping):
        raise ValueError(f"params must be a dict of symbol (or name) -> value, got {params!r}")
    by_name = {}
    for e in exprs:
        by_name.update({s.name: s for s in e.free_symbols if isinstance(s, sp.Symbol)})
    out = {}
    for key, value in params.items():
        sym = key if isinstance(key, sp.Symbol) else by_name.get(str(key), sp.Symbol(str(key)))
        out[sym] = as_scalar(f"params[{sym}]", value)
    return out


def _sympify(name: str, e, sp):
    """``e`` as a SymPy expression; strings (parsed by ``eval``), booleans and None are
    refused, so is anything SymPy does not make an expression of."""
    if e is None or isinstance(e, (str, bytes, bool, np.bool_)):
        raise ValueError(f"{name} must be a SymPy expression (or a real number), got {e!r}")
    if isinstance(e, (complex, np.generic, np.ndarray)) and np.iscomplexobj(e):
        raise ValueError(f"{name} is complex ({e!r}); pass a real expression")
    try:
        out = sp.sympify(e, strict=True)
    except (sp.SympifyError, TypeError, ValueError) as err:
        raise ValueError(f"{name} is not a SymPy expression: {err}") from None
    if not isinstance(out, sp.Expr):
        raise ValueError(f"{name} must be a SymPy expression, got {e!r}")
    return out


def _spec(family: str, expressions: list[str], params: dict, **extra: Any) -> dict[str, Any]:
    """An engine's systems as ``_core.ensemble`` takes them (with a ``state`` added): the
    family, the S-expressions, the parameters as ``(name, value)`` in the order the
    expressions index them (``param<j>``), and ``ndof`` or an ODE's ``energy``. Plain strings
    and floats, so it pickles without SymPy."""
    return {
        "family": family,
        "expressions": list(expressions),
        "params": [(str(k), float(v)) for k, v in params.items()],
        **extra,
    }


class _Translator:
    """SymPy expression -> prefix S-expression of ``Expr::parse``."""

    def __init__(self, sp, names: dict, declared: str = "a coordinate in q, a velocity in qdot, t, nor a key of params",
                 what: str = "the Lagrangian"):
        self.sp = sp
        self.names = names
        self.declared = declared
        self.what = what

    def __call__(self, e) -> str:
        sp = self.sp
        if e in self.names:
            return self.names[e]
        if isinstance(e, sp.Symbol):
            raise ValueError(f"{self.what}: symbol {e} is neither {self.declared}: declare it")
        if e is sp.pi:
            return "pi"
        if e is sp.E:
            return "(exp 1)"
        if isinstance(e, sp.Integer):
            if abs(int(e)) > 2**53:
                try:
                    return _number(float(int(e)), self.what)
                except OverflowError:
                    raise ValueError(f"{self.what} contains {e}, too large for a float") from None
            return str(int(e))
        if e.is_Number:
            if not e.is_real:
                raise ValueError(f"{self.what} must be real; found {e}")
            return _number(float(e), self.what)
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
                return f"(^ {self(base)} {_number(float(ex), self.what)})"
            return f"(^ {self(base)} {self(ex)})"
        if isinstance(e, sp.Function):
            name = type(e).__name__
            if name in _FUNCS and len(e.args) == 1:
                return f"({_FUNCS[name]} {self(e.args[0])})"
        if e.is_Number is False and e.is_constant() and e.free_symbols == set():
            value = complex(e.evalf())
            if value.imag == 0.0:
                return _number(value.real, self.what)
        raise ValueError(
            f"{self.what}: cannot translate {type(e).__name__} `{e}`: use +, *, powers, sin, "
            "cos, tan, exp, log, sqrt, sinh, cosh, tanh, asin, acos, atan, Abs"
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
        self.params = _resolve_params(params, [self.L], sp)
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

    def _native_spec(self) -> dict[str, Any]:
        """What builds this engine's systems natively, as plain data (``_core.ensemble`` builds
        one per member from it, on Dask workers too): see :func:`_spec`."""
        return _spec("lagrangian", [self.sexpr], self.params, ndof=self.n)

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

class HamiltonianEngine:
    """Native Hamilton's equations of a SymPy Hamiltonian ``H(q, p, t)``.

    ``dq/dt = dH/dp`` and ``dp/dt = -dH/dq`` are derived symbolically in Rust once and compiled;
    runs never call back into Python. When ``H = T(p) + V(q, t)`` with
    ``T = sum_i p_i**2 / (2 m_i)`` (+ a constant), detected from the terms of ``H``, the
    system is separable: ``yoshida4`` (the default) and ``verlet`` apply. Otherwise
    ``implicit_midpoint`` (the default then) and ``rk4`` do. Jacobians (force Jacobian, or
    the whole field's) come from automatic differentiation.

    Parameters
    ----------
    q : sequence of sympy.Symbol
        Generalized coordinates.
    p : sequence of sympy.Symbol
        Their conjugate momenta, in the same order.
    H : sympy.Expr
        The Hamiltonian.
    t : sympy.Symbol, optional
        The time symbol, if ``H`` depends explicitly on time.
    params : dict, optional
        Numerical values of the other symbols of ``H`` (keys: symbols or their names).

    Attributes
    ----------
    q, p, t, params, H
        As given; ``n`` is the number of degrees of freedom.
    separable : bool
        Whether the splitting methods apply (see above).
    mass_inv : numpy.ndarray or None
        ``1/m_i`` of a separable ``H`` (``d2H/dp_i2``), else None.
    sexpr : str
        The expression as handed to Rust.

    Raises
    ------
    ValueError
        If ``H`` uses an undeclared symbol or an unsupported function, if ``q`` and ``p``
        differ in length, or if a parameter value is not a finite real number.
    """

    def __init__(self, q, p, H: Any, t: Any = None, params: Optional[dict] = None):
        import sympy as sp

        self.q = _symbols("q", q, sp)
        self.p = _symbols("p", p, sp)
        if len(self.q) != len(self.p):
            raise ValueError(
                f"q and p must have equal lengths, got {len(self.q)} and {len(self.p)}"
            )
        self.n = len(self.q)
        if t is not None and not isinstance(t, sp.Symbol):
            raise ValueError(f"t must be a sympy Symbol or None, got {t!r}")
        self.t = t
        self.H = _sympify("H", H, sp)
        self.params = _resolve_params(params, [self.H], sp)
        names = {s: f"q{i}" for i, s in enumerate(self.q)}
        names.update({s: f"p{i}" for i, s in enumerate(self.p)})
        if t is not None:
            names[t] = "t"
        names.update({s: f"param{j}" for j, s in enumerate(self.params)})
        if len(names) != 2 * self.n + (t is not None) + len(self.params):
            raise ValueError("q, p, t and the keys of params must be distinct symbols")
        self._param_values = np.array(list(self.params.values()), dtype=np.float64)
        translate = _Translator(
            sp, names, "a coordinate in q, a momentum in p, t, nor a key of params", "H"
        )
        self.sexpr = translate(self.H)
        # One native system, kept for the engine's own evaluations (separability, masses,
        # Jacobians); every system() gets its own.
        self._probe = self._native_system(np.zeros(self.n), np.zeros(self.n))
        self.separable = bool(self._probe.separable)
        m = self._probe.mass_inv
        self.mass_inv = None if (m is None or not self.separable) else np.asarray(m)

    def _native_system(self, q0, p0):
        return native("expr_hamiltonian")(self.sexpr, self.n, self._param_values, q0, p0)

    def _native_spec(self) -> dict[str, Any]:
        """What builds this engine's systems natively, as plain data: see :func:`_spec`."""
        return _spec("hamiltonian", [self.sexpr], self.params, ndof=self.n)

    def system(self, q0, p0) -> "SymbolicHamiltonianSystem":
        """A :class:`~physicskit.classical.HamiltonianSystem` with this Hamiltonian, started at
        ``(q0, p0)``; it integrates fully natively."""
        return SymbolicHamiltonianSystem(self, q0, p0)

    def derivatives(self, t: float, state) -> np.ndarray:
        """``[dH/dp, -dH/dq]`` at ``(t, state)``, ``state = [q, p]``."""
        return self._probe.derivatives(as_scalar("t", t), as_vector("state", state, 2 * self.n))

    def jacobian(self, t: float, state) -> np.ndarray:
        """The Jacobian of :meth:`derivatives` at ``(t, state)``, shape ``(2n, 2n)``, by
        automatic differentiation."""
        return native("system_jacobian")(
            self._probe, as_scalar("t", t), as_vector("state", state, 2 * self.n)
        )

    def force(self, q, t: float = 0.0) -> np.ndarray:
        """``-dV/dq`` at ``(q, t)`` of a separable ``H`` (NotImplementedError otherwise, as
        :meth:`HamiltonianSystem.force`)."""
        return self._probe.force(as_vector("q", q, self.n), as_scalar("t", t))

    def force_jacobian(self, q, t: float = 0.0) -> np.ndarray:
        """``dF/dq = -d2V/dq2`` at ``(q, t)`` of a separable ``H``, shape ``(n, n)``, by
        automatic differentiation (NotImplementedError if ``H`` is not separable)."""
        return native("force_jacobian")(self._probe, as_vector("q", q, self.n), as_scalar("t", t))


class SymbolicHamiltonianSystem(HamiltonianSystem):
    """A HamiltonianSystem defined by a :class:`HamiltonianEngine`, integrated natively.

    ``integrate`` defaults to ``yoshida4`` for a separable ``H``, else ``implicit_midpoint``.
    The energy is ``H``.

    Parameters
    ----------
    engine : HamiltonianEngine
        The Hamiltonian.
    q0, p0 : array-like, shape (engine.n,)
        Initial positions and momenta.
    """

    def __init__(self, engine: HamiltonianEngine, q0, p0):
        if not isinstance(engine, HamiltonianEngine):
            raise ValueError(f"engine must be a HamiltonianEngine, got {type(engine).__name__}")
        super().__init__(as_vector("q0", q0, engine.n), as_vector("p0", p0, engine.n))
        self.engine = engine
        self.separable = engine.separable
        if engine.mass_inv is not None:
            self.mass_inv = engine.mass_inv.copy()
        self._native = engine._native_system(self.q, self.p)

    def kinetic_energy(self, p) -> float:
        """``sum_i p_i**2 / (2 m_i)`` of a separable ``H``; NaN if ``H`` does not split."""
        return self._native.kinetic_energy(as_vector("p", p, self.ndof))

    def potential_energy(self, q) -> float:
        """``V(q)`` (plus any constant of ``T``) of a separable ``H``; NaN if ``H`` does not
        split."""
        return self._native.potential_energy(as_vector("q", q, self.ndof))

    def integrate(self, t_span, dt: float, method: Optional[str] = None) -> SimulationResult:
        """Integrate like :meth:`HamiltonianSystem.integrate`; ``method`` defaults to
        ``"yoshida4"`` for a separable ``H``, else ``"implicit_midpoint"``."""
        return self._integrate(t_span, dt, method, _EVERY_SAMPLE)


class ODEEngine:
    """A native first-order system ``dy/dt = f(t, y)`` from SymPy expressions.

    ``f`` is compiled once into a straight-line program (subexpressions shared between
    components computed once); runs never call back into Python. The Jacobian ``df/dy`` comes
    from automatic differentiation, so ``implicit_midpoint`` (the default) uses Newton's
    method.

    Parameters
    ----------
    y : sequence of sympy.Symbol
        The state variables.
    f : sequence of sympy.Expr
        ``dy_i/dt``, one per variable, in the same order.
    t : sympy.Symbol, optional
        The time symbol, if ``f`` depends explicitly on time.
    params : dict, optional
        Numerical values of the other symbols (keys: symbols or their names).
    energy : sympy.Expr, optional
        A quantity reported as the energy of each sample (e.g. a conserved quantity). Without
        it, ``result.energy`` is None and ``energy()`` is NaN.

    Attributes
    ----------
    y, f, t, params, energy_expr
        As given; ``n`` is the dimension.
    sexprs : list of str
        The components as handed to Rust.

    Raises
    ------
    ValueError
        If an expression uses an undeclared symbol or an unsupported function, if ``f`` and
        ``y`` differ in length, or if a parameter value is not a finite real number.
    """

    def __init__(self, y, f, t: Any = None, params: Optional[dict] = None,
                 energy: Any = None):
        import sympy as sp

        self.y = _symbols("y", y, sp)
        try:
            if isinstance(f, (str, bytes)):
                raise TypeError
            f = list(f)
        except TypeError:
            raise ValueError(
                f"f must be a sequence of expressions, one per variable, got {f!r}"
            ) from None
        self.f = [_sympify(f"f[{i}]", e, sp) for i, e in enumerate(f)]
        self.n = len(self.y)
        if len(self.f) != self.n:
            raise ValueError(f"f has length {len(self.f)}, expected {self.n} (one per variable in y)")
        if t is not None and not isinstance(t, sp.Symbol):
            raise ValueError(f"t must be a sympy Symbol or None, got {t!r}")
        self.t = t
        self.energy_expr = None if energy is None else _sympify("energy", energy, sp)
        exprs = self.f + ([] if self.energy_expr is None else [self.energy_expr])
        self.params = _resolve_params(params, exprs, sp)
        names = {s: f"y{i}" for i, s in enumerate(self.y)}
        if t is not None:
            names[t] = "t"
        names.update({s: f"param{j}" for j, s in enumerate(self.params)})
        if len(names) != self.n + (t is not None) + len(self.params):
            raise ValueError("y, t and the keys of params must be distinct symbols")
        self._param_values = np.array(list(self.params.values()), dtype=np.float64)
        declared = "a variable in y, t, nor a key of params"
        self.sexprs = [_Translator(sp, names, declared, f"f[{i}]")(e) for i, e in enumerate(self.f)]
        self._energy_sexpr = None if self.energy_expr is None else _Translator(
            sp, names, declared, "energy"
        )(self.energy_expr)
        self._probe = self._native_system(np.zeros(self.n))

    def _native_system(self, y0):
        return native("expr_ode")(self.sexprs, self._param_values, y0, self._energy_sexpr)

    def _native_spec(self) -> dict[str, Any]:
        """What builds this engine's systems natively, as plain data: see :func:`_spec`."""
        return _spec("ode", self.sexprs, self.params, energy=self._energy_sexpr)

    def system(self, y0) -> "SymbolicODESystem":
        """An :class:`~physicskit.classical.ODESystem` with this right-hand side, started at
        ``y0``; it integrates fully natively."""
        return SymbolicODESystem(self, y0)

    def derivatives(self, t: float, state) -> np.ndarray:
        """``f(t, state)``."""
        return self._probe.derivatives(as_scalar("t", t), as_vector("state", state, self.n))

    def jacobian(self, t: float, state) -> np.ndarray:
        """``df/dy`` at ``(t, state)``, shape ``(n, n)``, by automatic differentiation."""
        return native("system_jacobian")(
            self._probe, as_scalar("t", t), as_vector("state", state, self.n)
        )


class SymbolicODESystem(ODESystem):
    """An ODESystem defined by an :class:`ODEEngine`, integrated natively.

    Parameters
    ----------
    engine : ODEEngine
        The right-hand side.
    y0 : array-like, shape (engine.n,)
        Initial state.
    """

    def __init__(self, engine: ODEEngine, y0):
        if not isinstance(engine, ODEEngine):
            raise ValueError(f"engine must be an ODEEngine, got {type(engine).__name__}")
        super().__init__(as_vector("y0", y0, engine.n))
        self.engine = engine
        self._native = engine._native_system(self.state)

    def energy(self, state: Optional[np.ndarray] = None) -> float:
        """The engine's ``energy`` expression at ``state`` (default: ``self.state``); NaN if
        it has none."""
        return self._native.energy(self._state_arg(state))
