"""Every ``_core`` function that takes a float64 array reads any layout of it.

numpy can hand the extension float64s at an address that is not a multiple of eight (a buffer
sliced at an odd offset, an array deserialized inside a message), strided, read-only, in
big-endian byte order or in Fortran order. Each call here is made with the plain array and
with each of those layouts of it; the outcome (the value, to the bit, or the exception's type
and message) must be the same. Reading an unaligned array in place panicked
(``PanicException``: "The pointer must be aligned") and a big-endian one was refused as a
type mismatch, before every read went through the one reader at the boundary
(``python/src/convert.rs``).
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from physicskit import _core


def unaligned(a: np.ndarray) -> np.ndarray:
    """The same values one byte past an aligned address."""
    buf = b"\0" + np.ascontiguousarray(a).tobytes()
    out = np.frombuffer(buf, dtype=np.float64, offset=1).reshape(a.shape)
    assert not out.flags.aligned or a.size == 0
    return out


def strided(a: np.ndarray) -> np.ndarray:
    """The same values every other element of a wider array (a view, not contiguous)."""
    wide = np.zeros(a.shape[:-1] + (2 * a.shape[-1],))
    wide[..., ::2] = a
    out = wide[..., ::2]
    assert not out.flags.c_contiguous or out.size <= 1
    return out


def reversed_view(a: np.ndarray) -> np.ndarray:
    """The same values through a negative stride."""
    return np.ascontiguousarray(a[..., ::-1])[..., ::-1]


def read_only(a: np.ndarray) -> np.ndarray:
    out = a.copy()
    out.setflags(write=False)
    return out


def big_endian(a: np.ndarray) -> np.ndarray:
    return a.astype(">f8")


def unaligned_big_endian(a: np.ndarray) -> np.ndarray:
    buf = b"\0" + a.astype(">f8").tobytes()
    return np.frombuffer(buf, dtype=">f8", offset=1).reshape(a.shape)


def fortran(a: np.ndarray) -> np.ndarray:
    return np.asfortranarray(a)


LAYOUTS: dict[str, Callable[[np.ndarray], np.ndarray]] = {
    "unaligned": unaligned,
    "strided": strided,
    "reversed": reversed_view,
    "read-only": read_only,
    "big-endian": big_endian,
    "unaligned-big-endian": unaligned_big_endian,
    "fortran": fortran,
}


def outcome(call: Callable[[], Any]) -> Any:
    """What a call gives: its value, or its exception's type and message. A panic is never an
    acceptable outcome, for the plain array or any other."""
    try:
        return ("value", call())
    except BaseException as e:  # noqa: BLE001 (a PanicException derives from BaseException)
        assert type(e).__name__ != "PanicException", f"panic: {e}"
        return ("raised", type(e), str(e))


def same(a: Any, b: Any) -> bool:
    """Bit-identical values (arrays, numbers, containers, systems by their state)."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        return a.shape == b.shape and a.tobytes() == b.tobytes()
    if isinstance(a, _core.NativeSystem):
        return isinstance(b, _core.NativeSystem) and same(a.state, b.state)
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, (tuple, list)):
        return (
            isinstance(b, (tuple, list))
            and len(a) == len(b)
            and all(same(x, y) for x, y in zip(a, b))
        )
    if isinstance(a, float) and isinstance(b, float):
        return np.float64(a).tobytes() == np.float64(b).tobytes()
    return bool(a == b)


def check_layouts(call: Callable[..., Any], arrays: list[np.ndarray]) -> None:
    """``call(*arrays)`` gives the same outcome with each layout of each array in turn."""
    expected = outcome(lambda: call(*arrays))
    for i, a in enumerate(arrays):
        for layout, make in LAYOUTS.items():
            args = list(arrays)
            args[i] = make(a)
            got = outcome(lambda: call(*args))
            assert same(expected, got), (
                f"argument {i} {layout}: {got!r} differs from the plain array's {expected!r}"
            )


# ---- NativeSystem methods of every catalogue system -----------------------------------------


def catalogue_systems() -> list[str]:
    return [e["name"] for e in _core.catalog()]


def build(name: str) -> _core.NativeSystem:
    """The system at its catalogue defaults (a vector left out whose length is another's
    or a count: zeros of that length; a demonstration's scalar left out: 0)."""
    entry = next(e for e in _core.catalog() if e["name"] == name)
    values = {p["name"]: p["default"] for p in entry["params"] if p["default"] is not None}
    for p in entry["params"]:
        length = str(p["length"])
        other, count = length.removeprefix("same as "), length.removeprefix("count ")
        if p["default"] is None and other in values:
            values[p["name"]] = np.zeros(len(values[other]))
        elif p["default"] is None and p["kind"] == "vector" and count in values:
            values[p["name"]] = np.zeros(int(values[count]))
        elif p["default_kind"] == "demo_absent" and p["kind"] == "scalar":
            values[p["name"]] = 0.0
    return _core.build(name, values)


ARRAY_NAMES = {"state", "q", "p", "qdot"}


def method_cases(system: _core.NativeSystem) -> list[tuple[str, list[str]]]:
    """Every method of ``system`` that takes an array, with its parameters' names."""
    cases = []
    for name in dir(system):
        if name.startswith("_"):
            continue
        attr = getattr(system, name)
        if not callable(attr):
            continue
        params = [
            p.name for p in inspect.signature(attr).parameters.values()
            if p.default is inspect.Parameter.empty
        ]
        if ARRAY_NAMES & set(params):
            cases.append((name, params))
    return cases


def argument(name: str, system: _core.NativeSystem) -> Any:
    state = np.asarray(system.state, dtype=np.float64)
    half = state.size // 2 if system.ndof is not None else state.size
    if name == "state":
        return state
    if name in ("q",):
        return state[:half].copy()
    if name in ("p", "qdot"):
        return state[half:].copy()
    if name == "t" or name == "t0":
        return 0.25
    if name == "t_span":
        return (0.25, 0.75)
    if name == "dt":
        return 0.05
    raise AssertionError(f"no test value for the parameter {name}")


@pytest.mark.parametrize("name", catalogue_systems())
def test_native_methods_read_every_layout(name: str) -> None:
    system = build(name)
    cases = method_cases(system)
    assert any(m == "energy" for m, _ in cases), "the search for methods found none"
    for method, params in cases:
        values = [argument(p, system) for p in params]
        positions = [i for i, v in enumerate(values) if isinstance(v, np.ndarray)]

        def call(*arrays: np.ndarray, method: str = method, values: list[Any] = values,
                 positions: list[int] = positions) -> Any:
            args = list(values)
            for i, a in zip(positions, arrays):
                args[i] = a
            # A fresh system per call: `reset` changes its state.
            return getattr(build(name), method)(*args)

        check_layouts(call, [values[i] for i in positions])


# ---- module-level functions -----------------------------------------------------------------


def kepler() -> _core.NativeSystem:
    return build("kepler-state")


class Oscillator:
    """A Python system for the callback engines: x'' = -x, written as forces and derivatives."""

    def derivatives(self, t: float, state: np.ndarray) -> np.ndarray:
        return np.array([state[1], -state[0]])

    def force(self, q: np.ndarray, t: float) -> np.ndarray:
        return -q

    def energy(self, state: np.ndarray) -> float:
        return 0.5 * float(state @ state)


class UnalignedOscillator(Oscillator):
    """The same system returning its forces and derivatives as unaligned arrays."""

    def derivatives(self, t: float, state: np.ndarray) -> np.ndarray:
        return unaligned(super().derivatives(t, state))

    def force(self, q: np.ndarray, t: float) -> np.ndarray:
        return unaligned(super().force(q, t))


ARRAY_1 = np.array([0.3, -0.1])
STATE_2 = np.array([1.0, 0.0, 0.0, 1.0])

FUNCTION_CASES: dict[str, tuple[Callable[..., Any], list[np.ndarray]]] = {
    "effective_potential_symmetric_top": (
        lambda th: _core.effective_potential_symmetric_top(th, 1.0, 2.0, 1.0, 0.5, 1.0),
        [np.linspace(0.2, 2.0, 5)],
    ),
    "expr_hamiltonian": (
        lambda k, q0, p0: _core.expr_hamiltonian("(+ (* 0.5 (^ p0 2)) (* 0.5 param0 (^ q0 2)))", 1,
                                                 k, q0, p0),
        [np.array([2.0]), np.array([0.5]), np.array([0.25])],
    ),
    "expr_ode": (
        lambda k, y0: _core.expr_ode(["y1", "(- (* param0 y0))"], k, y0),
        [np.array([2.0]), np.array([0.5, 0.25])],
    ),
    "expr_lagrangian": (
        lambda k, q0, v0: _core.expr_lagrangian("(- (* 0.5 (^ qdot0 2)) (* 0.5 param0 (^ q0 2)))", 1,
                                                k, q0, v0),
        [np.array([2.0]), np.array([0.5]), np.array([0.25])],
    ),
    "system_jacobian": (
        lambda s: _core.system_jacobian(kepler(), 0.0, s),
        [STATE_2],
    ),
    "force_jacobian": (
        lambda q: _core.force_jacobian(kepler(), q, 0.0),
        [np.array([1.0, 0.2])],
    ),
    "ensemble": (
        lambda values, states: _core.ensemble(
            "harmonic-oscillator", {"m": 1.0}, [("k", values)], states, 3, (0.0, 1.0), 0.1),
        [np.array([1.0, 2.0, 3.0]), np.array([[1.0, 0.0], [0.5, 0.5], [0.0, 1.0]])],
    ),
    "chaos_native": (
        lambda s: _core.chaos_native(kepler(), s, 0.0, (0.0, 1.0), 0.1, None, "lyapunov"),
        [STATE_2],
    ),
    "chaos_map": (
        lambda states: _core.chaos_map([kepler()], states, (0.0, 1.0), 0.1, None, "sali"),
        [np.array([[1.0, 0.0, 0.0, 1.0], [1.0, 0.1, 0.0, 0.9]])],
    ),
    "chaos_hamiltonian": (
        lambda s, m: _core.chaos_hamiltonian(Oscillator(), s, 0.0, (0.0, 1.0), 0.1, "verlet", 1,
                                             True, m, "lyapunov"),
        [np.array([1.0, 0.0]), np.array([1.0])],
    ),
    "chaos_ode": (
        lambda s: _core.chaos_ode(Oscillator(), s, 0.0, (0.0, 1.0), 0.1, "rk4", "lyapunov"),
        [np.array([1.0, 0.0])],
    ),
    "integrate_hamiltonian": (
        lambda s, m: _core.integrate_hamiltonian(Oscillator(), s, 0.0, (0.0, 1.0), 0.1, "verlet",
                                                 1, True, m),
        [np.array([1.0, 0.0]), np.array([1.0])],
    ),
    "integrate_ode": (
        lambda s: _core.integrate_ode(Oscillator(), s, 0.0, (0.0, 1.0), 0.1, "rk4"),
        [np.array([1.0, 0.0])],
    ),
    "foucault_analytic_solution": (
        lambda q0, v0, t: _core.foucault_analytic_solution(q0, v0, 1.0, 0.1, t),
        [np.array([1.0, 0.0]), np.array([0.0, 0.1]), np.linspace(0.0, 2.0, 5)],
    ),
    "eulers_disk_theta_analytic": (
        lambda t: _core.eulers_disk_theta_analytic(t, 0.5, 0.05),
        [np.linspace(0.0, 2.0, 5)],
    ),
    "spin_reversal_time": (
        lambda t, spin: _core.spin_reversal_time(t, spin),
        [np.linspace(0.0, 10.0, 101), np.cos(np.linspace(0.0, 10.0, 101))],
    ),
    "projectile_analytic_trajectory": (
        lambda t: _core.projectile_analytic_trajectory(20.0, 45.0, 9.81, t, 0.0),
        [np.linspace(0.0, 2.0, 5)],
    ),
}


def test_every_array_function_is_covered() -> None:
    """The table names every module-level function whose stub takes a float64 array."""
    stub = (inspect.getfile(_core).rsplit("/", 1)[0]) + "/_core.pyi"
    takes_array = set()
    with open(stub) as f:
        for line in f:
            if line.startswith("def ") and "(" in line:
                name, args = line[4:].split("(", 1)
                if "_ArrayF64" in args.split(")")[0] or "_MatrixF64" in args.split(")")[0]:
                    takes_array.add(name)
    assert takes_array == set(FUNCTION_CASES)


@pytest.mark.parametrize("name", sorted(FUNCTION_CASES))
def test_functions_read_every_layout(name: str) -> None:
    call, arrays = FUNCTION_CASES[name]
    plain = outcome(lambda: call(*arrays))
    assert plain[0] == "value", f"the plain call failed: {plain}"
    check_layouts(call, arrays)


def test_callback_results_are_read_at_any_address() -> None:
    """A Python system whose forces and derivatives come back unaligned runs as the aligned
    one does, to the bit (the per-step read of a callback's result)."""
    state = np.array([1.0, 0.0])
    for method in ("verlet", "rk4"):
        plain = _core.integrate_hamiltonian(Oscillator(), state, 0.0, (0.0, 1.0), 0.1, method, 1,
                                            True, np.array([1.0]))
        odd = _core.integrate_hamiltonian(UnalignedOscillator(), state, 0.0, (0.0, 1.0), 0.1,
                                          method, 1, True, np.array([1.0]))
        assert same(plain, odd)
    plain = _core.integrate_ode(Oscillator(), state, 0.0, (0.0, 1.0), 0.1, "rk4")
    odd = _core.integrate_ode(UnalignedOscillator(), state, 0.0, (0.0, 1.0), 0.1, "rk4")
    assert same(plain, odd)


@pytest.mark.parametrize(
    "value, message",
    [
        ([1.0, 0.0, 0.0, 1.0], "numpy array of float64, got list"),
        (np.array([1, 0, 0, 1]), "array of int64"),
        (np.zeros((2, 2)), "got a 2-dimensional array"),
        (np.zeros(4, dtype=np.float32), "array of float32"),
    ],
)
def test_other_inputs_are_refused_by_name(value: Any, message: str) -> None:
    with pytest.raises(TypeError, match=message):
        kepler().energy(value)
