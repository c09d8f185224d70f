"""The example scripts (``examples/*.py``) run to the end at a small size, and what they print
agrees with the physics."""

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def run_example(name, *args, cwd):
    """Runs ``examples/<name>`` with ``args`` in ``cwd`` (matplotlib drawing off screen);
    returns its standard output."""
    run = subprocess.run(
        [sys.executable, str(EXAMPLES / name), *args],
        cwd=cwd, capture_output=True, text=True, timeout=300,
        env={**os.environ, "MPLBACKEND": "Agg"},
    )
    assert run.returncode == 0, run.stderr
    return run.stdout


def test_henon_heiles_regular_fraction_runs_and_falls_with_energy(tmp_path):
    # About 2 s of CPU: 11 energies x ~110 members x 1e4 steps with SALI.
    out = run_example("henon_heiles_regular_fraction.py", cwd=tmp_path)
    fractions = [float(f) for f in re.findall(r"([\d.]+)% of \d+ starts regular", out)]
    assert len(fractions) == 11
    # Hénon & Heiles (1964): the section is covered by invariant curves at low energy, and
    # mostly chaotic near the escape energy 1/6. Any grid and run length shows both.
    assert fractions[0] == 100.0 and fractions[-1] < 50.0
    assert (tmp_path / "henon_heiles_regular_fraction.png").stat().st_size > 0


def test_flip_fractal_runs_and_flips_only_where_the_energy_allows(tmp_path):
    # 8 x 8 members for 1 s (a fraction of a second of CPU).
    n, t_max = 8, 1.0
    out = run_example("flip_fractal.py", str(n), str(t_max), cwd=tmp_path)
    found = re.search(r"(\d+) x (\d+) members: ([\d.]+)% flip within ([\d.]+) s; "
                      r"median flip time (\S+) s", out)
    assert found, out
    assert (int(found[1]), int(found[2]), float(found[4])) == (n, n, t_max)
    flipped, median = float(found[3]) / 100, float(found[5])
    # From rest, an arm can go over the top only if the energy allows it: with equal masses and
    # lengths that needs 2 cos(theta1) + cos(theta2) <= 1 (Heyl 2008), a bound independent of
    # the integration. The example's grid is the cell centres of [-pi, pi]^2.
    theta = -np.pi + (np.arange(n) + 0.5) * 2 * np.pi / n
    t1, t2 = np.meshgrid(theta, theta)
    allowed = np.mean(2 * np.cos(t1) + np.cos(t2) <= 1)
    # The printed fraction is rounded to 0.1 %.
    assert 0.0 < flipped <= allowed + 0.0005, (flipped, allowed)
    assert 0.0 < median <= t_max
    assert (tmp_path / "flip_fractal.png").stat().st_size > 0
