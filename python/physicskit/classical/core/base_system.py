"""Base classes of every system and the ``SimulationResult`` container.

A built-in system keeps a native Rust object in ``self._native``: every numeric method
(``derivatives``, ``energy``, ``force``, ``integrate`` ...) runs in Rust. A system written in
Python (a subclass that implements ``kinetic_energy``/``potential_energy``/``force``, or
``derivatives``) has ``_native = None`` and is integrated by the same Rust integrators, which
call its Python methods back at each step.

``state`` and ``t`` are plain instance attributes, as in the spec: ``integrate`` starts from
them (so editing ``system.state`` in place between calls works) and leaves them at the final
sample.

Beyond the spec, every system has ``integrate_sampled`` (stride, final-state-only and
energy-free runs, for trajectories too large to store whole); the spec's ``integrate`` keeps its
exact signature and stores every sample.
"""

from __future__ import annotations

import inspect
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import Any, NamedTuple, Optional

import numpy as np

from .._native import (
    _core,
    as_array,
    as_flag,
    as_int,
    as_real,
    as_scalar,
    as_t_span,
    as_vector,
)

#: Catalogue name -> its ``python`` path (``"kepler"`` -> ``"KeplerSystem.from_orbital_elements"``),
#: read from the catalogue on the first repr.
_CONSTRUCTORS: dict[str, str] = {}

__all__ = [
    "SimulationResult",
    "DynamicalSystem",
    "ODESystem",
    "HamiltonianSystem",
    "LagrangianSystem",
]


def _float_array(name: str, value: Any, ndim: int) -> np.ndarray:
    """``value`` as a float64 array of ``ndim`` dimensions: the array itself when it already is
    one (C-contiguous), else a converted copy, or ValueError naming ``name``."""
    if not (
        isinstance(value, np.ndarray)
        and value.dtype == np.float64
        and value.flags.c_contiguous
    ):
        value = np.ascontiguousarray(as_array(name, value))
    if value.ndim != ndim:
        raise ValueError(f"{name} must have {ndim} dimension(s), got shape {value.shape}")
    return value


@dataclass(repr=False)
class SimulationResult:
    """Output of ``integrate``: the sampled trajectory and its diagnostics.

    Every array is a C-contiguous float64 numpy array. ``t``, ``y`` and ``energy`` own memory
    moved from Rust (no copy); ``q`` and ``p`` are split off ``y`` when first read (one copy
    each, then kept), so a run writes each state once. With
    ``n_steps = round((t1 - t0) / dt)`` there are ``n_steps + 1`` samples.

    ``repr(result)`` is a one-line summary (method, steps, span, shapes, largest relative
    energy error); in a notebook the result shows as a table with a sparkline of the energy
    error (``_repr_html_``).
    """

    t: np.ndarray
    """Sample times, shape ``(n_steps + 1,)``."""
    y: np.ndarray
    """Raw stacked states, shape ``(n_steps + 1, state_dim)``, in the system's layout."""
    q: Optional[np.ndarray] = None
    """Generalized positions, shape ``(n_steps + 1, ndof)``; None for general ODE systems."""
    p: Optional[np.ndarray] = None
    """Canonical momenta (Hamiltonian) or qdot (Lagrangian), shape ``(n_steps + 1, ndof)``."""
    energy: Optional[np.ndarray] = None
    """Total energy at each sample, shape ``(n_steps + 1,)``."""
    method: str = ""
    """Name of the integrator used, e.g. ``"yoshida4"``."""
    extra: dict = field(default_factory=dict)
    """Additional diagnostics (``n_steps``, ``dt``, force or solver evaluation counts ...;
    ``stride`` after ``integrate_sampled``)."""

    def __post_init__(self) -> None:
        """Checks a result built by hand as the integrators' results are: ``t`` a vector of
        finite, non-decreasing times; ``y`` one row of finite-or-not states per time; ``energy``
        one value per time; ``q`` and ``p`` both or neither, of one shape, one row per time,
        whose widths add up to ``y``'s. Arrays already float64 and C-contiguous (what the
        integrators return) are kept without a copy; others are converted or refused by
        :func:`~physicskit.classical._native.as_array`'s rules."""
        if self.t is None or self.y is None:
            raise ValueError("SimulationResult needs t and y (got None)")
        t = _float_array("t", self.t, 1)
        n = t.shape[0]
        if not np.all(np.isfinite(t)):
            raise ValueError("t contains NaN or infinity")
        if n > 1 and not np.all(np.diff(t) >= 0):
            raise ValueError("t must not decrease")
        y = _float_array("y", self.y, 2)
        if y.shape[0] != n:
            raise ValueError(f"y has {y.shape[0]} rows for {n} times; expected one row per time")
        self.t, self.y = t, y
        if self.energy is not None:
            energy = _float_array("energy", self.energy, 1)
            if energy.shape[0] != n:
                raise ValueError(f"energy has {energy.shape[0]} values for {n} times")
            self.energy = energy
        # A split-on-access result keeps q and p out of its fields until they are read.
        given = {name: self.__dict__.get(name) for name in ("q", "p")}
        if (given["q"] is None) != (given["p"] is None):
            raise ValueError("q and p go together: pass both or neither")
        if given["q"] is not None:
            q = _float_array("q", given["q"], 2)
            p = _float_array("p", given["p"], 2)
            if q.shape != p.shape:
                raise ValueError(f"q has shape {q.shape} and p {p.shape}; they must match")
            if q.shape[0] != n:
                raise ValueError(f"q and p have {q.shape[0]} rows for {n} times")
            if 2 * q.shape[1] != y.shape[1]:
                raise ValueError(
                    f"q and p have {q.shape[1]} columns each, y has {y.shape[1]}: y is [q, p]"
                )
            self.q, self.p = q, p
        if not isinstance(self.method, str):
            raise ValueError(f"method must be a string, got {self.method!r}")
        if not isinstance(self.extra, dict):
            raise ValueError(f"extra must be a dict, got {type(self.extra).__name__}")

    def plot(self, system: Any = None, **kwargs: Any) -> Any:
        """``q(t)``, ``p(t)`` (or ``qdot``) and the relative energy error on a log scale, one
        figure; ``system`` labels the axes with its units. Needs matplotlib
        (``pip install physicskit[plot]``); see ``physicskit.classical.plotting.plot_result``.
        """
        from ..plotting import plot_result

        return plot_result(self, system, **kwargs)

    # The display and progress modules are imported on first use: `import physicskit.classical`
    # stays as fast as it was (tests/test_sampling.py times the first call).
    def __repr__(self) -> str:
        from . import display

        return display.result_repr(self)

    def _repr_html_(self) -> str:
        """The notebook display: method, steps, span, shapes, the largest energy error
        (relative to the first sample's energy; absolute if that is zero) and an SVG
        sparkline of the error over the run."""
        from . import display

        return display.result_html(self)


class _SplitOnAccess(SimulationResult):
    """A :class:`SimulationResult` whose ``q`` and ``p`` are split off ``y`` on first access.

    The native integrators store the stacked states once; ``q`` and ``p`` (C-contiguous
    float64 copies of the two halves of ``y``) are made when first read and then kept. This
    halves the memory a run writes: storing three arrays made a 200-pendulum swarm spend more
    time in first-touch page faults than in stepping.
    """

    def __init__(self, *args, ndof: int, **kwargs):
        self._ndof = ndof
        super().__init__(*args, **kwargs)

    def _half(self, name: str, start: int) -> np.ndarray:
        value = self.__dict__.get(name)
        if value is None:
            value = np.ascontiguousarray(self.y[:, start : start + self._ndof])
            self.__dict__[name] = value
        return value

    @property
    def q(self) -> np.ndarray:
        """Generalized positions, shape ``(n_samples, ndof)`` (split off ``y`` on first use)."""
        return self._half("_q", 0)

    @q.setter
    def q(self, value) -> None:
        self.__dict__["_q"] = value

    @property
    def p(self) -> np.ndarray:
        """Momenta (Hamiltonian) or qdot (Lagrangian), shape ``(n_samples, ndof)``."""
        return self._half("_p", self._ndof)

    @p.setter
    def p(self, value) -> None:
        self.__dict__["_p"] = value


def _native_result(
    t: np.ndarray,
    y: np.ndarray,
    energy: Optional[np.ndarray],
    method: str,
    extra: dict,
    ndof: Optional[int],
) -> SimulationResult:
    """The result of a native run, built without ``SimulationResult.__post_init__``'s checks:
    the native side makes ``t`` from finite, increasing steps and ``y`` and ``energy`` one row
    per time, all float64 and C-contiguous, so checking them again would only add passes over
    every sample (on the cheapest systems, a measurable part of the run). Results built by
    hand are checked."""
    cls = _SplitOnAccess if ndof else SimulationResult
    result = cls.__new__(cls)
    fields: dict[str, Any] = {"t": t, "y": y, "energy": energy, "method": method, "extra": extra}
    if ndof:
        fields["_ndof"] = ndof
    else:
        fields.update(q=None, p=None)
    result.__dict__.update(fields)
    return result


class _Sampling(NamedTuple):
    """What a run stores, and an adaptive method's tolerances (the keyword arguments of the
    native integrators)."""

    stride: int = 1
    final_only: bool = False
    energy: bool = True
    progress: Any = None
    """``progress(step, n_steps)``, called every few thousand steps, or None."""
    rtol: Optional[float] = None
    atol: Optional[float] = None
    max_steps: Optional[int] = None


_EVERY_SAMPLE = _Sampling()


def _as_stride(value) -> int:
    return as_int("stride", value, minimum=1)


def _readonly_message(system, name: str) -> str:
    cls = type(system).__name__
    return (
        f"{cls}.{name} is read-only: the system was built from it; construct a new {cls} "
        f"with {name}=... instead"
    )


class DynamicalSystem(ABC):
    """Any system whose state vector evolves in time; the root of the hierarchy.

    Parameters
    ----------
    state0 : array-like
        Initial state vector (finite numbers).
    """

    _native: Any = None

    def __init__(self, state0):
        self.state = as_vector("state0", state0)
        self.t = 0.0

    def __setattr__(self, name: str, value: Any) -> None:
        # A built-in system's parameters (``ProjectileMotion.g`` ...) are read-only: its
        # numerics were built from them, so a new value would be silently ignored.
        if name in self.__dict__.get("_readonly", ()):
            raise AttributeError(_readonly_message(self, name))
        object.__setattr__(self, name, value)

    def __delattr__(self, name: str) -> None:
        if name in self.__dict__.get("_readonly", ()):
            raise AttributeError(_readonly_message(self, name))
        object.__delattr__(self, name)

    @abstractmethod
    def derivatives(self, t: float, state: np.ndarray) -> np.ndarray:
        """Return d(state)/dt at ``(t, state)``."""

    @abstractmethod
    def energy(self, state: Optional[np.ndarray] = None) -> float:
        """Return the total mechanical energy of ``state`` (default: ``self.state``)."""

    @abstractmethod
    def integrate(self, t_span, dt: float, method: str = "rk4") -> SimulationResult:
        """Integrate from ``self.state`` at ``t_span[0]`` to ``t_span[1]`` with fixed step ``dt``.

        Returns the full trajectory as a :class:`SimulationResult` and leaves ``state`` and
        ``t`` at its last sample. Valid ``method`` names depend on the family.
        """

    def integrate_sampled(
        self, t_span, dt: float, method: Optional[str] = None, *, stride: int = 1,
        final_only: bool = False, energy: bool = True, progress: bool = False,
        rtol: Optional[float] = None, atol: Optional[float] = None,
        max_steps: Optional[int] = None,
    ) -> SimulationResult:
        """Integrate like :meth:`integrate`, storing only some samples (not in the spec).

        For runs whose full trajectory is too large to keep, e.g. a million-pendulum
        ``PendulumSwarm``: ``integrate`` stores ``(n_steps + 1) x state_dim`` values (and
        refuses, with ``ValueError``, a run that would not fit in memory); this stores
        ``n_steps // stride + 1`` rows (two with ``final_only``). The steps taken, and therefore
        every stored row, are exactly those of ``integrate``: the rows equal the corresponding
        rows of the full run bit for bit.

        Parameters
        ----------
        t_span, dt
            As for :meth:`integrate`.
        method : str, optional
            Integrator name; ``None`` (default) means the default of this class's ``integrate``.
        stride : int, keyword-only
            Keep every ``stride``-th step (steps ``0, stride, 2*stride, ...``) and always the
            final step. ``1`` (default) keeps every step.
        final_only : bool, keyword-only
            Keep only the initial and the final state (two rows; one if ``n_steps == 0``).
            Cannot be combined with ``stride > 1``.
        energy : bool, keyword-only
            Compute the energy of each stored sample (default). ``False`` leaves
            ``result.energy`` as ``None`` and saves one energy evaluation per stored sample.
        progress : bool, keyword-only
            Show a progress bar while the run goes on: ``tqdm`` (a widget in Jupyter) if it is
            installed, otherwise a one-line text bar on standard error. Updated every few
            thousand steps (every 128 for systems written in Python); costs nothing
            measurable. Default ``False``.
        rtol, atol : float, keyword-only, optional
            Relative and absolute error tolerances of an adaptive method (``"dop853"``), finite
            and > 0; ``None`` (default) means ``1e-10`` and ``1e-12``. An adaptive method
            chooses its own steps to meet them and ``dt`` is the spacing of the stored samples,
            which it interpolates from its steps (the final sample is a step's result, exactly
            at ``t1``); ``result.extra`` then also holds ``accepted_steps`` and
            ``rejected_steps``. A fixed-step method has no tolerances: giving either with one
            is a ``ValueError``.
        max_steps : int, keyword-only, optional
            The most steps, accepted and rejected, an adaptive method may attempt in this run
            before it stops with ``ConvergenceError`` (an integer >= 1; ``None``, the default,
            means ten million): a guard against runs that would not end, to raise for a long
            span at tight tolerances or to lower for a quick look. Like ``rtol`` and ``atol``,
            a ``ValueError`` with a fixed-step method, whose steps ``dt`` sets.

        Returns
        -------
        SimulationResult
            As from :meth:`integrate`, with ``t``, ``y``, ``q``, ``p`` and ``energy`` holding
            the stored samples only, and ``extra["stride"]``: the number of steps between
            stored rows (``n_steps`` for ``final_only``; the last gap may be shorter). ``state``
            and ``t`` are left at the final state, as by ``integrate``.

        Raises
        ------
        ValueError
            ``stride`` not an integer >= 1, ``stride > 1`` with ``final_only=True``, a
            non-boolean flag, ``rtol`` or ``atol`` not a finite number > 0, ``max_steps`` not
            an integer >= 1, any of the three given with a fixed-step method, every ``ValueError`` of ``integrate``, and a run whose stored
            samples would not fit in memory (checked before anything is allocated).
        ConvergenceError
            An adaptive method found no step meeting its tolerances (the step size fell to the
            rounding of ``t``, or the right-hand side returned NaN) or spent ``max_steps``,
            naming ``t``.
        NotImplementedError
            For a Python subclass of ``DynamicalSystem`` itself that implements its own
            ``integrate`` (there is no integrator to pass the sampling to). Subclasses of
            ``HamiltonianSystem``, ``LagrangianSystem`` and ``ODESystem`` written in Python are
            supported: the Rust integrators calling them back honour the sampling too.
        """
        stride = _as_stride(stride)
        final_only = as_flag("final_only", final_only)
        energy = as_flag("energy", energy)
        progress = as_flag("progress", progress)
        rtol = None if rtol is None else as_scalar("rtol", rtol)
        atol = None if atol is None else as_scalar("atol", atol)
        max_steps = None if max_steps is None else as_int("max_steps", max_steps, minimum=1)
        if final_only and stride > 1:
            raise ValueError(
                f"stride={stride} and final_only=True cannot be combined: pass one or the other"
            )
        if method is None:
            method = self._default_method()
        reporter = None
        if progress:
            from .progress import progress_reporter

            reporter = progress_reporter()
        sampling = _Sampling(stride, final_only, energy, reporter, rtol, atol, max_steps)
        try:
            result = self._integrate(t_span, dt, method, sampling)
        except BaseException:
            if reporter is not None:
                reporter.close(None)
            raise
        if reporter is not None:
            reporter.close(int(result.extra.get("n_steps", len(result.t) - 1)))
        if final_only:
            n_steps = int(result.extra.get("n_steps", len(result.t) - 1))
            result.extra["stride"] = max(n_steps, 1)
        else:
            result.extra["stride"] = stride
        return result

    def __repr__(self) -> str:
        """``ClassName(parameter=value, ...)``: a built-in system's catalogue parameters as
        the constructor that takes them takes them (``KeplerSystem.from_orbital_elements(a=...,
        e=...)`` for a system built by that classmethod; with ``t`` and ``state`` once it has
        moved on), other systems' ``ndof``, ``t`` and ``state``."""
        from . import display

        try:
            return display.format_call(self._repr_name(), self._repr_fields())
        except Exception:  # noqa: BLE001  (a repr must not raise)
            return object.__repr__(self)

    def _repr_name(self) -> str:
        """The catalogue's ``python`` path of the entry the system was built from, when that
        entry's class is this class (a user's subclass shows its own name)."""
        name = type(self).__name__
        native = getattr(self._native, "name", None)
        if native is None:
            return name
        if not _CONSTRUCTORS:
            _CONSTRUCTORS.update((e["name"], e["python"]) for e in _core.catalog() if e["python"])
        path = _CONSTRUCTORS.get(native)
        return path if path is not None and path.partition(".")[0] == name else name

    def _repr_fields(self) -> list[tuple[str, Any]]:
        """The ``(name, value)`` pairs :meth:`__repr__` shows; subclasses may extend them."""
        params = getattr(self._native, "params", None)
        fields: list[tuple[str, Any]] = []
        if params:
            fields = [(k, v) for k, v in params.items() if v is not None]
            if self.t == 0.0:
                return fields
        elif getattr(self, "ndof", 0):
            fields.append(("ndof", getattr(self, "ndof")))
        return fields + [("t", self.t), ("state", self.state)]

    def reset(self, state0=None, t0: float = 0.0):
        """Set the clock to ``t0`` and, if given, the state to ``state0``; return the state."""
        t0 = as_scalar("t0", t0)
        if state0 is not None:
            self.state = as_vector("state0", state0, len(self.state))
        self.t = t0
        return self.state

    # -- helpers for subclasses ---------------------------------------------------------
    def _default_method(self) -> Optional[str]:
        """The ``method`` default of this class's ``integrate`` (None: the native default)."""
        try:
            default = inspect.signature(type(self).integrate).parameters["method"].default
        except (KeyError, TypeError, ValueError):
            default = inspect.Parameter.empty
        return None if default is inspect.Parameter.empty else default

    def _integrate(self, t_span, dt, method, sampling: _Sampling) -> SimulationResult:
        """The run behind ``integrate`` and ``integrate_sampled``; each family overrides it."""
        raise NotImplementedError(
            f"{type(self).__name__} subclasses DynamicalSystem directly and defines its own "
            "integrate, so integrate_sampled cannot pass it a sampling; subclass "
            "HamiltonianSystem, LagrangianSystem or ODESystem instead, or call integrate"
        )

    def _state_arg(self, state) -> np.ndarray:
        if state is None:
            return as_vector("state", self.state, finite=False)
        # Evaluating a non-finite state is allowed (it yields NaN); only the length is checked.
        return as_vector("state", state, len(self.state), finite=False)

    def _finish(self, parts, ndof: Optional[int] = None) -> SimulationResult:
        """Builds the result from the native tuple ``(t, y, ndof, energy, method, extra)`` and
        moves the system to its last sample. Where ``ndof`` is set (by the native side, or by
        the caller for a run the native side saw as a plain ODE), ``q`` and ``p`` are split off
        ``y`` lazily."""
        t, y, native_ndof, energy, method, extra = parts
        ndof = native_ndof if ndof is None else ndof
        result = _native_result(t, y, energy, method, extra, ndof)
        self.state = result.y[-1].copy()
        self.t = float(result.t[-1])
        return result

    def _run_native(self, t_span, dt, method, sampling: _Sampling) -> SimulationResult:
        t_span, dt, t, state = self._run_inputs(t_span, dt, len(self.state))
        parts = self._native.integrate(state, t, t_span, dt, method, **sampling._asdict())
        return self._finish(parts)

    def _run_inputs(self, t_span, dt, state_len: int):
        """``(t_span, dt, t, state)`` of a run, converted and checked (ValueError naming the
        argument: ``self.state`` and ``self.t`` are plain attributes a user may have set to
        anything, a complex array included)."""
        return (
            as_t_span(t_span),
            as_scalar("dt", dt),
            as_scalar("t", self.t),
            as_vector("state", self.state, state_len),
        )

    def _run_callbacks(self, run, state: np.ndarray, t: float) -> SimulationResult:
        """``run()``, a run whose right-hand side calls this object's Python methods back,
        restoring ``state`` and ``t`` if it fails: a callback may have reassigned
        ``self.state`` (or ``self.t``) before the run was refused or raised, which must not
        leave the object changed by a call that did not happen."""
        try:
            parts = run()
        except BaseException:
            self.state, self.t = state.copy(), t
            raise
        return parts


class HamiltonianSystem(DynamicalSystem):
    """Canonical Hamiltonian system ``H(q, p, t)`` with state ``[q_1..q_n, p_1..p_n]``.

    To define one in Python, subclass it and implement ``kinetic_energy(p)`` and
    ``potential_energy(q)``; for a separable ``H = T(p) + V(q)`` (``separable = True``)
    also ``force(q, t)`` returning ``-dV/dq`` and set ``mass_inv`` (``dq/dt = mass_inv * p``);
    for a non-separable one set ``separable = False`` and override ``derivatives``. Every
    method that applies then works: ``yoshida4``/``verlet`` (separable only), ``rk4`` and
    ``implicit_midpoint``.

    Parameters
    ----------
    q0, p0 : array-like, shape (ndof,)
        Initial positions and momenta.
    """

    ndof: int = 0
    """Number of degrees of freedom, inferred from ``q0``."""
    separable: bool = True
    """Whether ``H = T(p) + V(q)``, which enables the ``verlet``/``yoshida4`` integrators."""
    mass_inv = 1.0
    """``1/m`` per coordinate (float or array); ``dq/dt = mass_inv * p``."""

    def __init__(self, q0, p0):
        q0 = as_vector("q0", q0)
        p0 = as_vector("p0", p0, len(q0))
        self.ndof = len(q0)
        super().__init__(np.concatenate([q0, p0]))

    @property
    def q(self) -> np.ndarray:
        """Generalized positions: the first ``ndof`` entries of ``state``."""
        return self.state[: self.ndof]

    @property
    def p(self) -> np.ndarray:
        """Canonical momenta: the last ``ndof`` entries of ``state``."""
        return self.state[self.ndof :]

    @staticmethod
    def split(state: np.ndarray, ndof: int):
        """Split a stacked ``[q, p]`` vector into ``(q, p)``, each of length ``ndof``."""
        state = np.asarray(state)
        return state[:ndof], state[ndof:]

    @abstractmethod
    def kinetic_energy(self, p: np.ndarray) -> float:
        """Return the kinetic energy ``T(p)``."""

    @abstractmethod
    def potential_energy(self, q: np.ndarray) -> float:
        """Return the potential energy ``V(q)``."""

    def force(self, q: np.ndarray, t: float = 0.0) -> np.ndarray:
        """Return ``-dV/dq`` at ``(q, t)``.

        Raises
        ------
        NotImplementedError
            If the system is not separable (or a Python subclass did not define it).
        """
        if self._native is not None:
            return self._native.force(as_vector("q", q, self.ndof), as_scalar("t", t))
        raise NotImplementedError(
            f"{type(self).__name__} does not define force(q, t); separable systems must"
        )

    def _qp(self, q, p):
        q = self.q if q is None else q
        p = self.p if p is None else p
        return as_vector("q", q, self.ndof), as_vector("p", p, self.ndof)

    def _mass_inv_vector(self) -> np.ndarray:
        m = as_array("mass_inv", self.mass_inv)
        try:
            m = np.broadcast_to(m, (self.ndof,))
        except ValueError:
            raise ValueError(
                f"mass_inv must be a float or an array of length ndof={self.ndof}"
            ) from None
        return as_vector("mass_inv", m, self.ndof)

    def derivatives(self, t: float, state: np.ndarray) -> np.ndarray:
        """Return ``d[q, p]/dt`` at ``(t, state)``: ``[mass_inv * p, force(q, t)]`` when separable."""
        state = as_vector("state", state, 2 * self.ndof)
        if self._native is not None:
            return self._native.derivatives(as_scalar("t", t), state)
        if not self.separable:
            raise NotImplementedError(
                f"{type(self).__name__} is not separable: it must override derivatives(t, state)"
            )
        q, p = self.split(state, self.ndof)
        force = as_vector("force(q, t)", self.force(q, t), self.ndof, finite=False)
        return np.concatenate([self._mass_inv_vector() * p, force])

    def energy(self, state: Optional[np.ndarray] = None) -> float:
        """Return ``H = T(p) + V(q)`` of ``state`` (default: ``self.state``)."""
        state = self._state_arg(state)
        if self._native is not None:
            return self._native.energy(state)
        q, p = self.split(state, self.ndof)
        # The package's converter, not float(): a callback returning 10**400 or a complex
        # number is a ValueError naming the callback and the value, not an OverflowError.
        kinetic = as_real("value returned by kinetic_energy(p)", self.kinetic_energy(p))
        return kinetic + as_real("value returned by potential_energy(q)", self.potential_energy(q))

    def integrate(self, t_span, dt: float, method: str = "yoshida4") -> SimulationResult:
        """Integrate with fixed step ``dt`` over ``t_span = (t0, t1)``.

        ``method`` is one of ``"yoshida4"`` (default), ``"verlet"`` (both need
        ``separable``), ``"rk4"``, ``"implicit_midpoint"``. Returns the ``(q, p)`` trajectory
        and the energy at every sample.
        """
        return self._integrate(t_span, dt, method, _EVERY_SAMPLE)

    def _integrate(self, t_span, dt, method, sampling: _Sampling) -> SimulationResult:
        if self._native is not None:
            return self._run_native(t_span, dt, method, sampling)
        t_span, dt, t, state = self._run_inputs(t_span, dt, 2 * self.ndof)
        mass_inv = self._mass_inv_vector()
        parts = self._run_callbacks(
            lambda: _core.integrate_hamiltonian(
                self, state, t, t_span, dt, method, self.ndof, bool(self.separable), mass_inv,
                **sampling._asdict(),
            ),
            state,
            t,
        )
        return self._finish(parts)


class LagrangianSystem(DynamicalSystem):
    """System defined by a Lagrangian ``L(q, qdot, t)``, state ``[q_1..q_n, qdot_1..qdot_n]``.

    Built-in systems derive their equations of motion natively (from a Rust Lagrangian or a
    :class:`~physicskit.classical.utils.symbolic.LagrangianEngine`). ``implicit_midpoint``
    (default) integrates the canonical ``(q, p)`` form and is symplectic even when the mass
    matrix depends on ``q``; ``rk4`` integrates ``(q, qdot)`` directly.

    A Python subclass may instead set ``self.engine`` to a ``LagrangianEngine`` (then it runs
    fully natively), or implement ``acceleration(q, qdot, t)`` and ``energy(state)``; it is
    then integrated in ``(q, qdot)`` form by the Rust integrators calling back into Python.

    Parameters
    ----------
    q0, qdot0 : array-like, shape (ndof,)
        Initial generalized positions and velocities.
    """

    ndof: int = 0
    """Number of degrees of freedom, inferred from ``q0``."""

    def __init__(self, q0, qdot0):
        q0 = as_vector("q0", q0)
        qdot0 = as_vector("qdot0", qdot0, len(q0))
        self.ndof = len(q0)
        super().__init__(np.concatenate([q0, qdot0]))

    @property
    def q(self) -> np.ndarray:
        """Generalized positions: the first ``ndof`` entries of ``state``."""
        return self.state[: self.ndof]

    @property
    def qdot(self) -> np.ndarray:
        """Generalized velocities: the last ``ndof`` entries of ``state``."""
        return self.state[self.ndof :]

    @staticmethod
    def split(state: np.ndarray, ndof: int):
        """Split a stacked ``[q, qdot]`` vector into ``(q, qdot)``, each of length ``ndof``."""
        state = np.asarray(state)
        return state[:ndof], state[ndof:]

    def _engine_native(self):
        if self._native is not None:
            return self._native
        engine = getattr(self, "engine", None)
        if engine is not None and hasattr(engine, "_system"):
            self._native = engine._system(self.state)
            return self._native
        return None

    def acceleration(self, q: np.ndarray, qdot: np.ndarray, t: float) -> np.ndarray:
        """Return ``qddot`` at ``(q, qdot, t)`` from the Euler-Lagrange equations."""
        nat = self._engine_native()
        if nat is None:
            raise NotImplementedError(
                f"{type(self).__name__} must define acceleration(q, qdot, t) or an engine"
            )
        return nat.acceleration(
            as_vector("q", q, self.ndof), as_vector("qdot", qdot, self.ndof), as_scalar("t", t)
        )

    def momentum(self, q: np.ndarray, qdot: np.ndarray) -> np.ndarray:
        """Return the canonical momentum ``p = dL/dqdot`` at ``(q, qdot)``."""
        nat = self._engine_native()
        if nat is None:
            raise NotImplementedError(f"{type(self).__name__} does not define momentum(q, qdot)")
        return nat.momentum(
            as_vector("q", q, self.ndof), as_vector("qdot", qdot, self.ndof),
            as_scalar("t", self.t),
        )

    def derivatives(self, t: float, state: np.ndarray) -> np.ndarray:
        """Return ``d[q, qdot]/dt = [qdot, acceleration(q, qdot, t)]``."""
        state = as_vector("state", state, 2 * self.ndof)
        nat = self._engine_native()
        if nat is not None:
            return nat.derivatives(as_scalar("t", t), state)
        q, qdot = self.split(state, self.ndof)
        acc = as_vector("acceleration(q, qdot, t)", self.acceleration(q, qdot, t), self.ndof,
                        finite=False)
        return np.concatenate([qdot, acc])

    @abstractmethod
    def energy(self, state: Optional[np.ndarray] = None) -> float:
        """Return the total mechanical energy of ``state`` (default: ``self.state``)."""

    def integrate(self, t_span, dt: float, method: str = "implicit_midpoint") -> SimulationResult:
        """Integrate with fixed step ``dt`` over ``t_span = (t0, t1)``.

        ``"implicit_midpoint"`` (default) is symplectic via the Legendre-transformed canonical
        form; ``"rk4"`` integrates ``(q, qdot)`` and is not symplectic. ``result.p`` holds
        ``qdot``, not the canonical momentum.
        """
        return self._integrate(t_span, dt, method, _EVERY_SAMPLE)

    def _integrate(self, t_span, dt, method, sampling: _Sampling) -> SimulationResult:
        if self._engine_native() is not None:
            return self._run_native(t_span, dt, method, sampling)
        t_span, dt, t, state = self._run_inputs(t_span, dt, 2 * self.ndof)
        parts = self._run_callbacks(
            lambda: _core.integrate_ode(self, state, t, t_span, dt, method, **sampling._asdict()),
            state,
            t,
        )
        # Integrated as a plain ODE on [q, qdot]: the split is known here only.
        return self._finish(parts, ndof=self.ndof)


class ODESystem(DynamicalSystem):
    """General first-order system ``dy/dt = f(t, y)``, possibly non-conservative.

    Integrated with ``"implicit_midpoint"`` (default; conserves every quadratic invariant),
    ``"rk4"`` or the adaptive ``"dop853"`` (see ``integrate_sampled``). A Python subclass implements ``derivatives(t, state)`` and ``energy(state)``.

    Parameters
    ----------
    state0 : array-like
        Initial state vector.
    """

    def derivatives(self, t: float, state: np.ndarray) -> np.ndarray:
        """Return d(state)/dt at ``(t, state)``."""
        if self._native is not None:
            return self._native.derivatives(
                as_scalar("t", t), as_vector("state", state, len(self.state))
            )
        raise NotImplementedError(f"{type(self).__name__} must define derivatives(t, state)")

    def integrate(self, t_span, dt: float, method: str = "implicit_midpoint") -> SimulationResult:
        """Integrate with fixed step ``dt`` over ``t_span = (t0, t1)`` (``"implicit_midpoint"``
        or ``"rk4"``); returns the state trajectory and its energy."""
        return self._integrate(t_span, dt, method, _EVERY_SAMPLE)

    def _integrate(self, t_span, dt, method, sampling: _Sampling) -> SimulationResult:
        if self._native is not None:
            return self._run_native(t_span, dt, method, sampling)
        t_span, dt, t, state = self._run_inputs(t_span, dt, len(self.state))
        parts = self._run_callbacks(
            lambda: _core.integrate_ode(self, state, t, t_span, dt, method, **sampling._asdict()),
            state,
            t,
        )
        return self._finish(parts)
