"""Kepler perihelion precession per orbit against the post-Newtonian coefficient c_pn, from an
ensemble of orbits, beside first-order perturbation theory (Landau & Lifshitz, Mechanics,
section 15, problem 3): delta_phi = -6 pi c_pn mu^2 k / L^4 per orbit.

    python examples/kepler_precession.py
"""

import numpy as np

import physicskit.classical as pc

a, e = 1.0, 0.5
period = 2 * np.pi * a**1.5
c_pn = -np.linspace(0.0005, 0.01, 20)
out = pc.ensemble(
    pc.KeplerSystem.from_orbital_elements(a, e), (0.0, 10 * period), period / 4000, "yoshida4",
    sweep={"c_pn": c_pn}, stride=20,
)
x, y, px, py = np.moveaxis(out.trajectory, -1, 0)  # each (members, samples)
L = x * py - y * px
r = np.hypot(x, y)
lrl = np.unwrap(np.arctan2(-px * L - y / r, py * L - x / r), axis=1)  # perihelion direction
slope = np.polyfit(out.t, lrl.T, 1)[0]  # rad per unit time, one per member
measured = slope * period
theory = -6 * np.pi * c_pn / (a * (1 - e**2)) ** 2
for c, m, t in zip(c_pn, measured, theory):
    print(f"c_pn = {c:+.5f}: measured {np.degrees(m):8.4f} deg/orbit, "
          f"first order {np.degrees(t):8.4f}, ratio {m / t:.4f}")
