"""Accuracy floors of our Taylor method and heyoka's, as medians over many starts.

A floor measured on one start is one draw of a random walk: over 100 Kepler orbits the final
error of equally valid roundings spreads over two decades (benchmarks/README.md). This script
runs both integrators at their tightest tolerances from N starts of each workload and prints
each side's median, quartiles and extremes of the final-state error (largest component)
against heyoka in real128 at tolerance 1e-32, started from the same doubles (converted exactly: a double's decimal text read in
real128 is another number, 1e-17 away, which chaos would amplify).

Workloads:
  kepler    e = 0.5, a = 1 (H = p^2/2 - 1/r), 100 orbits (t = 200 pi), starting at N mean
            anomalies spread over one orbit;
  hh-state  Hénon–Heiles on E = 1/6, t = 100, N starts on x = 0 with y in [-0.2, 0.3] and
            p_x = 0.4 (p_y > 0 from the energy).

Ours runs through the Python package (``integrate_sampled(..., method="taylor", rtol=tol,
atol=tol, final_only=True)`` of ``KeplerSystem`` / ``HenonHeilesSystem``) in the project's
venv, heyoka (``taylor_adaptive``, ``tol``) in its own; the starts go to ours as text.

Usage (heyoka's venv, see heyoka_compare.sh):
  /tmp/heyoka-venv/bin/python benchmarks/taylor_floors.py [N] [PROJECT_PYTHON]
"""

import json
import math
import subprocess
import sys

import heyoka as hy
import numpy as np

TOLERANCES = [1e-14, 1e-16]

OURS = r"""
import json, sys
import physicskit.classical as pc
job = json.load(sys.stdin)
out = []
for y0 in job["starts"]:
    row = []
    for tol in job["tolerances"]:
        cls = pc.KeplerSystem if job["name"] == "kepler" else pc.HenonHeilesSystem
        s = cls(q0=y0[:2], p0=y0[2:])
        t1 = job["t1"]
        r = s.integrate_sampled((0.0, t1), t1, method="taylor", rtol=tol, atol=tol,
                                final_only=True, energy=False)
        row.append([repr(float(v)) for v in list(r.q[-1]) + list(r.p[-1])])
    out.append(row)
json.dump(out, sys.stdout)
"""


def starts(name, n):
    if name == "kepler":
        e = 0.5
        rows = []
        for i in range(n):
            m = 2 * math.pi * i / n
            ecc = m
            for _ in range(60):
                ecc -= (ecc - e * math.sin(ecc) - m) / (1 - e * math.cos(ecc))
            edot = 1 / (1 - e * math.cos(ecc))
            b = math.sqrt(1 - e * e)
            rows.append([math.cos(ecc) - e, b * math.sin(ecc), -math.sin(ecc) * edot,
                         b * math.cos(ecc) * edot])
        return rows, 200.0 * math.pi
    rows = []
    for i in range(n):
        y, px = -0.2 + 0.5 * i / max(n - 1, 1), 0.4
        v = 0.5 * y * y - y**3 / 3.0
        rows.append([0.0, y, px, math.sqrt(2.0 * (1.0 / 6.0 - v) - px * px)])
    return rows, 100.0


def equations(name):
    x, y, px, py = hy.make_vars("x", "y", "px", "py")
    if name == "kepler":
        r3 = (x**2 + y**2) ** -1.5
        return [(x, px), (y, py), (px, -x * r3), (py, -y * r3)]
    return [(x, px), (y, py), (px, -x - 2.0 * x * y), (py, -y - x**2 + y**2)]


def reference(sys_, y0, t1):
    fp = hy.real128
    ta = hy.taylor_adaptive(sys_, np.array([fp(float(v)) for v in y0]), tol=fp("1e-32"),
                            fp_type=fp)
    ta.propagate_until(fp(t1))
    return np.array([np.longdouble(str(v)) for v in ta.state], dtype=np.longdouble)


def error(state, ref):
    return float(np.max(np.abs(np.array(state, dtype=np.longdouble) - ref)))


def summary(errors):
    q = np.quantile(errors, [0.0, 0.25, 0.5, 0.75, 1.0])
    return "min {:.1e}, quartiles {:.1e} / {:.1e} / {:.1e}, max {:.1e}".format(*q)


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 20
    project_python = sys.argv[2] if len(sys.argv) > 2 else ".venv/bin/python"
    for name in ("kepler", "hh-state"):
        rows, t1 = starts(name, n)
        sys_ = equations(name)
        job = json.dumps({"name": name, "starts": rows, "t1": t1, "tolerances": TOLERANCES})
        ours = json.loads(subprocess.run([project_python, "-c", OURS], input=job, text=True,
                                         capture_output=True, check=True).stdout)
        refs = [reference(sys_, y0, t1) for y0 in rows]
        for k, tol in enumerate(TOLERANCES):
            heyoka_errors, our_errors = [], []
            for y0, ref, mine in zip(rows, refs, ours):
                ta = hy.taylor_adaptive(sys_, np.array(y0), tol=tol)
                ta.propagate_until(t1)
                heyoka_errors.append(error(ta.state, ref))
                our_errors.append(error([np.longdouble(float(v)) for v in mine[k]], ref))
            print(f"{name} tol {tol:.0e}, {n} starts")
            print(f"  heyoka: {summary(heyoka_errors)}")
            print(f"  ours:   {summary(our_errors)}")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
