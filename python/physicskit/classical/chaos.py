"""Phase-space and chaos analyses of any system (not in the spec): Poincaré sections,
Lyapunov spectra, SALI and GALI, chaos maps.

Every function runs the system's orbit with the same fixed-step integrator ``integrate``
would use (``method=None``: the system's default) and, like ``integrate``, leaves ``state``
and ``t`` at the end of the run, so a second call continues the orbit. The tangent dynamics
are exact for the splitting methods (the derivative of the discrete step: symplectic, of
determinant one) and the variational equations integrated by the same method otherwise.
Jacobians: analytic for the built-in Hamiltonian and ODE systems; automatic differentiation
for the built-in Lagrangian systems (of their closed-form equations of motion) and the SymPy
engines, except the ``[q, qdot]`` form the explicit methods step for the coupled oscillators
and a SymPy Lagrangian (central differences); for a Python subclass its
optional ``force_jacobian(q, t)`` (Hamiltonian, ``(ndof, ndof)``) or ``jacobian(t, state)``
(ODE); else central differences (relative step ``eps**(1/3)``, about 6e-6).

References: Benettin et al., Meccanica 15 (1980) 9-30 (Lyapunov spectra); Skokos,
J. Phys. A 34 (2001) 10029 (SALI); Skokos, Bountis & Antonopoulos, Physica D 231 (2007) 30
(GALI).
"""

from __future__ import annotations

from typing import Any, Callable, Optional, Union

import numpy as np

from ._native import _core, as_array, as_int, as_scalar, as_t_span, as_vector
from .core.base_system import DynamicalSystem, HamiltonianSystem, LagrangianSystem

__all__ = [
    "PoincareSection",
    "LyapunovSpectrum",
    "AlignmentIndex",
    "CHAOS_THRESHOLD",
    "poincare_section",
    "lyapunov_spectrum",
    "max_lyapunov",
    "sali",
    "gali",
    "chaos_verdict",
    "chaos_map",
]

CHAOS_THRESHOLD: float = _core.CHAOS_THRESHOLD
"""SALI or GALI below this value classifies an orbit as chaotic (Skokos 2001): the core's
constant (``physicskit::classical::analysis::sali::CHAOS_THRESHOLD``, 1e-8), which its
verdicts use too."""


class PoincareSection:
    """Crossings of an orbit with a surface of section.

    Attributes
    ----------
    t : ndarray, shape (n,)
        Crossing times.
    y : ndarray, shape (n, state_dim)
        Crossing states, one row each (the section coordinate equals its value exactly).
    """

    def __init__(self, t: np.ndarray, y: np.ndarray):
        self.t = t
        self.y = y

    def __len__(self) -> int:
        return len(self.t)

    def __repr__(self) -> str:
        return f"PoincareSection({len(self.t)} crossings)"


class LyapunovSpectrum:
    """Lyapunov exponents of an orbit (Benettin's method).

    Attributes
    ----------
    exponents : ndarray, shape (k,)
        Final estimates, sorted in descending order.
    t : ndarray, shape (m,)
        Times of the re-orthonormalizations.
    history : ndarray, shape (m, k)
        Running estimates at those times, in the Gram-Schmidt order of the vectors (which is
        the descending order once converged).
    """

    def __init__(self, exponents: np.ndarray, t: np.ndarray, history: np.ndarray):
        self.exponents = exponents
        self.t = t
        self.history = history

    def __repr__(self) -> str:
        return f"LyapunovSpectrum(exponents={self.exponents!r})"


class AlignmentIndex:
    """SALI or GALI_k against time.

    Attributes
    ----------
    t : ndarray, shape (m,)
        Times (from the start, where the vectors are orthonormal).
    index : ndarray, shape (m,)
        The index at each time.
    verdict : str
        ``"chaotic"`` once the index fell below :data:`CHAOS_THRESHOLD`, else ``"regular"``.
    name : str
        Which index: ``"SALI"`` or ``"GALI_k"`` (``k`` the number of vectors, e.g.
        ``"GALI_3"``).
    """

    def __init__(self, t: np.ndarray, index: np.ndarray, verdict: str, name: str = "SALI"):
        self.t = t
        self.index = index
        self.verdict = verdict
        self.name = name

    def __repr__(self) -> str:
        return (f"AlignmentIndex({self.name}, final={self.index[-1]:.3g}, "
                f"verdict={self.verdict!r})")


def _native_of(system: Any):
    """The native object of a built-in system (or an engine-backed Lagrangian), else None."""
    if isinstance(system, LagrangianSystem):
        return system._engine_native()
    return system._native


def _method(method: Optional[str]) -> Optional[str]:
    if method is None or isinstance(method, str):
        return method
    raise ValueError(f"method must be a string or None, got {type(method).__name__}")


def _run(system: Any, t_span, dt, method: Optional[str], kind: str, **options) -> dict:
    if not isinstance(system, DynamicalSystem):
        raise TypeError(
            f"system must be a physicskit.classical DynamicalSystem, got {type(system).__name__}"
        )
    t_span = as_t_span(t_span)
    dt = as_scalar("dt", dt)
    method = _method(method)
    t = as_scalar("t", system.t)
    native = _native_of(system)
    if native is not None:
        state = as_vector("state", system.state, len(native.state))
        out = _core.chaos_native(native, state, t, t_span, dt, method, kind, **options)
    elif isinstance(system, HamiltonianSystem):
        ndof = int(system.ndof)
        state = as_vector("state", system.state, 2 * ndof)
        default = "yoshida4" if system.separable else "implicit_midpoint"
        out = _core.chaos_hamiltonian(
            system, state, t, t_span, dt, method or default, ndof, bool(system.separable),
            system._mass_inv_vector(), kind, **options,
        )
    else:
        state = as_vector("state", system.state)
        out = _core.chaos_ode(
            system, state, t, t_span, dt, method or "implicit_midpoint", kind, **options
        )
    system.state = out["state"]
    system.t = float(out["t_end"])
    return out


def _section_options(coordinate, normal, value, direction) -> dict:
    if normal is not None:
        normal = [float(v) for v in as_vector("normal", normal)]
        if not normal:
            raise ValueError("normal is empty; give one coefficient per state component")
    if coordinate is not None:
        coordinate = as_int("coordinate", coordinate)
    return dict(
        coordinate=coordinate,
        normal=normal,
        value=as_scalar("value", value),
        direction=as_int("direction", direction, minimum=-1, maximum=1),
    )


def poincare_section(
    system: DynamicalSystem, t_span, dt: float, *, coordinate: Optional[int] = None,
    value: float = 0.0, direction: int = 1, method: Optional[str] = None,
    normal=None,
) -> PoincareSection:
    """Crossings of the orbit with the plane ``state[coordinate] = value`` (or, with
    ``normal=a`` instead of ``coordinate``, the plane ``a . state = value``) in
    ``direction`` (1: increasing, -1: decreasing, 0: both).

    Each crossing is located inside its step by re-running that step of the same method with
    a shorter length (regula falsi on the step length), so its time and state are accurate
    to the method's order; the step sequence is the one ``integrate`` takes.
    """
    out = _run(
        system, t_span, dt, method, "section",
        **_section_options(coordinate, normal, value, direction),
    )
    return PoincareSection(out["t"], out["y"])


def lyapunov_spectrum(
    system: DynamicalSystem, t_span, dt: float, *, n_exponents: Optional[int] = None,
    renormalize_every: int = 10, method: Optional[str] = None, history_stride: int = 1,
) -> LyapunovSpectrum:
    """The ``n_exponents`` largest Lyapunov exponents (all for None), re-orthonormalizing the
    deviation vectors by QR every ``renormalize_every`` steps.

    ``history`` keeps the running estimates of every ``history_stride``-th renormalization
    (and of the last), so a long run need not hold them all; the exponents do not depend on
    it. Ctrl-C stops the run with ``KeyboardInterrupt``."""
    if n_exponents is not None:
        n_exponents = as_int("n_exponents", n_exponents, minimum=1)
    out = _run(
        system, t_span, dt, method, "lyapunov", n_exponents=n_exponents,
        renormalize_every=as_int("renormalize_every", renormalize_every, minimum=1),
        history_stride=as_int("history_stride", history_stride, minimum=1),
    )
    return LyapunovSpectrum(out["exponents"], out["t"], out["history"])


def max_lyapunov(
    system: DynamicalSystem, t_span, dt: float, *, renormalize_every: int = 10,
    method: Optional[str] = None, history_stride: int = 1,
) -> LyapunovSpectrum:
    """The largest Lyapunov exponent (one deviation vector): ``exponents[0]``."""
    return lyapunov_spectrum(
        system, t_span, dt, n_exponents=1, renormalize_every=renormalize_every, method=method,
        history_stride=history_stride,
    )


def sali(
    system: DynamicalSystem, t_span, dt: float, *, renormalize_every: int = 10,
    method: Optional[str] = None, history_stride: int = 1,
) -> AlignmentIndex:
    """The Smaller Alignment Index of two deviation vectors against time, kept at every
    ``history_stride``-th evaluation (and the first and last); the verdict is on all."""
    out = _run(
        system, t_span, dt, method, "sali",
        renormalize_every=as_int("renormalize_every", renormalize_every, minimum=1),
        history_stride=as_int("history_stride", history_stride, minimum=1),
    )
    return AlignmentIndex(out["t"], out["index"], out["verdict"])


def gali(
    system: DynamicalSystem, t_span, dt: float, k: int, *, renormalize_every: int = 10,
    method: Optional[str] = None, history_stride: int = 1,
) -> AlignmentIndex:
    """The Generalized Alignment Index GALI_k (volume spanned by ``k`` unit deviation
    vectors) against time; ``2 <= k <= state dimension``. ``history_stride`` as for
    :func:`sali`."""
    k = as_int("k", k, minimum=2)
    out = _run(
        system, t_span, dt, method, "gali", k=k,
        renormalize_every=as_int("renormalize_every", renormalize_every, minimum=1),
        history_stride=as_int("history_stride", history_stride, minimum=1),
    )
    return AlignmentIndex(out["t"], out["index"], out["verdict"], f"GALI_{k}")


def chaos_verdict(index: Union[AlignmentIndex, Any]) -> str:
    """``"chaotic"`` if an alignment index (an :class:`AlignmentIndex` or array of values)
    fell below :data:`CHAOS_THRESHOLD`, else ``"regular"``."""
    values = index.index if isinstance(index, AlignmentIndex) else as_array("index", index)
    return "chaotic" if np.any(values < CHAOS_THRESHOLD) else "regular"


_INDICATORS = ("lyapunov", "sali", "crossings")


def chaos_map(
    system: Union[DynamicalSystem, Callable[..., DynamicalSystem]], points, t_span, dt: float,
    *, indicator: str = "lyapunov", method: Optional[str] = None, renormalize_every: int = 10,
    coordinate: Optional[int] = None, value: float = 0.0, direction: int = 1, normal=None,
) -> np.ndarray:
    """One chaos indicator per initial condition, computed on all cores.

    ``system`` is a built-in system and ``points`` an array of its states, shape
    ``(n, state_dim)``; or ``system`` is a function and ``points`` an array of shape
    ``(n, m)`` whose rows are its arguments: point ``i`` is the orbit of
    ``system(*points[i])`` from its initial state. ``indicator`` is ``"lyapunov"`` (the
    largest exponent at ``t_span[1]``), ``"sali"`` (SALI at ``t_span[1]``, or once below
    1e-14) or ``"crossings"`` (the number of crossings of the section given by
    ``coordinate``/``normal``, ``value``, ``direction``). Returns shape ``(n,)``; the result
    is bit-identical for any number of threads. The systems are not changed.
    """
    if indicator not in _INDICATORS:
        raise ValueError(f"indicator must be one of {_INDICATORS}, got {indicator!r}")
    pts = as_array("points", points)
    if pts.ndim == 1:
        pts = pts.reshape(-1, 1) if callable(system) and not isinstance(
            system, DynamicalSystem) else pts.reshape(1, -1)
    if pts.ndim != 2:
        raise ValueError(f"points must be two-dimensional, got shape {pts.shape}")
    if isinstance(system, DynamicalSystem):
        systems = [system]
        states = pts
    elif callable(system):
        systems = [system(*row) for row in pts]
        if not systems:
            return np.zeros(0)
        states = np.array([as_vector("state", s.state) for s in systems])
    else:
        raise TypeError("system must be a DynamicalSystem or a function returning one")
    natives = [_native_of(s) if isinstance(s, DynamicalSystem) else None for s in systems]
    if any(n is None for n in natives):
        raise NotImplementedError(
            "chaos_map runs built-in systems (and LagrangianEngine systems); loop over "
            "max_lyapunov or sali for a system written in Python"
        )
    options: dict = dict(
        renormalize_every=as_int("renormalize_every", renormalize_every, minimum=1)
    )
    # Checked whatever the indicator, so that a bad value is never silently ignored.
    section = _section_options(coordinate, normal, value, direction)
    if indicator == "crossings":
        options.update(section)
    else:
        for name, given in (("coordinate", coordinate), ("normal", normal)):
            if given is not None:
                raise ValueError(f"{name} applies only to indicator='crossings'")
    return _core.chaos_map(
        natives, np.ascontiguousarray(states, dtype=np.float64), as_t_span(t_span),
        as_scalar("dt", dt), _method(method), indicator, **options,
    )
