"""Cost of the tangent dynamics per step relative to the orbit alone, and chaos-map
throughput (orbits per second), through the Python API. Best of REPEATS wall-clock runs, so
the figures are only as quiet as the machine: say how loaded it was when quoting them.

    python benchmarks/chaos_bench.py
"""

import os
import time

import numpy as np

import physicskit.classical as pc

REPEATS = 5
T_END, DT = 200.0, 0.01  # 2e4 steps


def hh():
    return pc.HenonHeilesSystem([0.0, 0.0], [0.1, np.sqrt(2.0 / 6.0 - 0.01)])


def best(run):
    times = []
    for _ in range(REPEATS):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return min(times)


def per_step(name, system, method, run):
    steps = T_END / DT
    t = best(run) / steps * 1e9
    print(f"  {name:<34} {t:8.1f} ns/step")
    return t


def main():
    print(f"cores visible: {os.cpu_count()}, load average: {os.getloadavg()}")
    for method in ["yoshida4", "rk4"]:
        print(f"Hénon–Heiles, {method}, {int(T_END / DT)} steps:")
        base = per_step("orbit (integrate, final only)", hh(), method,
                        lambda: hh().integrate_sampled((0, T_END), DT, method, final_only=True))
        for k in (1, 4):
            t = per_step(f"lyapunov_spectrum, {k} vector(s)", hh(), method,
                         lambda: pc.lyapunov_spectrum(hh(), (0, T_END), DT, n_exponents=k,
                                                      method=method))
            print(f"    ratio to the orbit: {t / base:.1f}")
        t = per_step("sali (2 vectors)", hh(), method,
                     lambda: pc.sali(hh(), (0, T_END), DT, method=method))
        print(f"    ratio to the orbit: {t / base:.1f}")
    e = 1.0 / 8.0
    n = 64
    ys = np.linspace(-0.3, 0.3, n)
    states = np.array([[0.0, y, 0.0, np.sqrt(2 * (e - 0.5 * y * y + y**3 / 3))] for y in ys])
    for indicator in ("lyapunov", "sali"):
        t = best(lambda: pc.chaos_map(hh(), states, (0, 100.0), 0.01, indicator=indicator))
        print(f"chaos_map {indicator}, {n} orbits of 1e4 yoshida4 steps: {n / t:.0f} orbits/s")


if __name__ == "__main__":
    main()
