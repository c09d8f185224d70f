"""Ensembles and parameter sweeps of a built-in system or a SymPy engine's system, on all
cores or on a Dask cluster.

>>> import numpy as np
>>> from physicskit.classical import DoublePendulum, ensemble, abs_above
>>> theta = np.linspace(-3, 3, 5)
>>> out = ensemble(DoublePendulum(theta0=[0, 0], thetadot0=[0, 0]), (0, 2), 0.01,
...                grid={"theta0[0]": theta, "theta0[1]": theta},
...                events={"flip": abs_above(1, np.pi)})
>>> out.events["flip"].shape
(5, 5)

Every member of a built-in system is built through the catalogue from the system's
constructor arguments, with the swept values in place; a member of a SymPy engine's system
(:class:`~physicskit.classical.utils.LagrangianEngine`,
:class:`~physicskit.classical.utils.HamiltonianEngine`,
:class:`~physicskit.classical.utils.ODEEngine`) is built natively from the engine's compiled
expressions with its parameter values and initial state. Each is checked before any
integration (a bad member raises ``ValueError`` naming its index in the flattened member list).
The Rust engine integrates each member with its own ``integrate`` loop, so a member's results
equal a single ``integrate`` of it bit for bit, on any number of threads and any split of the
members over Dask workers.

>>> import sympy as sp
>>> from physicskit.classical.utils import ODEEngine
>>> x, y, z, rho = sp.symbols("x y z rho")
>>> lorenz = ODEEngine([x, y, z], [10 * (y - x), x * (rho - z) - y, x * y - 8 * z / 3],
...                    params={rho: 28.0})
>>> out = ensemble(lorenz.system([1.0, 1.0, 1.0]), (0, 1), 0.01, "rk4",
...                grid={"rho": [0.5, 14.0, 28.0]})
>>> out.final_state.shape
(3, 3)

``client=distributed.Client(...)`` splits the members into chunks that the workers run with
the same engine; a worker lost mid-run costs only its chunks, which Dask runs again (an
engine's system travels as its compiled expressions: the workers need no SymPy). Dask is
optional (``pip install physicskit[distributed]``) and imported only when a client is given.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field
from typing import Any, Callable, Mapping, Sequence, cast

import numpy as np

from ._native import _core, as_array, as_flag, as_int, as_scalar, as_t_span, as_vector

__all__ = ["ensemble", "EnsembleResult", "crossing", "abs_above"]

EventSpec = tuple[int, str, float]


def crossing(index: int, value: float = 0.0, direction: str = "either") -> EventSpec:
    """Event: entry ``index`` of the state (``[q, p]``; ``[q, qdot]`` for Lagrangian systems)
    crosses ``value``; ``direction`` is ``"either"``, ``"rising"`` or ``"falling"``."""
    kinds = {"either": "crosses", "rising": "rising", "falling": "falling"}
    if not isinstance(direction, str) or direction not in kinds:
        raise ValueError(f"direction must be one of {sorted(kinds)}, got {direction!r}")
    return (as_int("index", index), kinds[direction], as_scalar("value", value))


def abs_above(index: int, value: float) -> EventSpec:
    """Event: ``|state[index]| > value`` (a double pendulum flips when ``|theta2| > pi``:
    ``abs_above(1, np.pi)``)."""
    return (as_int("index", index), "abs_above", as_scalar("value", value))


@dataclass
class EnsembleResult:
    """Outputs of :func:`ensemble`, shaped by the member grid ``shape``.

    ``final_state``: ``shape + (state length,)``; ``trajectory`` (with ``stride``):
    ``shape + (samples, state length)`` at times ``t``; ``energy_error`` (with
    ``energy_error=True``): ``max |E - E0| / |E0|`` per member; ``events``: the first time of
    each named event per member (``NaN``: never, ``t0``: already at the start);
    ``max_lyapunov`` and ``sali`` (with ``max_lyapunov=True``, ``sali=True``): the largest
    Lyapunov exponent and SALI at ``t_span[1]`` per member; ``steps``: the steps each member
    took (fewer than the span's for members stopped early, see :func:`ensemble`).
    ``final_state`` is ``None`` when ``final_state=False`` was asked.
    """

    shape: tuple[int, ...]
    method: str
    final_state: np.ndarray | None
    t: np.ndarray | None = None
    trajectory: np.ndarray | None = None
    energy_error: np.ndarray | None = None
    events: dict[str, np.ndarray] = field(default_factory=dict)
    max_lyapunov: np.ndarray | None = None
    sali: np.ndarray | None = None
    steps: np.ndarray | None = None


def _system_spec(system: Any) -> tuple[str | dict[str, Any], dict[str, Any]]:
    """What ``_core.ensemble`` builds the members from: the catalogue name and the constructor
    values of ``system`` (an instance of a built-in class, or a catalogue name for its
    defaults), or the native description of a SymPy engine's system (its expressions,
    parameters and current state) with no constructor values."""
    if isinstance(system, str):
        return system, {}
    from .core import DynamicalSystem, LagrangianSystem
    from .utils.symbolic import HamiltonianEngine, LagrangianEngine, ODEEngine

    if not isinstance(system, DynamicalSystem):
        raise TypeError(
            f"system must be a built-in system, a SymPy engine's system or a catalogue name, "
            f"got {system!r}"
        )
    native = getattr(system, "_native", None)
    module = type(system).__module__ or ""
    builtin = module.startswith("physicskit.")
    engine = getattr(system, "engine", None)
    # A LagrangianSystem subclass given an engine runs natively (its documented use); other
    # subclasses of an engine's system class are Python subclasses like any other.
    if isinstance(engine, (LagrangianEngine, HamiltonianEngine, ODEEngine)) and (
        builtin or (isinstance(system, LagrangianSystem) and isinstance(engine, LagrangianEngine))
    ):
        spec = engine._native_spec()
        spec["state"] = as_vector("state", system.state)
        return spec, {}
    if native is None or not builtin:
        raise TypeError(
            f"ensemble runs built-in systems and SymPy engines' systems only; "
            f"{type(system).__name__} is a Python subclass, whose methods are Python callbacks "
            "that hold the GIL and cannot run on the engine's threads or workers. Write it with "
            "a SymPy engine (physicskit.classical.utils), or integrate it member by member "
            "with .integrate()"
        )
    params = native.params
    if params is None:
        raise TypeError(f"{type(system).__name__} has no catalogue entry to build members from")
    return native.name, dict(params)


def _members(
    grid: Mapping[str, Sequence[float]] | None,
    sweep: Mapping[str, Any] | None,
    states: Any,
) -> tuple[tuple[int, ...], list[tuple[str, np.ndarray]], np.ndarray | None]:
    """The member shape, flattened sweeps and flattened states."""
    if grid is not None and sweep is not None:
        raise ValueError("give either grid (a Cartesian product) or sweep (zipped arrays)")
    for arg, value in (("grid", grid), ("sweep", sweep)):
        if value is not None and not isinstance(value, Mapping):
            raise TypeError(f"{arg} must be a dict of parameter name -> values, got {value!r}")
    columns: list[tuple[str, np.ndarray]] = []
    shape: tuple[int, ...] | None = None
    # Names as strings: an engine's parameter may be given by its SymPy symbol.
    if grid is not None:
        axes = []
        for name, values in grid.items():
            a = as_array(f"grid[{name!r}]", values)
            if a.ndim != 1 or a.size == 0:
                raise ValueError(f"grid[{name!r}] must be a non-empty 1-D sequence")
            axes.append(a)
        shape = tuple(a.size for a in axes)
        meshes = np.meshgrid(*axes, indexing="ij")
        columns = [(str(name), m.ravel()) for name, m in zip(grid, meshes)]
    if sweep is not None:
        for name, values in sweep.items():
            a = as_array(f"sweep[{name!r}]", values)
            if shape is None:
                shape = a.shape
            if a.shape != shape:
                raise ValueError(f"sweep[{name!r}] has shape {a.shape}, expected {shape}")
            columns.append((str(name), np.ascontiguousarray(a.ravel())))
    flat_states = None
    if states is not None:
        s = as_array("states", states)
        if s.ndim < 2:
            raise ValueError("states must have shape members_shape + (state length,)")
        if shape is None:
            shape = s.shape[:-1]
        if s.shape[:-1] != shape:
            raise ValueError(f"states has shape {s.shape}, expected {shape} + (state length,)")
        flat_states = np.ascontiguousarray(s.reshape(-1, s.shape[-1]))
    if shape is None:
        raise ValueError("no members: give grid, sweep or states")
    return shape, columns, flat_states


@dataclass
class _Job:
    """Members and run settings, as ``_core.ensemble`` takes them (plain data that pickles to
    Dask workers: a catalogue name, or an engine's system as its compiled expressions)."""

    system: str | dict[str, Any]
    common: dict[str, Any]
    sweeps: list[tuple[str, np.ndarray]]
    states: np.ndarray | None
    n: int
    run: dict[str, Any]

    def part(self, start: int, stop: int) -> _Job:
        """Members ``start:stop``."""
        return _Job(
            self.system,
            self.common,
            [(k, v[start:stop]) for k, v in self.sweeps],
            None if self.states is None else self.states[start:stop],
            stop - start,
            self.run,
        )

    def __call__(self, **extra: Any) -> dict[str, Any]:
        """Runs the members on the local engine (what a Dask worker does with a part).

        Dask's deserialization can place a small array at any byte offset of its message: the
        engine reads an array of any address, strides and byte order (``_core``'s one reader
        copies what it cannot read in place)."""
        return dict(
            _core.ensemble(self.system, self.common, self.sweeps, self.states, self.n,
                           **self.run, **extra)
        )


class _Bar:
    """A progress bar on stderr."""

    def __init__(self) -> None:
        self.shown = -1

    def __call__(self, done: int, total: int) -> None:
        percent = 100 * done // max(total, 1)
        if percent != self.shown:
            self.shown = percent
            filled = percent // 4
            sys.stderr.write(f"\r[{'#' * filled}{'.' * (25 - filled)}] {done}/{total} members")
            sys.stderr.flush()

    def close(self) -> None:
        sys.stderr.write("\n")
        sys.stderr.flush()


def ensemble(
    system: Any,
    t_span: tuple[float, float],
    dt: float,
    method: str | None = None,
    *,
    grid: Mapping[str, Sequence[float]] | None = None,
    sweep: Mapping[str, Any] | None = None,
    states: Any = None,
    stride: int | None = None,
    energy_error: bool = False,
    events: Mapping[str, EventSpec] | None = None,
    max_lyapunov: bool = False,
    sali: bool = False,
    renormalize_every: int = 10,
    final_state: bool = True,
    progress: bool | Callable[[int, int], None] = False,
    threads: int | None = None,
    client: Any = None,
    chunk_size: int | None = None,
    rtol: float | None = None,
    atol: float | None = None,
    max_steps: int | None = None,
) -> EnsembleResult:
    """Integrates an ensemble of ``system``: a built-in system, whose constructor arguments all
    members share; a catalogue name, for its defaults; or a system of a SymPy engine
    (``LagrangianEngine``, ``HamiltonianEngine``, ``ODEEngine``: ``engine.system(...)``),
    whose members share the engine's expressions and parameter values and start from the
    system's current ``state``.

    Members: ``grid`` (name -> 1-D values, the Cartesian product in ``indexing="ij"`` order:
    the outputs have shape ``(len, len, ...)``), or ``sweep`` (name -> arrays of one shape,
    zipped), and/or ``states`` (``shape + (state length,)`` initial states). A name is a real or
    integer parameter (``"c_pn"``) or one entry of a vector parameter (``"theta0[1]"``); for an
    engine's system, a key of the engine's ``params`` (its name or its SymPy symbol). An
    unknown name is refused with the list of valid ones.

    Keeps per member the final state, the trajectory every ``stride`` steps, the maximum
    relative energy error (``energy_error=True``) and the first time of each event in
    ``events`` (name -> :func:`crossing` or :func:`abs_above`), located inside its step to the
    method's order.

    ``max_lyapunov=True`` and ``sali=True`` keep the largest Lyapunov exponent and SALI of each
    member at ``t_span[1]``, from the same loops as :func:`max_lyapunov` and :func:`sali` (each
    member's value is ``max_lyapunov(member, ...).exponents[0]`` and ``sali(member,
    ...).index[-1]`` bit for bit), renormalizing every ``renormalize_every`` steps. Their
    deviation vectors are followed in a run of their own beside the member's ``integrate``
    (engines' systems get their tangent dynamics by automatic differentiation). SALI above
    :data:`CHAOS_THRESHOLD` (1e-8) says the orbit stayed regular over the span. They need a
    fixed-step method: an adaptive one (``dop853``) is refused before any work.

    Against :func:`chaos_map` on the same states: ``max_lyapunov`` equals its
    ``indicator="lyapunov"`` bit for bit. ``sali`` does not: ``chaos_map`` stops a point once
    SALI falls below its floor ``SALI_FLOOR`` = 1e-14 (the orbit classified long before, only
    rounding left) and returns that value, while the ensemble follows every member to
    ``t_span[1]`` like :func:`sali` does, so a chaotic member's SALI can be exactly ``0.0``
    (its deviation vectors aligned to rounding) where ``chaos_map`` gives about 1e-14. The two
    agree on every verdict against :data:`CHAOS_THRESHOLD`.

    ``rtol``, ``atol`` and ``max_steps``: the tolerances and step budget of an adaptive method
    (``"dop853"``, ``"taylor"``) for every member, as ``integrate_sampled`` takes them
    (finite and > 0; an integer >= 1; ``None``, the default, means ``1e-10``, ``1e-12`` and ten
    million); each member's results then equal its own ``integrate_sampled`` with the same
    tolerances bit for bit. A fixed-step method has none: giving any with one is a
    ``ValueError``, as is a value that is not a finite number > 0 (an integer >= 1).

    ``final_state=False`` keeps no final states (another output must then be asked); when only
    ``events`` are asked (no ``stride``, no other reduction) each member then stops at its last
    event, with the same event times as the full run (a flip-time map costs the time to each
    flip, not the span).

    ``progress``: ``True`` for a bar on stderr, or a callable ``(done, total)`` (members; with
    a ``client``, called as chunks finish). ``threads``:
    worker threads (default: one per core). ``client``: a ``distributed.Client``; the members
    are split into chunks of ``chunk_size`` members run by its workers (default: large chunks
    first, then smaller ones, the last about 1/32 of a worker core's share, so that the cores
    finish together), each chunk's outputs fetched as soon as it is done. Results are
    bit-identical whatever ``threads``, ``client`` and ``chunk_size``; a member failing during
    its run raises the same error as locally (the lowest failing member's).

    Raises ``ValueError`` for a bad argument or member (named by its flattened index) before
    any integration, ``TypeError`` for Python subclasses (their callbacks hold the GIL; a SymPy
    engine runs the same system natively).
    """
    source, common = _system_spec(system)
    shape, sweeps, flat_states = _members(grid, sweep, states)
    n = math.prod(shape)
    if n == 0:
        raise ValueError("the member grid is empty")
    run: dict[str, Any] = {
        "t_span": as_t_span(t_span),
        "dt": as_scalar("dt", dt),
        "method": _method(method),
        "stride": None if stride is None else as_int("stride", stride, minimum=1),
        "energy_error": as_flag("energy_error", energy_error),
        "events": _events(events),
        "final_state": as_flag("final_state", final_state),
        "rtol": None if rtol is None else as_scalar("rtol", rtol),
        "atol": None if atol is None else as_scalar("atol", atol),
        "max_steps": None if max_steps is None else as_int("max_steps", max_steps, minimum=1),
    }
    every = as_int("renormalize_every", renormalize_every, minimum=1)
    for key, value in (("max_lyapunov", max_lyapunov), ("sali", sali)):
        run[key] = every if as_flag(key, value) else None
    outputs = ("stride", "energy_error", "events", "max_lyapunov", "sali")
    if not run["final_state"] and not any(run[k] for k in outputs):
        raise ValueError(
            "final_state=False with nothing else asked leaves no output: ask for stride, "
            "energy_error=True, events, max_lyapunov=True or sali=True, or keep final_state"
        )
    if threads is not None:
        threads = as_int("threads", threads, minimum=1, maximum=_core.MAX_THREADS)
    if chunk_size is not None:
        chunk_size = as_int("chunk_size", chunk_size, minimum=1)
    if not (isinstance(progress, (bool, np.bool_)) or callable(progress)):
        raise TypeError(f"progress must be True, False or a callable (done, total), got {progress!r}")
    if client is not None and not hasattr(client, "submit"):
        raise TypeError(f"client must be a distributed.Client, got {client!r}")
    event_names = list(events or {})
    job = _Job(source, common, sweeps, flat_states, n, run)
    bar = _Bar() if progress is True else None
    callback = bar if bar is not None else (progress if callable(progress) else None)
    try:
        if client is None:
            out = job(threads=threads, progress=callback)
        else:
            out = _distributed(client, job, chunk_size, callback)
    finally:
        if bar is not None:
            bar.close()
    return _shape(out, shape, run, event_names)


def _method(method: Any) -> str | None:
    if method is None or isinstance(method, str):
        return method
    raise ValueError(f"method must be a method name (a str) or None, got {method!r}")


def _events(events: Any) -> list[EventSpec]:
    """The events' ``(index, kind, value)`` in order, checked."""
    if events is None:
        return []
    if not isinstance(events, Mapping):
        raise TypeError(f"events must be a dict of name -> crossing(...)/abs_above(...), got {events!r}")
    out = []
    for key, e in events.items():
        if not (isinstance(e, tuple) and len(e) == 3 and isinstance(e[1], str)):
            raise ValueError(f"events[{key!r}] must be made by crossing(...) or abs_above(...), got {e!r}")
        out.append((as_int(f"events[{key!r}] index", e[0]), e[1], as_scalar(f"events[{key!r}] value", e[2])))
    return out


def _run_part(part: _Job) -> dict[str, Any]:
    """A chunk on a Dask worker, on one thread: the worker's own threads run as many chunks at
    once as it has (the native call releases the GIL), so a host with several worker processes
    is not oversubscribed by each chunk spreading over all its cores. Its members were checked
    by the client before any chunk was sent (``prechecked``: the worker does not build each
    member once more to check it before building it to run it).

    A failure that is not an ``Exception`` (the engine's ``PanicException``, a
    ``KeyboardInterrupt`` or ``SystemExit`` raised in the task) is raised as a
    ``RuntimeError`` naming it: a Dask worker reports only an ``Exception`` to the client as the
    task's error, and leaves the task running forever after any other."""
    try:
        return part(threads=1, prechecked=True)
    except Exception:
        raise
    except BaseException as e:
        raise RuntimeError(
            f"a chunk of {part.n} members of the ensemble failed on its Dask worker: "
            f"{type(e).__name__}: {e}"
        ) from None


#: The smallest default chunk holds about 1/``_SMALLEST`` of a worker core's share of the
#: members: the last chunks, which decide when the run ends, are that small.
_SMALLEST = 32


def _chunks(n: int, cores: int, chunk_size: int | None) -> list[tuple[int, int]]:
    """The members' ranges ``[start, stop)``, in the order they should run: ``chunk_size``
    each when given; by default by *factoring* (Hummel, Schonberg & Flynn, "Factoring: a
    method for scheduling parallel loops", CACM 35(8), 1992): batches of ``cores`` equal
    chunks, each batch holding half the members left, down to chunks of about
    ``1/_SMALLEST`` of a core's share. Most members go in a few large chunks (little
    per-task cost), and the last chunks are small, so every core finishes within a small
    chunk of the others even when members differ in cost (a flip fractal's members stop at
    their flips) or a worker runs slower than the others."""
    if chunk_size is not None:
        return [(start, min(n, start + chunk_size)) for start in range(0, n, chunk_size)]
    smallest = max(1, math.ceil(n / (_SMALLEST * cores)))
    out: list[tuple[int, int]] = []
    start = 0
    while start < n:
        size = max(smallest, math.ceil((n - start) / (2 * cores)))
        for _ in range(cores):
            if start < n:
                out.append((start, min(n, start + size)))
                start = out[-1][1]
    return out


def _distributed(
    client: Any,
    job: _Job,
    chunk_size: int | None,
    progress: Callable[[int, int], None] | None = None,
) -> dict[str, Any]:
    """Runs the members in chunks on ``client``'s workers and concatenates the chunks;
    ``progress(members done, members)`` is called as chunks finish."""
    from distributed import as_completed

    # Every member is built and checked here before anything is shipped.
    job(check_only=True)
    cores = sum(client.ncores().values()) or 1
    chunks = _chunks(job.n, cores, chunk_size)
    # The scheduler starts the chunks in this order (larger first, by factoring).
    futures = [
        client.submit(_run_part, job.part(start, stop), pure=False, priority=len(chunks) - k)
        for k, (start, stop) in enumerate(chunks)
    ]
    index = {future.key: k for k, future in enumerate(futures)}
    parts: list[dict[str, Any] | None] = [None] * len(futures)
    failed: int | None = None
    try:
        # Each chunk's outputs are fetched as soon as it is done, while the others run.
        for batch in as_completed(futures).batches():
            done = []
            for future in batch:
                k = index[future.key]
                if future.status == "finished":
                    done.append(future)
                elif failed is None or k < failed:
                    # An error (or a chunk cancelled from elsewhere). The local run raises the
                    # lowest member's error: wait for the chunks before this one (one of them
                    # may fail too), not for those after.
                    failed = k
                    client.cancel([f for f in futures[k + 1:] if not f.done()])
            if failed is None and done:
                for future, part in zip(done, client.gather(done)):
                    parts[index[future.key]] = part
                if progress is not None:
                    progress(sum(stop - start for (start, stop), part in zip(chunks, parts)
                                 if part is not None), job.n)
        if failed is not None:
            futures[failed].result()  # raises the chunk's error
    except BaseException:
        client.cancel([f for f in futures if not f.done()])
        raise
    # Every chunk finished and was fetched (a failed one raised above).
    got = cast(list[dict[str, Any]], parts)
    first = got[0]
    out: dict[str, Any] = {
        "method": first["method"],
        "t": first["t"],
        "final_state": np.concatenate([p["final_state"] for p in got]),
        "steps": np.concatenate([p["steps"] for p in got]),
        "trajectory": None
        if first["trajectory"] is None
        else np.concatenate([p["trajectory"] for p in got]),
        "reductions": {
            name: [np.concatenate([p["reductions"][name][k] for p in got])
                   for k in range(len(arrays))]
            for name, arrays in first["reductions"].items()
        },
    }
    return out


def _shape(
    out: Mapping[str, Any], shape: tuple[int, ...], run: Mapping[str, Any], event_names: list[str]
) -> EnsembleResult:
    """The engine's member-major outputs reshaped to the member grid; the reductions by the
    engine's names (each a list of arrays: one per event for ``event_time``)."""
    final = np.asarray(out["final_state"])
    reductions = {
        name: [np.asarray(a).reshape(shape) for a in arrays]
        for name, arrays in out["reductions"].items()
    }

    def one(name: str) -> np.ndarray | None:
        return reductions[name][0] if name in reductions else None

    energy = one("max_energy_error")
    events = dict(zip(event_names, reductions.get("event_time", []), strict=True))
    chaos = {k: one(k) for k in ("max_lyapunov", "sali")}
    trajectory = out["trajectory"]
    return EnsembleResult(
        shape=shape,
        method=out["method"],
        final_state=final.reshape(shape + final.shape[1:]) if run["final_state"] else None,
        steps=np.asarray(out["steps"]).reshape(shape),
        t=out["t"],
        trajectory=None if trajectory is None else trajectory.reshape(shape + trajectory.shape[1:]),
        energy_error=energy,
        events=events,
        max_lyapunov=chaos["max_lyapunov"],
        sali=chaos["sali"],
    )
