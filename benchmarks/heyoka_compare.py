"""Time to accuracy: our adaptive Taylor method against heyoka, on the same workloads, in one run.

Run by ``benchmarks/heyoka_compare.sh`` (it makes heyoka's venv under /tmp and builds our side,
the ``heyoka_taylor`` binary, in release). For each workload heyoka runs at the tolerances 1e-6,
1e-8, ... 1e-16 (its single ``tol``) and ours at every half decade from 1e-6 to 1e-16 (rtol =
atol = tol), each the best wall time of five after one untimed run (ours with its recurrences
compiled by the JIT, and interpreted for comparison; the compile times of both sides are
printed); errors are measured against a reference in extended precision: heyoka in real128 where
its build has it, else in x87 long double (64-bit mantissa) at tolerance 1e-19, and the closed
form for Kepler. The table then gives, for each of heyoka's runs, our cheapest run with an error
at most heyoka's, and the ratio of the times (heyoka's over ours: above 1 we are faster); and
the ratio to our run at heyoka's tolerance, whatever its error. Both sides take the same steps
at the same tolerance (the same order and step-size rule), so their errors there differ in the
roundings only; where ours comes out a hair above heyoka's, the finer grid finds our cheapest
run below it instead of charging the next whole decade.

Workloads (the same starts as ``benchmarks/src/bin/heyoka_taylor.rs``):
  kepler     e = 0.5, a = 1 from perihelion, 100 orbits: final-state error (closed form)
  hh-state   Hénon–Heiles E = 1/6 from q = (0, 0.1), p_x = 0.4, t = 100: final-state error
  hh-energy  the same start, t = 1000: largest energy error on a grid of unit spacing
  pendulum   double pendulum from rest at (2, 1.5) rad, t = 10, state (q, p): final error

Batch workload (``batch``, with the ``heyoka_batch`` binary): 1000 Hénon–Heiles orbits at E =
1/6 launched on the surface x = 0 (a lattice of 50 heights y by 20 momenta p_x, none zero, p_y >
0; the binary prints the starts and heyoka starts from the same bits), t = 100, final states, at
tolerances 1e-6, 1e-10, 1e-14. heyoka: ``taylor_adaptive_batch`` (batch size
``recommended_simd_size()``) over the orbits on one thread; on two threads,
``ensemble_propagate_until_batch`` (its own ensemble API, ``max_workers=2``: a copy of the
integrator per batch) and two Python threads each stepping its own integrator over half the
batches (heyoka releases the GIL while it propagates). Ours: the ensemble API
(``ensemble::run``, method ``taylor``, at its default tolerances, the only ones its plan takes)
and the compiled recurrences over the members with rayon, on one and two threads (see the
binary), ours at every half decade from 1e-6 to 1e-16. Errors: the largest component error over
every 20th orbit (50 orbits) against heyoka in real128 at tolerance 1e-32. The orbits are
chaotic: over t = 100 the error of the most unstable of them grows from the tolerance by several
orders of magnitude, alike for both.

Rounds: this machine's speed comes in two modes, for both sides alike, and a run of a few
milliseconds lands in one of them: the same binary, pinned to one core with address
randomisation off, runs a quarter slower in some processes than in others (benchmarks/README.md,
"Two speeds of the machine"), so one best-of-five can differ from the next for reasons that are
not the code's. The whole measurement is therefore repeated in ``--rounds`` rounds (five by
default), ours then heyoka's in each, and every time is the least over the rounds. Every round
must give the same states and errors bit for bit (both sides are deterministic); a difference
stops the script.

Usage: heyoka_compare.py [--rounds N] PATH_TO_heyoka_taylor [PATH_TO_heyoka_batch]
       heyoka_compare.py [--rounds N] --batch-only PATH_TO_heyoka_batch
"""

import json
import math
import subprocess
import sys
import threading
import time

import heyoka as hy
import numpy as np

TOLERANCES = [1e-6, 1e-8, 1e-10, 1e-12, 1e-14, 1e-16]
REPEATS = 5
#: Rounds of the whole measurement (the module's docstring says why); ``--rounds`` sets it.
ROUNDS = 5
BATCH_TOLERANCES = [1e-6, 1e-10, 1e-14]
BATCH_T_END = 100.0
#: Every this many orbits of the batch gets a real128 reference (50 of the 1000): real128 runs
#: in software, about 0.1 s an orbit.
REFERENCE_EVERY = 20


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


def run_binary(path):
    """One run of one of our binaries: its JSON records."""
    return [json.loads(line) for line in subprocess.run(
        [path], check=True, capture_output=True, text=True).stdout.splitlines()]


def same(a, b):
    """Whether two results of different rounds are equal, bit for bit (NaN equal to NaN)."""
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype.kind != "f" or b.dtype.kind != "f":
        return a.shape == b.shape and bool(np.all(a == b))
    return np.array_equal(a, b, equal_nan=True)


def merge_rounds(rounds, key, timed):
    """One record per ``key(record)`` from several rounds of a binary's records: each field in
    ``timed`` the least over the rounds, every other field the first round's, which every
    round must repeat."""
    merged = {}
    for records in rounds:
        for o in records:
            m = merged.setdefault(key(o), dict(o))
            for field, value in o.items():
                if field in timed:
                    m[field] = min(m[field], value)
                elif not same(m[field], value):
                    raise SystemExit(f"our {key(o)}: {field} differs between rounds")
    return list(merged.values())


def least_of_rounds(label, runs):
    """(least seconds, first round's compile seconds, first round's results) of heyoka's
    rounds of one run; every round must give the first one's results."""
    for seconds, _, out in runs[1:]:
        for k, v in out.items():
            if not same(v, runs[0][2][k]):
                raise SystemExit(f"heyoka {label}: {k} differs between rounds")
    return min(r[0] for r in runs), runs[0][1], runs[0][2]


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


def batch_reference(hh, starts):
    """Final states of every REFERENCE_EVERY-th orbit in real128 at tolerance 1e-32, as long
    doubles (through text: numpy cannot cast real128)."""
    fp = hy.real128
    first = [fp(repr(float(v))) for v in starts[0]]
    ta = hy.taylor_adaptive(hh, first, tol=fp("1e-32"), fp_type=fp)
    ref = {}
    for i in range(0, len(starts), REFERENCE_EVERY):
        ta.time = fp(0)
        ta.state[:] = [fp(repr(float(v))) for v in starts[i]]
        if ta.propagate_until(fp(BATCH_T_END))[0] != hy.taylor_outcome.time_limit:
            raise RuntimeError(f"the real128 reference of orbit {i} stopped early")
        ref[i] = np.array([np.longdouble(str(v)) for v in ta.state], dtype=np.longdouble)
    return ref


def batch_error(finals, ref):
    """The largest component error over the reference's orbits (finals: n x 4)."""
    finals = np.asarray(finals, dtype=np.longdouble).reshape(-1, 4)
    return float(max(np.max(np.abs(finals[i] - r)) for i, r in ref.items()))


def heyoka_batches(starts, size):
    """The starts in batches of `size` (4 x size each, the last padded with its last orbit)."""
    s = np.asarray(starts, dtype=float)
    pad = (-len(s)) % size
    s = np.concatenate([s, np.repeat(s[-1:], pad, axis=0)])
    return [np.ascontiguousarray(s[k:k + size].T) for k in range(0, len(s), size)]


def run_heyoka_batch(hh, starts, tol):
    """heyoka's batch mode on one thread, on two threads of its ensemble API and on two Python
    threads: the batch size, and (seconds, compile seconds, {"final": final states}) for each,
    keyed by label, as ``run_heyoka`` gives them."""
    size = hy.recommended_simd_size()
    batches = heyoka_batches(starts, size)
    n = len(starts)
    start = time.perf_counter()
    ta = hy.taylor_adaptive_batch(hh, batches[0], tol=tol)
    compile_seconds = time.perf_counter() - start
    out = {}

    def reached(integrator):
        # Every lane reached t (an orbit escaping to infinity would stop early).
        if any(r[0] != hy.taylor_outcome.time_limit for r in integrator.propagate_res):
            raise RuntimeError(f"heyoka stopped early: {integrator.propagate_res}")

    def propagate(integrator, group):
        finals = []
        for b in group:
            integrator.set_time(0.0)
            integrator.state[:] = b
            integrator.propagate_until(BATCH_T_END)
            reached(integrator)
            finals.append(integrator.state.T.copy())
        return finals

    def one_thread():
        out["1 thread"] = np.concatenate(propagate(ta, batches))[:n]

    def ensemble_api():
        def gen(integrator, i):
            integrator.set_time(0.0)
            integrator.state[:] = batches[i]
            return integrator

        ret = hy.ensemble_propagate_until_batch(ta, BATCH_T_END, len(batches), gen,
                                                max_workers=2)
        for r in ret:
            reached(r[0])
        out["2 threads, ensemble API"] = np.concatenate([r[0].state.T for r in ret])[:n]

    second = hy.taylor_adaptive_batch(hh, batches[0], tol=tol)
    halves = [batches[: len(batches) // 2], batches[len(batches) // 2:]]

    def two_threads():
        parts = [None, None]

        def work(k, integrator):
            parts[k] = propagate(integrator, halves[k])

        threads = [threading.Thread(target=work, args=(k, it))
                   for k, it in enumerate((ta, second))]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        out["2 threads, own integrators"] = np.concatenate(parts[0] + parts[1])[:n]

    times = {"1 thread": best_time(one_thread),
             "2 threads, ensemble API": best_time(ensemble_api),
             "2 threads, own integrators": best_time(two_threads)}
    return size, {k: (times[k], compile_seconds, {"final": out[k]}) for k in times}


def batch(batch_bin):
    """The batch workload: heyoka's batch mode against our ensembles; prints a table."""
    heyoka_rounds = {tol: [] for tol in BATCH_TOLERANCES}
    our_rounds = []
    hh = systems()["hh-state"][0]
    starts = None
    for _ in range(ROUNDS):
        our_rounds.append(run_binary(batch_bin))
        if starts is None:
            starts = np.array(next(o for o in our_rounds[0] if o["kind"] == "starts")["states"])
            starts = starts.reshape(-1, 4)
        for tol in BATCH_TOLERANCES:
            heyoka_rounds[tol].append(run_heyoka_batch(hh, starts, tol))
    lines = merge_rounds(
        our_rounds,
        lambda o: (o["kind"], o.get("tol", o.get("rtol")), o.get("threads")),
        {"seconds", "build_seconds", "compile_seconds"},
    )
    start = time.perf_counter()
    ref = batch_reference(hh, starts)
    print(f"\nbatch: {len(starts)} Hénon–Heiles orbits, t = {BATCH_T_END:g} (reference: heyoka "
          f"real128 for {len(ref)} orbits, {time.perf_counter() - start:.1f} s)")
    check = next(o for o in lines if o["kind"] == "check")
    print(f"  ours: compiled recurrences at the ensemble's tolerances give the ensemble's bits: "
          f"{check['compiled_equals_ensemble']}")
    ours = {}
    for o in lines:
        if o["kind"] in ("ensemble", "compiled", "lanes") and "final" in o:
            o["error"] = batch_error(o["final"], ref)
    for o in lines:
        if o["kind"] in ("ensemble", "compiled", "lanes"):
            tol = o.get("tol", o.get("rtol"))
            one = next(p for p in lines if p["kind"] == o["kind"] and p.get("tol") == o.get("tol")
                       and p["threads"] == 1)
            ours[(o["kind"], tol, o["threads"])] = (o["seconds"], one["error"])
            bits = "" if o["threads"] == 1 else f", same bits as 1 thread: {o['same_bits']}"
            extra = (f" (rtol {o['rtol']:.0e}, atol {o['atol']:.0e})" if o["kind"] == "ensemble"
                     else f", the compiled run's bits: {o['equals_compiled']}"
                     if o["kind"] == "lanes"
                     else f", {o['steps']:.0f} steps, compile {o['compile_seconds'] * 1e3:.1f} ms")
            print(f"  ours {o['kind']}, {o['threads']} thread(s), tol {tol:.2g}{extra}: "
                  f"{one['error']:.1e} in {o['seconds'] * 1e3:.2f} ms{bits}")
    rows = []
    for tol in BATCH_TOLERANCES:
        size = heyoka_rounds[tol][0][0]
        for label in heyoka_rounds[tol][0][1]:
            seconds, compile_seconds, out = least_of_rounds(
                f"batch tol {tol:.0e}, {label}", [r[1][label] for r in heyoka_rounds[tol]])
            finals = out["final"]
            err = batch_error(finals, ref)
            print(f"  heyoka tol {tol:.0e}, {label}, batch {size}: {err:.1e} in "
                  f"{seconds * 1e3:.2f} ms (compile {compile_seconds * 1e3:.1f} ms)")
            threads = 1 if label == "1 thread" else 2
            # Ours at the same thread count, cheapest with an error at most heyoka's.
            reaching = [(v[0], k) for k, v in ours.items() if k[2] == threads and v[1] <= err]
            if reaching:
                best_seconds, (kind, our_tol, _) = min(reaching)
                ours_txt = (f"{kind} tol {our_tol:.2g}: {ours[(kind, our_tol, threads)][1]:.1e}, "
                            f"{best_seconds * 1e3:.2f} ms")
                ratio = f"{seconds / best_seconds:.2f}"
            else:
                ours_txt, ratio = "not reached", "-"
            same_seconds, same_error = ours[("lanes", tol, threads)]
            same_txt = (f"{same_error:.1e}, {same_seconds * 1e3:.2f} ms, "
                        f"{seconds / same_seconds:.2f}")
            rows.append((tol, label, size, err, seconds, ours_txt, ratio, same_txt))
    print("\n| heyoka tol | heyoka run | heyoka error, time | our fastest to that error, "
          "same threads | ratio | lanes at that tol: error, time, ratio |")
    print("|---|---|---|---|---|---|")
    for tol, label, size, err, seconds, ours_txt, ratio, same_txt in rows:
        print(f"| {tol:.0e} | {label}, batch {size} | {err:.1e}, {seconds * 1e3:.2f} ms | "
              f"{ours_txt} | {ratio} | {same_txt} |")


def main():
    global ROUNDS
    usage = __doc__[__doc__.index("Usage:"):].strip()
    args = sys.argv[1:]
    if args[:1] == ["--rounds"]:
        if len(args) < 2 or not args[1].isdigit() or int(args[1]) < 1:
            raise SystemExit(f"--rounds takes a positive whole number\n{usage}")
        ROUNDS = int(args[1])
        args = args[2:]
    if not args or args[:1] == ["--batch-only"] and len(args) < 2:
        raise SystemExit(usage)
    if args[0] == "--batch-only":
        print(f"heyoka {hy.__version__}, numpy {np.__version__}, {ROUNDS} rounds")
        batch(args[1])
        return
    ours_bin = args[0]
    workloads = systems()
    our_rounds, heyoka_rounds = [], {}
    for _ in range(ROUNDS):
        our_rounds.append(run_binary(ours_bin))
        for name, (sys_, y0, t1) in workloads.items():
            for tol in TOLERANCES:
                heyoka_rounds.setdefault((name, tol), []).append(
                    run_heyoka(name, sys_, y0, t1, tol))
    ours = merge_rounds(our_rounds, lambda o: (o["workload"], o["tol"]),
                        {"seconds", "interpreted_seconds", "build_seconds", "compile_seconds"})
    rows = []
    print(f"heyoka {hy.__version__}, numpy {np.__version__}, {ROUNDS} rounds")
    for name, (sys_, y0, t1) in workloads.items():
        ref, label = reference(name, sys_, y0, t1)
        print(f"\n{name} (reference: {label})")
        mine = [o for o in ours if o["workload"] == name]
        for o in mine:
            if name == "hh-energy":
                o["error"] = o["energy_error"]
            else:
                o["error"] = error_of(name, o["final"], ref, y0)
        for tol in TOLERANCES:
            seconds, compile_seconds, out = least_of_rounds(
                f"{name} tol {tol:.0e}", heyoka_rounds[(name, tol)])
            if name == "hh-energy":
                err = error_of(name, out["grid"], None, y0)
            else:
                err = error_of(name, out["final"], ref, y0)
            reaching = [o for o in mine if o["error"] <= err]
            if reaching:
                best = min(reaching, key=lambda o: o["seconds"])
                ours_txt = (f"tol {best['tol']:.2g}: {best['error']:.1e}, "
                            f"{best['seconds'] * 1e3:.3f} ms, {best['steps']:.0f} steps, "
                            f"order {best['order']:.0f}")
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
            same_txt = (f"{same['error']:.1e}, {same['seconds'] * 1e3:.3f} ms, "
                        f"{seconds / same['seconds']:.2f}")
            rows.append((name, tol, err, seconds, ours_txt, ratio, same_txt))
    print("\n| workload | tol | heyoka error, time | our fastest to that error | ratio "
          "| ours at that tol: error, time, ratio |")
    print("|---|---|---|---|---|---|")
    for name, tol, err, seconds, ours_txt, ratio, same_txt in rows:
        print(f"| {name} | {tol:.0e} | {err:.1e}, {seconds * 1e3:.3f} ms | {ours_txt} | {ratio} "
              f"| {same_txt} |")
    if len(args) > 1:
        batch(args[1])


if __name__ == "__main__":
    main()
