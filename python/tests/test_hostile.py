"""Hostile input: every public constructor, method and function of ``physicskit.classical``
fed NaN, +-inf, complex numbers, huge integers, booleans, strings, wrong shapes and sizes that
cannot fit in memory.

The only outcomes allowed are an exception of a documented type (``ValueError`` for bad
input, ``TypeError`` for a call Python itself refuses, ``NotImplementedError``,
``ConvergenceError``) with a message, or a correct result. Never a crash, a ``PanicException``
(pyo3's, a ``BaseException``: it would escape ``except Exception``), a numpy warning, or a
silent truncation (a complex number's imaginary part dropped, ``1.5`` taken as ``1``): any value
that is not a real number (of the right kind) must be refused, naming the argument.

The classes and functions are listed from ``physicskit.classical.__all__``; the valid call each
hostile value is put into comes from ``GOOD_CALLS``, which must cover every one of them (a new
system without an entry fails ``test_every_public_callable_has_a_good_call``). Hypothesis runs
derandomized, with few examples, so the file is reproducible and takes seconds.
"""

from __future__ import annotations

import inspect
import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import physicskit.classical as pc
from physicskit.classical import ConvergenceError
from physicskit.classical._native import MAX_NATIVE_INT

from conftest import catalogue_calls, make_systems

SETTINGS = settings(
    max_examples=40,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)

#: The exception types a hostile call may raise.
ALLOWED = (ValueError, TypeError, NotImplementedError, ConvergenceError)

#: The sizes the issue lists; each must be refused before anything is allocated.
HUGE_SIZES = [10**9, 10**12, 2**62]


def _available_bytes() -> int:
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 2**62


# -- valid calls --------------------------------------------------------------------------

#: name in ``pc.__all__`` -> (callable, positional args, keyword args) of a valid call.
#: The system the chaos functions' good calls run on (they move its state a little each time).
_HH = pc.HenonHeilesSystem([0.1, 0.0], [0.0, 0.3])

#: The catalogue's systems, each called with its entry's defaults and demonstration values by
#: keyword (``conftest.catalogue_calls``); then the functions, named constructors and static
#: helpers that are not catalogue entries.
GOOD_CALLS = {path: (fn, (), kwargs) for path, (fn, kwargs) in catalogue_calls().items()}
_HAND_CALLS = {
    "FoucaultPendulum.analytic_solution": (pc.FoucaultPendulum.analytic_solution,
                                           ([1.0, 0.0], [0.0, 0.1], 0.4, 5e-5, [0.0, 1.0]), {}),
    "eulers_disk_theta_analytic": (pc.eulers_disk_theta_analytic, ([0.0, 1.0], 0.5, 0.05), {}),
    "effective_potential_symmetric_top": (pc.effective_potential_symmetric_top,
                                          ([0.3, 0.5], 1.0, 2.0, 1.0, 0.5, 1.0), {}),
    "find_theta_equilibrium": (pc.find_theta_equilibrium, (1.0, 2.0, 1.0, 0.5, 1.0), {}),
    "nutation_frequency": (pc.nutation_frequency, (1.0, 2.0, 1.0, 0.5, 1.0), {}),
    "precession_frequency": (pc.precession_frequency, (1.0, 2.0, 1.0, 0.5), {}),
    "pendulum_action_angle": (pc.pendulum_action_angle, (0.5,), dict(g_over_l=1.0)),
    "methods": (pc.methods, (), {}),
    "catalog": (pc.catalog, (), {}),
    # Named constructors and static helpers, reached through the classes.
    "FoucaultPendulum.from_deflection": (pc.FoucaultPendulum.from_deflection, (1.0, 30.0),
                                         dict(length=67.0, g=9.81, latitude_deg=48.85,
                                              omega_earth=7.3e-5)),
    "ProjectileMotion.analytic_trajectory": (pc.ProjectileMotion.analytic_trajectory,
                                             (20.0, 45.0, 9.81, [0.0, 0.5, 1.0]), {}),
    "ProjectileMotion.range_and_max_height": (pc.ProjectileMotion.range_and_max_height,
                                              (20.0, 45.0, 9.81), {}),
    "SineGordonChain.kink": (pc.SineGordonChain.kink, (20, 10.0),
                             dict(width=1.0, velocity=0.3, polarity=1)),
    # The chaos toolkit (physicskit.classical.chaos), on short runs.
    "poincare_section": (pc.poincare_section, (_HH, (0.0, 2.0), 0.1),
                         dict(coordinate=1, value=0.0, direction=1, method=None, normal=None)),
    "lyapunov_spectrum": (pc.lyapunov_spectrum, (_HH, (0.0, 1.0), 0.1),
                          dict(n_exponents=None, renormalize_every=5, method=None,
                               history_stride=1)),
    "max_lyapunov": (pc.max_lyapunov, (_HH, (0.0, 1.0), 0.1),
                     dict(renormalize_every=5, method=None, history_stride=1)),
    "sali": (pc.sali, (_HH, (0.0, 1.0), 0.1),
             dict(renormalize_every=5, method=None, history_stride=1)),
    "gali": (pc.gali, (_HH, (0.0, 1.0), 0.1, 3),
             dict(renormalize_every=5, method=None, history_stride=1)),
    "chaos_verdict": (pc.chaos_verdict, ([0.5, 1e-9],), {}),
    "chaos_map": (pc.chaos_map, (_HH, [[0.1, 0.0, 0.0, 0.3]], (0.0, 1.0), 0.1),
                  dict(indicator="lyapunov", method=None, renormalize_every=5, coordinate=None,
                       value=0.0, direction=1, normal=None)),
    "ensemble": (pc.ensemble, ("harmonic-oscillator", (0.0, 1.0), 0.1),
                 dict(sweep={"q0": [0.1, 0.2]}, energy_error=True, stride=None)),
    "crossing": (pc.crossing, (0,), dict(value=0.0, direction="falling")),
    "abs_above": (pc.abs_above, (0, 1.0), {}),
}
assert not set(_HAND_CALLS) & set(GOOD_CALLS), "a catalogue entry written by hand too"
GOOD_CALLS.update(_HAND_CALLS)

# The SymPy engines (physicskit.classical.utils), when SymPy is installed: their constructors
# (symbols, expressions and params dict) and the systems they build (initial states).
try:
    import sympy as _sp
except ImportError:  # pragma: no cover - sympy is a test dependency of dev.sh env
    _sp = None
if _sp is not None:
    from physicskit.classical.utils import HamiltonianEngine, ODEEngine

    _q, _p, _k = _sp.symbols("q p k")
    _H = _p**2 / 2 + _k * _q**4 / 4
    GOOD_CALLS.update({
        "HamiltonianEngine": (HamiltonianEngine, ([_q], [_p], _H), dict(params={"k": 1.0})),
        "HamiltonianEngine.system": (HamiltonianEngine([_q], [_p], _H, params={"k": 1.0}).system,
                                     ([0.5], [0.1]), {}),
        "ODEEngine": (ODEEngine, ([_q, _p], [_p, -_k * _q]), dict(params={"k": 1.0})),
        "ODEEngine.system": (ODEEngine([_q, _p], [_p, -_k * _q], params={"k": 1.0}).system,
                             ([0.5, 0.1],), {}),
        "ODEEngine.jacobian": (ODEEngine([_q, _p], [_p, -_k * _q], params={"k": 1.0}).jacobian,
                               (0.0, [0.5, 0.1]), {}),
    })

#: Parameters that take an integer (sizes, indices, seeds, signs).
INT_PARAMS = {"n", "mode", "seed", "polarity", "stride", "coordinate", "direction", "n_exponents",
              "renormalize_every"}

#: Parameters that take True or False (``progress`` also a callable): bools are good there.
BOOL_PARAMS = {"energy_error", "progress", "max_lyapunov", "sali", "final_state"}

#: Parameters that take an array; the rest take a real number.
ARRAY_PARAMS = {"q0", "p0", "v0", "n0", "qdot0", "theta0", "thetadot0", "omega0", "quat0", "state0",
                "state", "q", "p", "qdot", "theta", "t", "y0"}


def _is_public_callable(name: str, obj) -> bool:
    if inspect.isclass(obj):
        return issubclass(obj, pc.DynamicalSystem) and not inspect.isabstract(obj) and \
            obj.__module__.startswith("physicskit.classical.systems")
    return inspect.isfunction(obj)


def test_every_public_callable_has_a_good_call():
    names = {n for n in pc.__all__ if _is_public_callable(n, getattr(pc, n))}
    assert names, "nothing listed"
    assert names <= set(GOOD_CALLS), sorted(names - set(GOOD_CALLS))
    # Every good call is good: the hostile cases below start from a call that works.
    for name, (fn, args, kwargs) in GOOD_CALLS.items():
        fn(*args, **kwargs)


def _params(name: str):
    """``(parameter name, how to put a value there)`` for every parameter of ``name``'s good
    call, the positional ones by index, the keyword ones by name."""
    fn, args, kwargs = GOOD_CALLS[name]
    sig = inspect.signature(fn)
    names = [p for p in sig.parameters if p not in ("self", "cls", "kwargs")]
    out = []
    for i, pname in enumerate(names):
        if i < len(args):
            out.append((pname, ("pos", i)))
        else:
            out.append((pname, ("kw", pname)))
    return out


def _call_with(name: str, where, value):
    fn, args, kwargs = GOOD_CALLS[name]
    args, kwargs = list(args), dict(kwargs)
    kind, key = where
    if kind == "pos":
        args[key] = value
    else:
        kwargs[key] = value
    return fn(*args, **kwargs)


# -- hostile values -----------------------------------------------------------------------

NONREAL_SCALARS = [
    1j, complex(2.0, 0.0), np.complex128(1.0 + 1.0j), np.complex64(3.0), np.array(1.0 + 2.0j),
    True, np.bool_(False), "1.0", b"1", None, [1.0, 2.0][:0], object(),
]
#: Integers no float64 holds (for a real parameter) or beyond the native integer range.
HUGE_REALS = [10**400, -(10**400)]
HUGE_INTS = HUGE_REALS + [2**64, 2**1000]
NONFINITE = [math.nan, math.inf, -math.inf, np.float64("nan"), np.float32("inf")]
NONINT_NUMBERS = [1.5, 5.4e16, 32.0, np.float64(2.0), Fraction(3, 2)]


def _length(good) -> int:
    """The good value's length (a list of SymPy symbols has one too, but no float array)."""
    if isinstance(good, (list, tuple)):
        return max(len(good), 1)
    return max(len(np.atleast_1d(np.asarray(good, dtype=float))), 1)


def _nonreal_vectors(good):
    """Arrays with the good one's length that hold something other than real numbers."""
    n = _length(good)
    base = [0.1] * n
    out = [
        np.array(base, dtype=complex),
        np.array(base, dtype=complex) + 1j,
        [complex(x, 0.5) for x in base],
        [np.complex128(x) for x in base],
        np.array([np.complex128(x) for x in base], dtype=object),
        np.array(base, dtype=bool),
        [str(x) for x in base],
        np.array([10**400] + base[1:], dtype=object),
        [10**400] + base[1:],
        [Fraction(1, 3)] * (n - 1) + [1j],
    ]
    return out


def _wrong_shape_vectors(good):
    n = _length(good)
    return [np.zeros((n, 2)), np.zeros(n + 1), [], [[0.1] * n, [0.2]], np.zeros((0, n))]


def _check_refused(exc_info, pname: str):
    """A refusal: allowed type, a message, and (for ValueError) the argument named."""
    exc = exc_info.value
    assert str(exc), f"empty message for {pname}"


def _run(fn):
    """Runs ``fn``; returns ``(ok, value_or_exception)``, failing on anything not allowed."""
    try:
        return True, fn()
    except ALLOWED as exc:
        assert str(exc), f"{type(exc).__name__} without a message"
        return False, exc
    except BaseException as exc:  # noqa: BLE001 - a PanicException is a BaseException
        if type(exc).__name__ == "PanicException":
            pytest.fail(f"panic: {exc}")
        raise


def _must_refuse(fn, pname: str, value):
    ok, out = _run(fn)
    assert not ok, f"{pname}={value!r} was accepted (silent conversion): {out!r}"
    # The argument is named: by its own name, or (for an entry of a pair) as name[i].
    assert pname.split("[")[0] in str(out) or isinstance(out, TypeError), \
        f"{pname}={value!r}: message does not name it: {out}"
    return out


# -- constructors and functions ----------------------------------------------------------

CALL_PARAMS = [(name, pname, where) for name in sorted(GOOD_CALLS)
               for pname, where in _params(name)]


@pytest.mark.parametrize("name, pname, where", CALL_PARAMS,
                         ids=[f"{n}-{p}" for n, p, _ in CALL_PARAMS])
@SETTINGS
@given(data=st.data())
def test_hostile_argument_is_refused_or_handled(name, pname, where, data):
    fn, args, kwargs = GOOD_CALLS[name]
    kind, key = where
    good = args[key] if kind == "pos" else kwargs.get(key)
    if pname in BOOL_PARAMS:
        value = data.draw(st.sampled_from([v for v in NONREAL_SCALARS + HUGE_REALS + NONFINITE
                                           if not isinstance(v, (bool, np.bool_))]))
        if value is None and good is None:
            return
        _must_refuse(lambda: _call_with(name, where, value), pname, value)
    elif pname in INT_PARAMS:
        value = data.draw(st.sampled_from(NONREAL_SCALARS + HUGE_INTS + NONFINITE
                                          + NONINT_NUMBERS))
        if value is None and pname in kwargs and good is None:
            return
        _must_refuse(lambda: _call_with(name, where, value), pname, value)
    elif pname in ARRAY_PARAMS or isinstance(good, (list, tuple, np.ndarray)):
        if good is None:
            good = [0.1]
        hostile = _nonreal_vectors(good)
        value = data.draw(st.sampled_from(hostile + _wrong_shape_vectors(good)
                                          + [[math.nan] * len(np.atleast_1d(good))]))
        if any(value is h for h in hostile):
            _must_refuse(lambda: _call_with(name, where, value), pname, value)
        else:
            # Wrong shapes and NaN: refused, or (theta/t of the vectorized functions, which
            # keep the input's shape) a result of that shape.
            _run(lambda: _call_with(name, where, value))
    else:
        value = data.draw(st.sampled_from(NONREAL_SCALARS + HUGE_REALS + NONFINITE))
        if value is None and good is None:
            return  # None is this parameter's default
        if isinstance(value, float) or (isinstance(value, np.floating)):
            # Non-finite: refused, or a correct (NaN-propagating) result; never a crash.
            _run(lambda: _call_with(name, where, value))
        else:
            _must_refuse(lambda: _call_with(name, where, value), pname, value)


@pytest.mark.parametrize("n", HUGE_SIZES)
@pytest.mark.parametrize("make", [
    lambda n: pc.FPUTChain(n=n),
    lambda n: pc.SineGordonChain(n=n),
    lambda n: pc.SineGordonChain.kink(n, 10.0),
    lambda n: pc.PendulumSwarm.from_box(1.0, 0.0, 0.1, 0.1, n=n),
], ids=["FPUTChain", "SineGordonChain", "SineGordonChain.kink", "PendulumSwarm.from_box"])
def test_sizes_that_cannot_fit_are_refused_before_allocating(make, n):
    # 10^9 sites take 32-72 GB: refused where less is available (every machine this runs on);
    # 10^12 and 2^62 are refused everywhere (2^62 overflows a byte count in 64 bits).
    if n == 10**9 and _available_bytes() > 80 * 10**9:
        pytest.skip("this machine could hold 10^9 sites")
    with pytest.raises(ValueError, match=r"`n` = \d+ is too large"):
        make(n)


def test_coupled_oscillators_refuse_matrices_that_cannot_fit():
    # 10^6 masses: 8 MB of state, but the n x n work matrices would take 24 TB.
    n = 10**6
    with pytest.raises(ValueError, match="too large"):
        pc.CoupledOscillators(np.zeros(n), np.zeros(n), n=n)


@pytest.mark.parametrize("n", [10**400, 2**64, MAX_NATIVE_INT + 1])
def test_integers_beyond_the_native_range_are_value_errors(n):
    for make in (lambda: pc.FPUTChain(n=n), lambda: pc.SineGordonChain.kink(n, 1.0),
                 lambda: pc.PendulumSwarm.from_box(1.0, 0.0, 0.1, 0.1, n=20, seed=n)):
        # "does not fit in a 64-bit integer" (constructors, through the catalogue) or "must be
        # <= 2**64 - 1" (the static helpers' as_int): either way the argument is named.
        with pytest.raises(ValueError, match=r"(must be <=|does not fit in a 64-bit integer)"):
            make()


@pytest.mark.parametrize("bad", [5.4e16, 1.5, 32.0, np.float64(8.0), True, "8", 8 + 0j])
def test_integer_parameters_take_only_integers(bad):
    with pytest.raises(ValueError, match=r"(^n |`n`)"):
        pc.FPUTChain(n=bad)
    with pytest.raises(ValueError, match=r"(^mode |`mode`)"):
        pc.FPUTChain(n=8, mode=bad)
    with pytest.raises(ValueError, match=r"(^polarity |`polarity`)"):
        pc.SineGordonChain.kink(20, 10.0, polarity=bad)
    with pytest.raises(ValueError, match=r"(^seed |`seed`)"):
        pc.PendulumSwarm.from_box(1.0, 0.0, 0.1, 0.1, n=20, seed=bad)


def test_numpy_integers_are_integers():
    chain = pc.FPUTChain(n=np.int64(8), mode=np.uint8(2))
    assert chain.ndof == 8 and chain.mode == 2
    assert pc.SineGordonChain.kink(np.int32(5), 2.0, polarity=np.int8(-1))[0][0] < 0


# -- methods of every built-in system --------------------------------------------------------

def _method_calls(system):
    """``(label, parameter, call(value))`` for each numeric argument of each public method,
    the other arguments taken from the system's own state."""
    state = np.array(system.state, dtype=float)
    nd = getattr(system, "ndof", None)
    q = state[:nd] if nd else state
    p = state[nd:] if nd else state
    calls = [
        ("energy", "state", lambda v: system.energy(v)),
        ("derivatives", "state", lambda v: system.derivatives(0.0, v)),
        ("derivatives", "t", lambda v: system.derivatives(v, state)),
        ("integrate", "dt", lambda v: system.integrate((0.0, 0.1), v)),
        ("integrate", "t_span", lambda v: system.integrate((0.0, v), 0.05)),
        ("integrate", "t_span", lambda v: system.integrate(v, 0.05)),
        ("integrate_sampled", "stride", lambda v: system.integrate_sampled((0.0, 0.1), 0.05,
                                                                          stride=v)),
        ("integrate_sampled", "rtol", lambda v: system.integrate_sampled((0.0, 0.1), 0.05,
                                                                        "dop853", rtol=v)),
        ("integrate_sampled", "atol", lambda v: system.integrate_sampled((0.0, 0.1), 0.05,
                                                                        "dop853", atol=v)),
        ("reset", "state0", lambda v: system.reset(v)),
        ("reset", "t0", lambda v: system.reset(None, v)),
    ]
    if isinstance(system, pc.HamiltonianSystem):
        calls += [
            ("kinetic_energy", "p", lambda v: system.kinetic_energy(v)),
            ("potential_energy", "q", lambda v: system.potential_energy(v)),
            ("force", "q", lambda v: system.force(v)),
            ("force", "t", lambda v: system.force(q, v)),
        ]
    if isinstance(system, pc.LagrangianSystem):
        calls += [
            ("acceleration", "q", lambda v: system.acceleration(v, p, 0.0)),
            ("acceleration", "qdot", lambda v: system.acceleration(q, v, 0.0)),
            ("acceleration", "t", lambda v: system.acceleration(q, p, v)),
            ("momentum", "q", lambda v: system.momentum(v, p)),
        ]
    for meth in ("normal_mode_coords", "modal_energies", "per_particle_energy",
                 "phase_space_area"):
        if hasattr(system, meth):
            f = getattr(system, meth)
            calls += [(meth, "q", lambda v, f=f: f(v, p)), (meth, "p", lambda v, f=f: f(q, v))]
    for meth in ("positions", "symmetry_axis"):
        if hasattr(system, meth):
            f = getattr(system, meth)
            calls.append((meth, "q", lambda v, f=f: f(v)))
    if hasattr(system, "inertia_box"):
        calls.append(("inertia_box", "mass", lambda v: system.inertia_box(v)))
    for meth in ("conserved_quantities", "mode_energies", "body_angular_momentum"):
        if hasattr(system, meth):
            f = getattr(system, meth)
            calls.append((meth, "state", lambda v, f=f: f(v)))
    if hasattr(system, "precession_nutation_rate"):
        calls.append(("precession_nutation_rate", "state",
                      lambda v: system.precession_nutation_rate(v)))
    return calls, state


SYSTEM_NAMES = sorted(make_systems())


@pytest.mark.parametrize("system_name", SYSTEM_NAMES)
@SETTINGS
@given(data=st.data())
def test_hostile_method_arguments(system_name, data):
    system = make_systems()[system_name]()
    calls, state = _method_calls(system)
    label, pname, call = data.draw(st.sampled_from(calls), label="method")
    before = (np.array(system.state, copy=True), system.t)
    if pname in ("dt", "t", "t0", "t_span", "stride", "rtol", "atol", "mass"):
        pool = NONREAL_SCALARS + HUGE_REALS
        if pname == "stride":
            pool = pool + HUGE_INTS + NONINT_NUMBERS + [0, -1]
        if pname in ("rtol", "atol"):
            pool = pool + NONFINITE + [0.0, -1e-8]
        if pname == "mass":
            pool = pool + NONFINITE + [0.0, -1.0]
        value = data.draw(st.sampled_from(pool), label="value")
        if value is None and pname in ("t0", "rtol", "atol"):
            return
        if label == "integrate" and pname == "t_span" and isinstance(value, list):
            return  # the empty list is not a pair: refused, checked elsewhere
        _must_refuse(lambda: call(value), pname, value)
    else:
        good = state if pname in ("state", "state0") else np.zeros(
            getattr(system, "ndof", len(state)))
        hostile = _nonreal_vectors(good)
        value = data.draw(st.sampled_from(hostile + _wrong_shape_vectors(good)), label="value")
        if any(value is h for h in hostile):
            _must_refuse(lambda: call(value), pname, value)
        else:
            _run(lambda: call(value))
    if label not in ("reset",):
        # A refused call leaves the system as it was.
        ok_state = np.array_equal(system.state, before[0]) and system.t == before[1]
        assert ok_state or label.startswith("integrate"), f"{label} changed the state"


@pytest.mark.parametrize("system_name", SYSTEM_NAMES)
@pytest.mark.parametrize("bad", [
    lambda s: np.asarray(s, dtype=complex),
    lambda s: np.asarray(s, dtype=complex) * (1 + 1e-3j),
    lambda s: [complex(x) for x in s],
    lambda s: np.array([np.complex128(x) for x in s], dtype=object),
    lambda s: np.asarray(s) > 0,
    lambda s: np.concatenate([s, [1.0]]),
], ids=["complex-dtype", "complex-imag", "complex-list", "complex-objects", "bool", "long"])
def test_assigned_state_that_is_not_real_is_refused_at_integrate(system_name, bad):
    system = make_systems()[system_name]()
    good = np.array(system.state, copy=True)
    system.state = bad(good)
    with pytest.raises(ValueError, match="state"):
        system.integrate((0.0, 0.1), 0.05)
    with pytest.raises(ValueError, match="state"):
        system.energy()
    # Nothing was silently cast: the attribute is as the user set it, and a real state works.
    system.state = good
    system.integrate((0.0, 0.1), 0.05)


def test_complex_time_on_the_instance_is_refused():
    system = make_systems()["KeplerSystem"]()
    system.t = 1j
    with pytest.raises(ValueError, match="^t "):
        system.integrate((0.0, 0.1), 0.05)


# -- Python subclasses ----------------------------------------------------------------------

class _Oscillator(pc.HamiltonianSystem):
    """A harmonic oscillator in Python whose force reassigns ``self.state`` after a few calls
    and then raises or returns something that is refused."""

    separable = True

    def __init__(self, mode):
        super().__init__([1.0], [0.0])
        self.mode, self.calls = mode, 0

    def kinetic_energy(self, p):
        return 0.5 * float(p[0] ** 2)

    def potential_energy(self, q):
        return 0.5 * float(q[0] ** 2)

    def force(self, q, t=0.0):
        self.calls += 1
        if self.calls == 5:
            self.state = np.array([99.0, 99.0])
            self.t = 42.0
            if self.mode == "raise":
                raise RuntimeError("callback failed")
            if self.mode == "complex":
                return np.array([1j])
            if self.mode == "complex-list":
                return [np.complex128(1 + 1j)]
            if self.mode == "bad-length":
                return np.zeros(3)
        return -q


@pytest.mark.parametrize("mode", ["raise", "complex", "complex-list", "bad-length"])
def test_a_callback_reassigning_state_then_failing_leaves_the_state_restored(mode):
    system = _Oscillator(mode)
    state0, t0 = np.array(system.state, copy=True), system.t
    with pytest.raises((RuntimeError, ValueError)):
        system.integrate((0.0, 1.0), 0.01, method="verlet")
    np.testing.assert_array_equal(system.state, state0)
    assert system.t == t0
    # And the system still runs from there (the callback no longer misbehaves).
    system.mode = "ok"
    result = system.integrate((0.0, 0.1), 0.01, method="verlet")
    assert result.t[0] == t0


class _ComplexEnergy(pc.ODESystem):
    def derivatives(self, t, state):
        return -state

    def energy(self, state=None):
        return np.complex128(1.0 + 1.0j)


def test_a_complex_energy_from_a_callback_is_refused():
    system = _ComplexEnergy([1.0, 2.0])
    with pytest.raises(ValueError, match="complex"):
        system.integrate((0.0, 0.1), 0.01, method="rk4")
    np.testing.assert_array_equal(system.state, [1.0, 2.0])
