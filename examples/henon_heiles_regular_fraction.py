"""The Henon-Heiles fraction of regular orbits against energy (Henon & Heiles 1964, their
figure of the "relative area covered by curves"), from SALI on one ensemble.

At each energy E a grid of starts covers the surface of section x = 0 inside its
zero-velocity curve p_y^2 + y^2 - 2 y^3 / 3 = 2 E, with p_x >= 0 from the energy. Each start
is one member; SALI at t1 above 1e-8 (pc.CHAOS_THRESHOLD) calls its orbit regular. The
fraction of regular starts estimates the area of the section covered by invariant curves.

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


def section_starts(energy):
    """Cell centres of an n x n grid on x = 0 inside the zero-velocity curve, as [x, y, px, py]."""
    roots = np.roots([-1 / 3, 1 / 2, 0.0, -energy]).real  # y^2/2 - y^3/3 = E: y0 < 0 < y1
    y0, y1 = roots[(roots > -1) & (roots < 0)][0], roots[(roots > 0) & (roots < 1)][0]
    p_max = np.sqrt(2 * energy)
    y = y0 + (np.arange(n) + 0.5) * (y1 - y0) / n
    py = -p_max + (np.arange(n) + 0.5) * 2 * p_max / n
    y, py = (a.ravel() for a in np.meshgrid(y, py, indexing="ij"))
    px2 = 2 * energy - py**2 - y**2 + 2 * y**3 / 3
    inside = px2 > 0
    return np.stack([np.zeros(inside.sum()), y[inside], np.sqrt(px2[inside]), py[inside]], axis=1)


starts = [section_starts(e) for e in energies]
out = pc.ensemble(
    pc.HenonHeilesSystem([0.0, 0.0], [0.0, 0.0]), (0.0, t1), 0.1, "yoshida4",
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
plt.ylabel("fraction of regular orbits (SALI > 1e-8)")
plt.xlim(0, 1 / 6)
plt.ylim(0, 1.05)
plt.savefig("henon_heiles_regular_fraction.png", dpi=150)
print("wrote henon_heiles_regular_fraction.png")
