"""The peer-comparison workloads through the spec's Python API, runnable against any implementation.

Both physicskit (this repository) and the Numba peer (physicskit 0.4.0 on PyPI) expose
`physicskit.classical` with the spec's names, so this one file serves both; the driver runs it
in each implementation's own virtual environment.

    python workloads.py list
    python workloads.py run CASE STEPS REPEATS     # prints one JSON line
    python workloads.py first CASE                 # import + construct + 1e3 steps, fresh process
    python workloads.py same CASE STEPS REPEATS TARGET FINAL
        # ours only (it reads `methods()`): for every fixed-step method the system accepts, the
        # fewest equal steps over the workload's span, on the ladder STEPS, STEPS // 2,
        # STEPS // 4, ..., 1 (each count half the last, rounded down), whose max relative
        # energy error stays <= TARGET and whose final state is as close to a reference run as
        # the peer's (FINAL: the peer's final state as JSON), timed best of REPEATS. Prints
        # {"peer_final_error": ..., "methods": [one row per method]}
    python workloads.py final CASE STEPS           # the final state of the workload's run, JSON
"""

import json
import sys
import time
from pathlib import Path

import numpy as np


# The cases: the one table, which benchmarks/src/workloads.rs reads too.
TABLE = json.loads((Path(__file__).resolve().parent / "workloads.json").read_text())["cases"]


def _argument(pc, value):
    """A table argument: a JSON value, or one of the table's generated starts (its `about`)."""
    if not isinstance(value, dict):
        return value
    if "sine_mode" in value:
        # The formula of the library's `systems::sine_mode` (FPUTChain's start, which the Rust
        # workloads call), written out here because this file also runs in the peer's
        # environment, whose API has no mode shape to call.
        mode = value["sine_mode"]
        wave = np.pi * mode["mode"] / (mode["n"] + 1)
        return mode["amplitude"] * np.sin(wave * np.arange(1, mode["n"] + 1))
    if "kink" in value:
        return pc.SineGordonChain.kink(**value["kink"])[value["part"]]
    raise ValueError(f"unknown start in workloads.json: {value}")


def _cases(pc):
    """Each case's (constructor, method, dt), the constructor calling the system by its Python
    name with the table's keyword arguments."""
    cases = {}
    for case in TABLE:
        owner, _, constructor = case["system"].partition(".")
        make = getattr(getattr(pc, owner), constructor) if constructor else getattr(pc, owner)

        def build(make=make, args=case["args"]):
            return make(**{key: _argument(pc, value) for key, value in args.items()})

        cases[case["name"]] = (build, case["method"], case["dt"])
    return cases


def _run(pc, case, steps, method=None, n=None):
    """One run of `case` over its span `steps * dt`: with the workload's method and step, or
    with `method` in `n` equal steps of the same span. Returns (seconds, max |dE/E0|,
    final state)."""
    make, default_method, dt = _cases(pc)[case]
    span = steps * dt
    step = dt if n is None else span / n
    system = make()
    start = time.perf_counter()
    result = system.integrate((0.0, span), step, method=method or default_method)
    elapsed = time.perf_counter() - start
    e = np.asarray(result.energy)
    drift = float(np.max(np.abs(e - e[0])) / abs(e[0]))
    return elapsed, drift, np.asarray(result.y)[-1]


# The reference's tolerances: dop853 at rtol 1e-13 is some two orders below the closest final
# states compared here (ERROR_FLOOR), and independent of every fixed-step method.
REFERENCE_RTOL, REFERENCE_ATOL = 1e-13, 1e-15
# Final-state errors below this are the reference's own level, where comparing is noise.
ERROR_FLOOR = 1e-11
# Energy errors below this are rounding: 1e5 steps each rounding E at ~1e-16 relative random-walk
# to ~3e-14, so a peer figure of 3e-14 against ours of 4e-14 says nothing about either method.
ENERGY_FLOOR = 1e-13


def _reference(pc, case, steps):
    make, _, dt = _cases(pc)[case]
    span = steps * dt
    result = make().integrate_sampled(
        (0.0, span), span, "dop853", rtol=REFERENCE_RTOL, atol=REFERENCE_ATOL
    )
    return np.asarray(result.y)[-1]


def _error(final, reference):
    return float(np.max(np.abs(final - reference)) / max(np.max(np.abs(reference)), 1e-300))


def _ladder(steps):
    """The step counts tried: `steps`, then each half the last (rounded down), down to 1."""
    n = steps
    while n >= 1:
        yield n
        n //= 2


def _fewest_steps(pc, case, steps, method, passes):
    """The last count of `_ladder(steps)` at which `method` passes (`passes(drift, final)`)
    before its first failure, or None if it fails at `steps` already or the system refuses it.
    The search stops at the first failure: a coarser step that passed again would be luck
    (a resonance, a cancelling error), not accuracy."""
    fewest = None
    for n in _ladder(steps):
        try:
            _, drift, final = _run(pc, case, steps, method, n)
        except (ValueError, RuntimeError):  # refused, or an implicit solve gave up
            break
        if not passes(drift, final):
            break
        fewest = n
    return fewest


def _same_accuracy(pc, case, steps, repeats, target, peer_final):
    """Per fixed-step method: the fewest steps (`_fewest_steps`) whose run stays within
    `target` in energy and within the peer's final-state error of the reference run, timed best
    of `repeats`; `None` fields where even the workload's step misses it or the system refuses
    the method. Energy alone would crown a single step of the implicit midpoint rule on a
    linear system, whose quadratic energy it keeps exactly at any step."""
    reference = _reference(pc, case, steps)
    peer_error = _error(np.asarray(peer_final), reference)
    bar = max(peer_error, ERROR_FLOOR)
    target = max(target, ENERGY_FLOOR)

    def passes(drift, final):
        return drift <= target and _error(final, reference) <= bar

    rows = []
    for info in pc.methods():
        if info["adaptive"]:
            continue  # its cost is set by rtol/atol, not by a step: not on this ladder
        name = info["name"]
        n = _fewest_steps(pc, case, steps, name, passes)
        if n is None:
            rows.append({"method": name, "steps": None, "seconds": None, "drift": None,
                         "final_error": None})
            continue
        best = float("inf")
        for _ in range(repeats):
            elapsed, drift, final = _run(pc, case, steps, name, n)
            best = min(best, elapsed)
        rows.append({"method": name, "steps": n, "seconds": best, "drift": drift,
                     "final_error": _error(final, reference)})
    return {"peer_final_error": peer_error, "methods": rows}


def main(argv):
    if argv[1] == "first":
        start = time.perf_counter()
        import physicskit.classical as pc

        _run(pc, argv[2], 1000)
        print(json.dumps({"first_call_s": time.perf_counter() - start}))
        return
    import physicskit.classical as pc

    if argv[1] == "list":
        print(" ".join(_cases(pc)))
        return
    if argv[1] == "final":
        print(json.dumps(_run(pc, argv[2], int(argv[3]))[2].tolist()))
        return
    case, steps, repeats = argv[2], int(argv[3]), int(argv[4])
    if argv[1] == "same":
        peer_final = json.loads(argv[6])
        print(json.dumps(_same_accuracy(pc, case, steps, repeats, float(argv[5]), peer_final)))
        return
    _run(pc, case, 1000)  # warm-up: the peer compiles here
    best, drift = float("inf"), float("nan")
    for _ in range(repeats):
        elapsed, drift, _ = _run(pc, case, steps)
        best = min(best, elapsed)
    print(json.dumps({"ns_per_step": best * 1e9 / steps, "drift": drift}))


if __name__ == "__main__":
    main(sys.argv)
