"""The Lorenz system written in SymPy, integrated natively by ``ODEEngine``.

    python python/examples/lorenz_sympy.py [t_end]

Builds ``dx/dt = sigma (y - x)``, ``dy/dt = x (rho - z) - y``, ``dz/dt = x y - beta z`` once,
integrates it with ``rk4`` (no Python call per step), prints the final state, the Jacobian at
the start (automatic differentiation) and the time-averaged divergence ``-(sigma + 1 + beta)``,
and, if matplotlib is installed, saves the butterfly to ``lorenz.png``.
"""

import sys
import time

import numpy as np
import sympy as sp

from physicskit.classical.utils.symbolic import ODEEngine


def main(t_end: float = 40.0) -> None:
    x, y, z = sp.symbols("x y z")
    sigma, rho, beta = sp.symbols("sigma rho beta")
    engine = ODEEngine(
        [x, y, z],
        [sigma * (y - x), x * (rho - z) - y, x * y - beta * z],
        params={"sigma": 10.0, "rho": 28.0, "beta": 8.0 / 3.0},
    )
    lorenz = engine.system([1.0, 1.0, 1.0])
    start = time.perf_counter()
    result = lorenz.integrate((0.0, t_end), 1e-3, method="rk4")
    elapsed = time.perf_counter() - start
    steps = len(result.t) - 1
    print(f"{steps} rk4 steps in {elapsed * 1e3:.1f} ms ({elapsed / steps * 1e9:.0f} ns per step)")
    print("final state:", result.y[-1])
    print("Jacobian at (1, 1, 1):\n", engine.jacobian(0.0, [1.0, 1.0, 1.0]))
    print("trace (the constant divergence):", np.trace(engine.jacobian(0.0, result.y[-1])))
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    fig = plt.figure(figsize=(6, 5))
    ax = fig.add_subplot(projection="3d")
    ax.plot(*result.y.T, lw=0.3)
    ax.set_title("Lorenz attractor (SymPy -> ODEEngine, rk4)")
    fig.savefig("lorenz.png", dpi=120)
    print("saved lorenz.png")


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 40.0)
