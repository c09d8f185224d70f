"""The issue-7 workloads through the spec's Python API, runnable against any implementation.

Both physicskit (this repository) and the Numba peer (physicskit 0.4.0 on PyPI) expose
`physicskit.classical` with the spec's names, so this one file serves both; the driver runs it
in each implementation's own virtual environment.

    python workloads.py list
    python workloads.py run CASE STEPS REPEATS     # prints one JSON line
    python workloads.py first CASE                 # import + construct + 1e3 steps, fresh process
    python workloads.py same CASE STEPS REPEATS TARGET
        # ours only (it reads `methods()`): for every fixed-step method the system accepts, the
        # coarsest step of the ladder dt, 2 dt, 4 dt, ... (whole fractions of the workload's
        # span) whose max relative energy error stays <= TARGET, timed best of REPEATS
"""

import json
import sys
import time

import numpy as np


def _cases(pc):
    chain_q0 = 0.5 * np.sin(np.pi * np.arange(1, 17) / 17.0)

    def sine_gordon():
        q0, p0 = pc.SineGordonChain.kink(100, 50.0, velocity=0.2)
        return pc.SineGordonChain(n=100, q0=q0, p0=p0)

    return {
        "projectile": (lambda: pc.ProjectileMotion.from_launch(20.0, 45.0), "yoshida4", 1e-3),
        "kepler": (lambda: pc.KeplerSystem.from_orbital_elements(1.0, 0.5), "yoshida4", 1e-3),
        "kepler_verlet": (lambda: pc.KeplerSystem.from_orbital_elements(1.0, 0.5), "verlet", 1e-3),
        "kepler_pn": (
            lambda: pc.KeplerSystem.from_orbital_elements(1.0, 0.3, c_pn=0.01),
            "yoshida4",
            1e-3,
        ),
        "double_pendulum": (
            lambda: pc.DoublePendulum([2.0, 1.0], [0.5, -0.3]),
            "implicit_midpoint",
            3e-5,
        ),
        "double_pendulum_rk4": (lambda: pc.DoublePendulum([2.0, 1.0], [0.5, -0.3]), "rk4", 3e-5),
        "hoop": (lambda: pc.BeadOnRotatingHoop(0.3, 0.0, omega=3.0), "implicit_midpoint", 2.2e-5),
        "coupled_oscillators": (
            lambda: pc.CoupledOscillators([0.1, -0.2, 0.15], [0.0, 0.0, 0.0]),
            "implicit_midpoint",
            1e-4,
        ),
        "henon_heiles": (lambda: pc.HenonHeilesSystem([0.0, 0.3], [0.3, 0.0]), "yoshida4", 5e-3),
        "swarm": (
            lambda: pc.PendulumSwarm.from_box(1.0, 0.0, 0.05, 0.05, n=200),
            "yoshida4",
            1e-3,
        ),
        "harmonic_chain": (lambda: pc.HarmonicChain(chain_q0, np.zeros(16)), "yoshida4", 1e-2),
        "fput": (
            lambda: pc.FPUTChain(n=32, beta=0.7, mode=1, amplitude=0.5),
            "yoshida4",
            5e-2,
        ),
        "sine_gordon": (sine_gordon, "yoshida4", 1e-2),
        "euler_top": (lambda: pc.EulerTop([0.01, 1.0, 0.01]), "implicit_midpoint", 1e-3),
        "heavy_top": (
            lambda: pc.HeavySymmetricTop([0.0, 0.5, 0.0], [0.0, 0.0, 20.0]),
            "implicit_midpoint",
            5e-5,
        ),
    }


def _run(pc, case, steps, method=None, n=None):
    """One run of `case` over its span `steps * dt`: with the workload's method and step, or
    with `method` in `n` equal steps of the same span. Returns (seconds, max |dE/E0|)."""
    make, default_method, dt = _cases(pc)[case]
    span = steps * dt
    step = dt if n is None else span / n
    system = make()
    start = time.perf_counter()
    result = system.integrate((0.0, span), step, method=method or default_method)
    elapsed = time.perf_counter() - start
    e = np.asarray(result.energy)
    drift = float(np.max(np.abs(e - e[0])) / abs(e[0]))
    return elapsed, drift


def _same_accuracy(pc, case, steps, repeats, target):
    """Per fixed-step method: the fewest steps (halving the count from the workload's) whose
    run stays within `target`, timed best of `repeats`; `None` fields where even the
    workload's step misses it or the system refuses the method."""
    rows = []
    for info in pc.methods():
        if info["adaptive"]:
            continue  # its cost is set by rtol/atol, not by a step: not on this ladder
        name, best_n, n = info["name"], None, steps
        while n >= 1:
            try:
                _, drift = _run(pc, case, steps, name, n)
            except (ValueError, RuntimeError):  # refused, or an implicit solve gave up
                break
            if not drift <= target:
                break
            best_n, n = n, n // 2
        if best_n is None:
            rows.append({"method": name, "steps": None, "seconds": None, "drift": None})
            continue
        best, drift = float("inf"), float("nan")
        for _ in range(repeats):
            elapsed, drift = _run(pc, case, steps, name, best_n)
            best = min(best, elapsed)
        rows.append({"method": name, "steps": best_n, "seconds": best, "drift": drift})
    return rows


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
    case, steps, repeats = argv[2], int(argv[3]), int(argv[4])
    if argv[1] == "same":
        print(json.dumps(_same_accuracy(pc, case, steps, repeats, float(argv[5]))))
        return
    _run(pc, case, 1000)  # warm-up: the peer compiles here
    best, drift = float("inf"), float("nan")
    for _ in range(repeats):
        elapsed, drift = _run(pc, case, steps)
        best = min(best, elapsed)
    print(json.dumps({"ns_per_step": best * 1e9 / steps, "drift": drift}))


if __name__ == "__main__":
    main(sys.argv)
