"""The Henon-Heiles fraction of regular orbits against energy (Henon & Heiles 1964, their
figure of the "relative area covered by curves"), from SALI on one ensemble: the Python twin of
the gallery's demonstration 21 (crates/physicskit-viz/src/gallery/henon_heiles_regular.rs),
with the same energies, grid and run.

At each energy E a grid of starts covers the surface of section x = 0 inside its
zero-velocity curve V(0, y) + p_y^2 / 2 = E, with p_x >= 0 from the energy. The energies are
the system's own (its potential_energy and kinetic_energy): nothing here restates H. Each start
is one member; SALI at t1 above pc.CHAOS_THRESHOLD calls its orbit regular. The fraction of
regular starts estimates the area of the section covered by invariant curves.

    python examples/henon_heiles_regular_fraction.py          # 12 x 12 per energy, t1 = 1000
    python examples/henon_heiles_regular_fraction.py --full   # 60 x 60, t1 = 3000

With matplotlib installed the curve is saved to henon_heiles_regular_fraction.png.
"""

import sys

import numpy as np

import physicskit.classical as pc

full = "--full" in sys.argv[1:]
n, t1 = (60, 3000.0) if full else (12, 1000.0)
energies = np.array([1 / 24, 1 / 16, 1 / 12, 0.1, 0.11, 0.12, 0.125, 0.13, 0.14, 0.15, 0.16])
hh = pc.HenonHeilesSystem([0.0, 0.0], [0.0, 0.0])


def edge(energy, lo, hi):
    """The y in [lo, hi] where the section's potential V(0, y) equals energy (V - energy
    changes sign over [lo, hi]), bisected to adjacent floats."""
    below_at_lo = hh.potential_energy([0.0, lo]) < energy
    while lo < (mid := 0.5 * (lo + hi)) < hi:
        if (hh.potential_energy([0.0, mid]) < energy) == below_at_lo:
            lo = mid
        else:
            hi = mid
    return mid


def section_starts(energy):
    """Cell centres of an n x n grid on x = 0 inside the zero-velocity curve, as [x, y, px, py]."""
    # The curve spans y between the roots of V(0, y) = E either side of 0, and |p_y| <= p_max
    # (T = |p|^2 / 2: unit masses).
    y0, y1 = edge(energy, -1.0, 0.0), edge(energy, 0.0, 1.0)
    p_max = np.sqrt(2 * energy)
    starts = []
    for y in y0 + (np.arange(n) + 0.5) * (y1 - y0) / n:
        for py in -p_max + (np.arange(n) + 0.5) * 2 * p_max / n:
            rest = hh.potential_energy([0.0, y]) + hh.kinetic_energy([0.0, py])
            if rest < energy:  # p_x^2 / 2 takes what is left of E
                starts.append([0.0, y, np.sqrt(2 * (energy - rest)), py])
    return np.array(starts)


starts = [section_starts(e) for e in energies]
out = pc.ensemble(
    hh, (0.0, t1), 0.1, "yoshida4",
    states=np.concatenate(starts), sali=True, renormalize_every=10, progress=True,
)
bounds = np.cumsum([0] + [len(s) for s in starts])
fraction = [np.mean(out.sali[a:b] > pc.CHAOS_THRESHOLD) for a, b in zip(bounds, bounds[1:])]
for e, f, s in zip(energies, fraction, starts):
    print(f"E = {e:.4f}: {f:6.1%} of {len(s)} starts regular")

try:
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit(0)
plt.plot(energies, fraction, "o-")
plt.xlabel("energy E")
plt.ylabel(f"fraction of regular orbits (SALI > {pc.CHAOS_THRESHOLD:g})")
plt.xlim(0, 1 / 6)
plt.ylim(0, 1.05)
plt.savefig("henon_heiles_regular_fraction.png", dpi=150)
print("wrote henon_heiles_regular_fraction.png")
