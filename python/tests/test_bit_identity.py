"""The same runs through Python and directly in Rust give bit-identical arrays.

The Rust side is `python/examples/reference_run.rs`, a plain Rust program on the `physicskit`
crate (no PyO3 in the path), run with `cargo run` in the profile of the extension. An independent process rather
than a hook inside the extension module: it shows that nothing in the binding layer (argument
conversion, parameter handling, the choice of integrator path, the zero-copy hand-over of the
arrays) changes a single bit. The program is built by `dev.sh env`; the test skips if cargo
is unavailable.
"""

import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

import physicskit.classical as pc

REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def reference(tmp_path_factory, cargo_profile):
    if shutil.which("cargo") is None:
        pytest.skip("cargo is not installed")
    out = tmp_path_factory.mktemp("reference")
    subprocess.run(
        ["cargo", "run", "--quiet", *cargo_profile, "-p", "physicskit-python", "--example",
         "reference_run", "--", str(out)],
        cwd=REPO, check=True, env={**os.environ, "CARGO_BUILD_JOBS": os.environ.get("CARGO_BUILD_JOBS", "2")},
    )
    return out


def python_runs():
    yield "kepler_yoshida4", pc.KeplerSystem.from_orbital_elements(1.0, 0.5).integrate((0.0, 20.0), 1e-3, "yoshida4")
    yield "double_pendulum_implicit_midpoint", pc.DoublePendulum([2.0, 1.0], [0.5, -0.3]).integrate(
        (0.0, 3.0), 3e-4, "implicit_midpoint")
    yield "euler_top_rk4", pc.EulerTop([0.01, 1.0, 0.01]).integrate((0.0, 10.0), 1e-3, "rk4")
    yield "fput_verlet", pc.FPUTChain(16, 1.0, 1.0, 1.0, 1, 1.0).integrate((0.0, 50.0), 5e-3, "verlet")


def test_python_equals_rust_bit_for_bit(reference):
    for name, r in python_runs():
        raw = np.fromfile(reference / f"{name}.f64", dtype="<f8")
        mine = np.concatenate([r.t, r.y.ravel(), r.energy])
        assert raw.shape == mine.shape, name
        assert raw.tobytes() == mine.astype("<f8").tobytes(), name
