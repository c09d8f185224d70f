"""Time to accuracy: our adaptive Taylor method against heyoka, on the same workloads, in one run.

Run by ``benchmarks/heyoka_compare.sh`` (it makes heyoka's venv under /tmp and builds our
side, the ``heyoka_taylor`` binary, in release). For each workload and each tolerance
1e-6 ... 1e-16 (rtol = atol = tol for us, heyoka's single ``tol``) both integrators run, each
the best wall time of five after one untimed run (ours with its recurrences compiled by the
JIT, and interpreted for comparison; the compile times of both sides are printed); errors are measured against a reference in
extended precision: heyoka in real128 where its build has it, else in x87 long double (64-bit
mantissa) at tolerance 1e-19, and the closed form for Kepler. The table then gives, for each of
heyoka's runs, our cheapest run with an error at most heyoka's, and the ratio of the times
(heyoka's over ours: above 1 we are faster).

Workloads (the same starts as ``benchmarks/src/bin/heyoka_taylor.rs``):
  kepler     e = 0.5, a = 1 from perihelion, 100 orbits: final-state error (closed form)
  hh-state   Hénon–Heiles E = 1/6 from q = (0, 0.1), p_x = 0.4, t = 100: final-state error
  hh-energy  the same start, t = 1000: largest energy error on a grid of unit spacing
  pendulum   double pendulum from rest at (2, 1.5) rad, t = 10, state (q, p): final error

Usage: heyoka_compare.py PATH_TO_heyoka_taylor
"""

import json
import math
import subprocess
import sys
import time

import heyoka as hy
import numpy as np

TOLERANCES = [1e-6, 1e-8, 1e-10, 1e-12, 1e-14, 1e-16]
REPEATS = 5


def systems():
    """The heyoka equations and starts of each workload."""
    x, y, px, py = hy.make_vars("x", "y", "px", "py")
    r3 = (x**2 + y**2) ** -1.5
    kepler = [(x, px), (y, py), (px, -x * r3), (py, -y * r3)]
    hh = [(x, px), (y, py), (px, -x - 2.0 * x * y), (py, -y - x**2 + y**2)]
    # Canonical double pendulum, unit masses and arms, g = 9.81 (see the binary's notation).
    a, b, d, g1, g2 = 2.0, 1.0, 1.0, 2.0 * 9.81, 9.81
    q1, q2, p1, p2 = x, y, px, py
    cd, sd = hy.cos(q1 - q2), hy.sin(q1 - q2)
    det = a * d - b * b * cd * cd
    w1 = (d * p1 - b * cd * p2) / det
    w2 = (a * p2 - b * cd * p1) / det
    pendulum = [
        (q1, w1),
        (q2, w2),
        (p1, -b * w1 * w2 * sd - g1 * hy.sin(q1)),
        (p2, b * w1 * w2 * sd - g2 * hy.sin(q2)),
    ]
    xh, yh, pxh = 0.0, 0.1, 0.4
    v = 0.5 * (xh * xh + yh * yh) + xh * xh * yh - yh**3 / 3.0
    pyh = math.sqrt(2.0 * (1.0 / 6.0 - v) - pxh * pxh)
    hh0 = [xh, yh, pxh, pyh]
    return {
        "kepler": (kepler, [0.5, 0.0, 0.0, math.sqrt(3.0)], 200.0 * math.pi),
        "hh-state": (hh, hh0, 100.0),
        "hh-energy": (hh, hh0, 1000.0),
        "pendulum": (pendulum, [2.0, 1.5, 0.0, 0.0], 10.0),
    }


def hh_energy(s):
    x, y, px, py = s[..., 0], s[..., 1], s[..., 2], s[..., 3]
    return 0.5 * (px * px + py * py + x * x + y * y) + x * x * y - y**3 / 3.0


def kepler_closed_form(t):
    """State of the e = 0.5 orbit at t, from Kepler's equation in mpmath-free double double:
    Newton in long double, which is enough for a reference at 1e-16 over 100 orbits."""
    e = np.longdouble(0.5)
    two_pi = 2 * np.longdouble(math.pi) + np.longdouble(2.4492935982947064e-16)
    m = np.longdouble(t) % two_pi
    ecc = m + e * np.sin(m)
    for _ in range(60):
        step = (ecc - e * np.sin(ecc) - m) / (1 - e * np.cos(ecc))
        ecc -= step
    edot = 1 / (1 - e * np.cos(ecc))
    b = np.sqrt(1 - e * e)
    return np.array(
        [np.cos(ecc) - e, b * np.sin(ecc), -np.sin(ecc) * edot, b * np.cos(ecc) * edot],
        dtype=np.longdouble,
    )


def reference(name, sys_, y0, t1):
    """The extended-precision reference: the final state, or the energy grid for hh-energy."""
    if name == "kepler":
        # 200 pi in extended precision: the binary's t1 is the double nearest 200 pi.
        return kepler_closed_form(np.longdouble(200.0 * math.pi)), "closed form"
    fp = None
    for candidate in ("real128",):
        if hasattr(hy, candidate):
            fp = getattr(hy, candidate)
    label = "heyoka real128" if fp is not None else "heyoka long double"
    if fp is None:
        fp = np.longdouble
        tol = np.longdouble(1e-19)
        state = np.array(y0, dtype=np.longdouble)
    else:
        tol = fp("1e-32")
        state = np.array([fp(repr(v)) for v in y0])
    ta = hy.taylor_adaptive(sys_, state, tol=tol, fp_type=fp)
    if name == "hh-energy":
        return None, label
    ta.propagate_until(fp(t1) if fp is not np.longdouble else np.longdouble(t1))
    # To long double through text (numpy cannot cast real128): 19 digits, enough for errors
    # down to 1e-17.
    return np.array([np.longdouble(str(v)) for v in ta.state], dtype=np.longdouble), label


def best_time(f):
    f()
    best = math.inf
    for _ in range(REPEATS):
        start = time.perf_counter()
        f()
        best = min(best, time.perf_counter() - start)
    return best


def run_heyoka(name, sys_, y0, t1, tol):
    start = time.perf_counter()
    ta = hy.taylor_adaptive(sys_, y0, tol=tol)
    compile_seconds = time.perf_counter() - start
    grid = np.arange(0.0, t1 + 0.5, 1.0)
    out = {}

    def once():
        ta.time = 0.0
        ta.state[:] = y0
        if name == "hh-energy":
            out["grid"] = ta.propagate_grid(grid)[5]
        else:
            ta.propagate_until(t1)
            out["final"] = np.array(ta.state)

    seconds = best_time(once)
    return seconds, compile_seconds, out


def error_of(name, result, ref, y0):
    if name == "hh-energy":
        e0 = hh_energy(np.array(y0, dtype=np.longdouble))
        return float(np.max(np.abs(hh_energy(np.array(result, dtype=np.longdouble)) - e0)))
    return float(np.max(np.abs(np.array(result, dtype=np.longdouble) - ref)))


def main():
    ours_bin = sys.argv[1]
    ours = [json.loads(line) for line in subprocess.run(
        [ours_bin], check=True, capture_output=True, text=True).stdout.splitlines()]
    rows = []
    print(f"heyoka {hy.__version__}, numpy {np.__version__}")
    for name, (sys_, y0, t1) in systems().items():
        ref, label = reference(name, sys_, y0, t1)
        print(f"\n{name} (reference: {label})")
        mine = [o for o in ours if o["workload"] == name]
        for o in mine:
            if name == "hh-energy":
                o["error"] = o["energy_error"]
            else:
                o["error"] = error_of(name, o["final"], ref, y0)
        for tol in TOLERANCES:
            seconds, compile_seconds, out = run_heyoka(name, sys_, y0, t1, tol)
            if name == "hh-energy":
                err = error_of(name, out["grid"], None, y0)
            else:
                err = error_of(name, out["final"], ref, y0)
            reaching = [o for o in mine if o["error"] <= err]
            if reaching:
                best = min(reaching, key=lambda o: o["seconds"])
                ours_txt = (f"tol {best['tol']:.0e}: {best['error']:.1e}, "
                            f"{best['seconds'] * 1e3:.3f} ms, {best['steps']:.0f} steps")
                ratio = f"{seconds / best['seconds']:.2f}"
            else:
                ours_txt, ratio = "not reached", "-"
            same = next(o for o in mine if o["tol"] == tol)
            print(f"  tol {tol:.0e}: heyoka {err:.1e} in {seconds * 1e3:.3f} ms "
                  f"(compile {compile_seconds * 1e3:.1f} ms) | ours at this tol "
                  f"{same['error']:.1e} in {same['seconds'] * 1e3:.3f} ms "
                  f"(interpreted {same['interpreted_seconds'] * 1e3:.3f} ms; build "
                  f"{same['build_seconds'] * 1e6:.0f} us, compile "
                  f"{same['compile_seconds'] * 1e3:.2f} ms; {same['steps']:.0f} steps) "
                  f"| our fastest to heyoka's error: {ours_txt} | ratio {ratio}")
            rows.append((name, tol, err, seconds, ours_txt, ratio))
    print("\n| workload | tol | heyoka error, time | our fastest to that error | ratio |")
    print("|---|---|---|---|---|")
    for name, tol, err, seconds, ours_txt, ratio in rows:
        print(f"| {name} | {tol:.0e} | {err:.1e}, {seconds * 1e3:.3f} ms | {ours_txt} | {ratio} |")


if __name__ == "__main__":
    main()
