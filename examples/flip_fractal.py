"""The double pendulum's flip-time fractal (Heyl 2008) as one ensemble.

Each member starts from rest at angles (theta1, theta2) on a grid; the output is the time
until either arm first flips over the top (|theta| > pi), NaN if it does not within the run.

    python examples/flip_fractal.py            # 100 x 100, 10 s: a few seconds on 2 cores
    python examples/flip_fractal.py 1000 100   # Heyl's resolution (see benchmarks/README.md)

With matplotlib installed the map is saved to flip_fractal.png.
"""

import sys

import numpy as np

import physicskit.classical as pc

n = int(sys.argv[1]) if len(sys.argv) > 1 else 100
t_max = float(sys.argv[2]) if len(sys.argv) > 2 else 10.0
theta = -np.pi + (np.arange(n) + 0.5) * 2 * np.pi / n

out = pc.ensemble(
    pc.DoublePendulum([0.0, 0.0], [0.0, 0.0]), (0.0, t_max), 0.01, "rk4",
    grid={"theta0[0]": theta, "theta0[1]": theta},
    events={"upper": pc.abs_above(0, np.pi), "lower": pc.abs_above(1, np.pi)},
    final_state=False,  # events only: each member stops once both arms have flipped
    progress=True,
)
flip = np.fmin(out.events["upper"], out.events["lower"])  # NaN only if neither flips
print(f"{n} x {n} members: {np.isfinite(flip).mean():.1%} flip within {t_max} s; "
      f"median flip time {np.nanmedian(flip):.2f} s")

try:
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit(0)
scaled = np.log10(np.where(np.isfinite(flip), flip, t_max) / np.sqrt(1 / 9.81))
plt.imshow(scaled.T, origin="lower", extent=[-np.pi, np.pi, -np.pi, np.pi], cmap="viridis")
plt.colorbar(label="log10 (t_flip / sqrt(l/g))")
plt.xlabel("theta1 (rad)")
plt.ylabel("theta2 (rad)")
plt.savefig("flip_fractal.png", dpi=150)
print("wrote flip_fractal.png")
