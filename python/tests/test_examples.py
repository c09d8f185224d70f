"""The example scripts (``examples/*.py``) run to the end at their default (small) size."""

import os
import re
import subprocess
import sys
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_henon_heiles_regular_fraction_runs_and_falls_with_energy(tmp_path):
    # About 2 s of CPU: 11 energies x ~110 members x 1e4 steps with SALI.
    run = subprocess.run(
        [sys.executable, str(EXAMPLES / "henon_heiles_regular_fraction.py")],
        cwd=tmp_path, capture_output=True, text=True, timeout=300,
        env={**os.environ, "MPLBACKEND": "Agg"},
    )
    assert run.returncode == 0, run.stderr
    fractions = [float(f) for f in re.findall(r"([\d.]+)% of \d+ starts regular", run.stdout)]
    assert len(fractions) == 11
    # Hénon & Heiles (1964): the section is covered by invariant curves at low energy, and
    # mostly chaotic near the escape energy 1/6. Any grid and run length shows both.
    assert fractions[0] == 100.0 and fractions[-1] < 50.0
