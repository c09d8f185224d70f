"""Ensemble throughput (issue 17): members per second for the double pendulum and Hénon–Heiles
on 1 and 2 threads, the Dask LocalCluster overhead against the local engine, and the wall time
of the flip-time fractal, from which the 1000 x 1000 map is extrapolated.

    .venv/bin/python benchmarks/ensemble_bench.py [--quick]
    .venv/bin/python benchmarks/ensemble_bench.py --dask [ROUNDS]
    .venv/bin/python benchmarks/ensemble_bench.py --fractal [SIDE [T]]

`--dask` runs only the Dask overhead: 1e5 Hénon–Heiles members at 100 and 1000 steps, local
engine (2 threads) and a warm LocalCluster of 2 single-threaded workers in turn, ROUNDS times
(default 5; the order alternates between rounds), with the load average of each round.

`--fractal` runs the flip-time fractal of `examples/flip_fractal.py` at full size (default
1000 x 1000, 10 s; events only, so each member stops once both arms have flipped) once on 1 and
2 threads and on a Dask LocalCluster of 1 and 2 single-threaded workers: its wall time and how
it scales with workers.

Wall times are the best of `REPEAT` runs (a shared machine only ever slows a run down); the
process CPU time is printed beside each, so a loaded machine shows as wall >> CPU / threads.
"""

import os
import sys
import time

import numpy as np

import physicskit.classical as pc

QUICK = "--quick" in sys.argv
REPEAT = 2 if QUICK else 3


def best(fn):
    walls, cpus = [], []
    for _ in range(REPEAT):
        c0, t0 = time.process_time(), time.perf_counter()
        fn()
        walls.append(time.perf_counter() - t0)
        cpus.append(time.process_time() - c0)
    i = int(np.argmin(walls))
    return walls[i], cpus[i]


def double_pendulum(n, t1, threads=None, client=None, events=False):
    """An n x n grid from rest; with `events`, the flip fractal's two events and no final state
    (each member stops once both have fired), as in examples/flip_fractal.py."""
    theta = np.linspace(-3.0, 3.0, n)
    kw = {}
    if events:
        kw = dict(events={"upper": pc.abs_above(0, np.pi), "lower": pc.abs_above(1, np.pi)},
                  final_state=False)
    return pc.ensemble(pc.DoublePendulum([0.0, 0.0], [0.0, 0.0]), (0.0, t1), 0.01, "rk4",
                       grid={"theta0[0]": theta, "theta0[1]": theta}, threads=threads,
                       client=client, **kw)


def henon_heiles(n, t1, threads=None, client=None):
    y = np.linspace(-0.3, 0.3, n)
    states = np.zeros((n, 4))
    states[:, 1] = y
    states[:, 2] = np.sqrt(np.maximum(2 * 0.1 - y**2 + 2 * y**3 / 3, 0.0))  # E = 0.1
    return pc.ensemble(pc.HenonHeilesSystem([0.0, 0.0], [0.0, 0.0]), (0.0, t1), 0.01,
                       "yoshida4", states=states, threads=threads, client=client)


def report(label, members, fn):
    wall, cpu = best(fn)
    print(f"{label}: {members} members, best wall {wall:.3f} s, cpu {cpu:.3f} s, "
          f"{members / wall:,.0f} members/s", flush=True)
    return wall


def fractal(side, t1):
    """The full-size flip fractal once per configuration (each run takes minutes)."""
    import distributed

    print(f"cores: {os.cpu_count()}, load average: {os.getloadavg()}")
    walls = {}
    for threads in (1, 2):
        t0 = time.perf_counter()
        out = double_pendulum(side, t1, threads, events=True)
        walls[f"{threads} thread(s)"] = time.perf_counter() - t0
        print(f"flip fractal {side} x {side}, {t1} s, {threads} thread(s): "
              f"{walls[f'{threads} thread(s)']:.1f} s wall, mean steps per member "
              f"{out.steps.mean():.0f} of {round(t1 / 0.01)}; load {os.getloadavg()[0]:.2f}",
              flush=True)
    for workers in (1, 2):
        with distributed.LocalCluster(n_workers=workers, threads_per_worker=1,
                                      dashboard_address=None, silence_logs=50) as cluster, \
                distributed.Client(cluster) as client:
            double_pendulum(10, 1.0, client=client, events=True)  # warm the workers
            t0 = time.perf_counter()
            double_pendulum(side, t1, client=client, events=True)
            wall = time.perf_counter() - t0
        print(f"flip fractal {side} x {side}, {t1} s, Dask LocalCluster {workers} worker(s): "
              f"{wall:.1f} s wall; load {os.getloadavg()[0]:.2f}", flush=True)


def main():
    if "--dask" in sys.argv:
        rest = sys.argv[sys.argv.index("--dask") + 1:]
        dask_overhead(100000, int(rest[0]) if rest else 5)
        return
    if "--fractal" in sys.argv:
        rest = sys.argv[sys.argv.index("--fractal") + 1:]
        fractal(int(rest[0]) if rest else 1000, float(rest[1]) if len(rest) > 1 else 10.0)
        return
    print(f"cores: {os.cpu_count()}, load average: {os.getloadavg()}")
    side = 50 if QUICK else 100
    dp = {}
    for threads in (1, 2):
        dp[threads] = report(f"double pendulum rk4 1000 steps, {threads} thread(s)", side * side,
                             lambda: double_pendulum(side, 10.0, threads))
    print(f"double pendulum parallel efficiency on 2 threads: {dp[1] / dp[2] / 2:.0%}")
    hh_n = 2000 if QUICK else 10000
    hh = {}
    for threads in (1, 2):
        hh[threads] = report(f"Hénon–Heiles yoshida4 1000 steps, {threads} thread(s)", hh_n,
                             lambda: henon_heiles(hh_n, 10.0, threads))
    print(f"Hénon–Heiles parallel efficiency on 2 threads: {hh[1] / hh[2] / 2:.0%}")

    flip = report(f"flip fractal {side} x {side}, 10 s, events", side * side,
                  lambda: double_pendulum(side, 10.0, events=True))
    print(f"  -> 1000 x 1000 at the same settings: about {flip * (1000 / side) ** 2 / 60:.0f} min "
          "on this machine (linear in members)")

    try:
        import distributed  # noqa: F401
    except ImportError:
        return
    dask_overhead(20000 if QUICK else 100000, 2 if QUICK else 5)


def dask_overhead(n, rounds):
    """Dask LocalCluster against the local engine on the same cores, at 100 and 1000 steps per
    member, interleaved: each round times both, in alternating order, so that a change of load
    hits both alike. The workers are warm (imported, one small ensemble run), as a cluster
    that is used is; the first call on a fresh cluster also pays the workers' imports."""
    import distributed

    print(f"cores: {os.cpu_count()}, load average: {os.getloadavg()}")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None,
                                  silence_logs=50) as cluster, distributed.Client(cluster) as client:
        henon_heiles(1000, 1.0, client=client)  # warm the workers (import, first task)
        for steps in (100, 1000):
            t1 = steps * 0.01
            ratios = []
            for r in range(rounds):
                runs = {"local": lambda: henon_heiles(n, t1),
                        "dask": lambda: henon_heiles(n, t1, client=client)}
                walls = {}
                for name in (("local", "dask") if r % 2 == 0 else ("dask", "local")):
                    t0 = time.perf_counter()
                    runs[name]()
                    walls[name] = time.perf_counter() - t0
                ratios.append(walls["dask"] / walls["local"] - 1)
                print(f"Hénon–Heiles {n} members, {steps} steps, round {r + 1}: load "
                      f"{os.getloadavg()[0]:.2f}, local engine (2 threads) {walls['local']:.3f} s, "
                      f"LocalCluster 2 workers {walls['dask']:.3f} s, Dask overhead "
                      f"{ratios[-1]:+.0%}", flush=True)
            print(f"Dask overhead at {steps} steps: median {np.median(ratios):+.0%}, range "
                  f"{min(ratios):+.0%} to {max(ratios):+.0%}", flush=True)


if __name__ == "__main__":  # Dask's worker processes import this file
    main()
