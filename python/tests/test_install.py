"""Installing physicskit into an environment of one's own: build the wheel with maturin,
install it into a fresh virtual environment and use it there.

The wheel is built exactly as ``python/dev.sh env`` builds the editable install (same cargo
target directory, cargo profile, features and interpreter, which pyo3's build script keys
on), so it reuses that build: no dependency (pyo3, numpy, the physicskit core ...) is compiled
again. The test checks that, so CI never compiles them twice. The extension crate itself may
be recompiled (about 30 s of one core): ``cargo build --example reference_run`` (``dev.sh
env``, ``test_bit_identity.py``) builds the same library unit with another crate-type
configuration, and cargo keeps one (``TargetConfigurationChanged``). Straight after ``maturin
develop`` nothing at all is compiled (second build measured at 0.4 s of cargo, 6.7 s in all).
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import zipfile
from pathlib import Path

PYTHON_DIR = Path(__file__).resolve().parents[1]
VENV = Path(sys.prefix)

# Packaging an already-built extension takes seconds; compiling it takes minutes. The limit
# only stops a hang: the compile check below is what catches a lost cache.
BUILD_TIMEOUT = 900
INSTALL_TIMEOUT = 300


def _env() -> dict[str, str]:
    """The environment ``dev.sh env`` runs maturin in (its venv activated), minus
    PYTHONPATH, so that nothing outside the fresh venv is importable."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["VIRTUAL_ENV"] = str(VENV)
    env["PATH"] = f"{VENV / 'bin'}{os.pathsep}{env.get('PATH', '')}"
    return env


def test_wheel_builds_from_the_dev_build_installs_and_runs(tmp_path, cargo_profile):
    dist = tmp_path / "dist"
    build = subprocess.run(
        [str(VENV / "bin" / "maturin"), "build", *cargo_profile, "--out", str(dist)],
        cwd=PYTHON_DIR, env=_env(), capture_output=True, text=True, timeout=BUILD_TIMEOUT)
    assert build.returncode == 0, build.stderr
    compiled = set(re.findall(r"^\s*Compiling (\S+)", build.stderr, re.M))
    assert compiled <= {"physicskit-python"}, (
        f"the wheel build compiled {sorted(compiled)}: it did not reuse the cargo build of "
        "'bash python/dev.sh env' (run that first; if it was run, the two builds differ in "
        "profile, features, target directory or interpreter)")
    (wheel,) = dist.glob("physicskit-*.whl")
    names = set(zipfile.ZipFile(wheel).namelist())
    assert {"physicskit/_core.pyi", "physicskit/py.typed",
            "physicskit/classical/core/display.py"} <= names
    assert any(re.fullmatch(r"physicskit/_core\..*\.so", n) for n in names), sorted(names)

    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True,
                   timeout=INSTALL_TIMEOUT)
    py = venv / "bin" / "python"
    # This environment's pip installs into the new one (numpy comes from the index or cache).
    install = subprocess.run(
        [sys.executable, "-m", "pip", "--python", str(py), "install", "--quiet",
         "--disable-pip-version-check", str(wheel)],
        env=_env(), capture_output=True, text=True, timeout=INSTALL_TIMEOUT)
    assert install.returncode == 0, install.stderr

    code = (
        "import physicskit, physicskit.classical as pc\n"
        "print(physicskit.__file__)\n"
        "r = pc.KeplerSystem.from_orbital_elements(1.0, 0.5).integrate((0.0, 1.0), 1e-3)\n"
        "assert r.y.shape == (1001, 4), r.y.shape\n"
        # yoshida4 at dt = 1e-3 keeps a Kepler orbit's energy to ~1e-12; 1e-9 only checks
        # that the installed extension really integrated.
        "assert abs(r.energy[-1] / r.energy[0] - 1) < 1e-9\n"
        "print(r)\n"
    )
    run = subprocess.run([str(py), "-W", "error", "-c", code], cwd=tmp_path, env=_env(),
                         capture_output=True, text=True, timeout=INSTALL_TIMEOUT)
    assert run.returncode == 0, run.stderr
    location, summary = run.stdout.splitlines()
    assert Path(location).resolve().is_relative_to(venv.resolve())
    assert summary.startswith("SimulationResult(method='yoshida4', steps=1000")
