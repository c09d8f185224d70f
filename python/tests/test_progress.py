"""``integrate_sampled(..., progress=True)``: a tqdm bar when tqdm is installed, a plain text
bar on standard error otherwise. The tqdm path runs against a fake ``tqdm.auto`` module put into
``sys.modules`` (what the bar is told) and against the real tqdm, the optional extra
``physicskit[progress]`` that ``python/dev.sh env`` installs (what a user sees); the plain path
with tqdm made unimportable."""

from __future__ import annotations

import re
import subprocess
import sys
import types

import numpy as np
import pytest

import physicskit.classical as pc
from physicskit.classical.core import progress as progress_module

# Enough steps for several native progress checks (one every 2048 steps), still ~1 ms of work.
N_STEPS = 10_000


class FakeTqdm:
    """Records what a tqdm bar is told."""

    made: list["FakeTqdm"] = []

    def __init__(self, total=None, desc=None, unit=None):
        self.total, self.desc, self.unit = total, desc, unit
        self.updates: list[int] = []
        self.closed = 0
        FakeTqdm.made.append(self)

    def update(self, n):
        self.updates.append(n)

    def close(self):
        self.closed += 1


@pytest.fixture
def fake_tqdm(monkeypatch):
    FakeTqdm.made = []
    auto = types.ModuleType("tqdm.auto")
    auto.tqdm = FakeTqdm
    package = types.ModuleType("tqdm")
    package.auto = auto
    package.tqdm = FakeTqdm
    monkeypatch.setitem(sys.modules, "tqdm", package)
    monkeypatch.setitem(sys.modules, "tqdm.auto", auto)
    return FakeTqdm


@pytest.fixture
def no_tqdm(monkeypatch):
    # None in sys.modules makes `import tqdm.auto` raise ImportError.
    monkeypatch.setitem(sys.modules, "tqdm", None)
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)
    # Draw at every report, so the test sees each one (the bar redraws every 0.25 s).
    monkeypatch.setattr(progress_module.PlainBar, "min_interval", 0.0)


def oscillator():
    return pc.HarmonicChain([0.1, -0.05], [0.0, 0.1])


def test_plain_bar_on_stderr_without_tqdm(no_tqdm, capsys):
    res = oscillator().integrate_sampled((0.0, N_STEPS * 1e-3), 1e-3, progress=True)
    err = capsys.readouterr().err
    assert err.endswith("\n") and err.count("\n") == 1
    frames = [f for f in err.strip("\n").split("\r") if f]
    counts = [tuple(map(int, re.search(r"(\d+)/(\d+) steps", f).groups())) for f in frames]
    # Reports during the run (increasing, below the total), then the final count.
    assert len(counts) >= 3
    assert all(n == N_STEPS for _, n in counts)
    steps = [s for s, _ in counts]
    assert steps == sorted(steps) and 0 < steps[0] < N_STEPS and steps[-1] == N_STEPS
    assert frames[-1].startswith("integrate [" + "#" * 30 + "] 100%")
    assert len(res.t) == N_STEPS + 1


def test_plain_bar_is_throttled(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "tqdm", None)
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)
    oscillator().integrate_sampled((0.0, N_STEPS * 1e-3), 1e-3, progress=True)
    # The whole run takes well under 0.25 s: the first report and the final count only.
    assert capsys.readouterr().err.count("\r") <= 2


def test_tqdm_bar_when_tqdm_is_installed(fake_tqdm, capsys):
    oscillator().integrate_sampled((0.0, N_STEPS * 1e-3), 1e-3, stride=100, progress=True)
    (bar,) = fake_tqdm.made
    assert (bar.total, bar.unit) == (N_STEPS, "step")
    assert len(bar.updates) >= 2 and all(u > 0 for u in bar.updates)
    assert sum(bar.updates) == N_STEPS and bar.closed == 1
    assert capsys.readouterr().err == ""


def test_real_tqdm_bar_on_stderr(capsys):
    import tqdm  # the physicskit[progress] extra, installed by python/dev.sh env
    import tqdm.auto

    reporter = progress_module.progress_reporter()
    assert isinstance(reporter, progress_module.TqdmBar)
    assert reporter._tqdm in (tqdm.tqdm, tqdm.auto.tqdm)
    oscillator().integrate_sampled((0.0, N_STEPS * 1e-3), 1e-3, progress=True)
    err = capsys.readouterr().err
    # tqdm's own text bar, ended at the full count.
    final = err.rstrip("\n").split("\r")[-1]
    assert final.startswith("integrate: 100%") and f"{N_STEPS}/{N_STEPS}" in final, err


def test_import_of_the_package_does_not_load_tqdm():
    code = ("import sys, physicskit.classical as pc\n"
            "print('tqdm' in sys.modules)\n"
            "pc.HarmonicChain([0.1], [0.0]).integrate_sampled((0.0, 1.0), 0.1)\n"
            "print('tqdm' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    # Neither the import nor a run without progress=True imports it.
    assert out.stdout.split() == ["False", "False"]


def test_python_subclass_reports_progress(fake_tqdm):
    class Spring(pc.HamiltonianSystem):
        def kinetic_energy(self, p):
            return 0.5 * float(p @ p)

        def potential_energy(self, q):
            return 0.5 * float(q @ q)

        def force(self, q, t=0.0):
            return -q

    Spring([1.0], [0.0]).integrate_sampled((0.0, 1.0), 1e-3, progress=True)
    (bar,) = fake_tqdm.made
    # Python right-hand sides are checked every 128 steps: several reports in 1000 steps.
    assert len(bar.updates) >= 5 and sum(bar.updates) == 1000 and bar.closed == 1


def test_short_run_still_completes_the_bar(fake_tqdm):
    oscillator().integrate_sampled((0.0, 0.01), 1e-3, progress=True)
    (bar,) = fake_tqdm.made
    assert (bar.total, bar.updates, bar.closed) == (10, [10], 1)


def test_error_in_the_bar_stops_the_run_and_propagates(fake_tqdm):
    class Boom(Exception):
        pass

    def update(self, n):
        raise Boom("display failed")

    fake_tqdm.update = update
    system = oscillator()
    before = system.state.copy()
    with pytest.raises(Boom):
        system.integrate_sampled((0.0, N_STEPS * 1e-3), 1e-3, progress=True)
    np.testing.assert_array_equal(system.state, before)
    assert fake_tqdm.made[-1].closed == 1


def test_progress_off_prints_nothing(no_tqdm, capsys):
    oscillator().integrate_sampled((0.0, N_STEPS * 1e-3), 1e-3)
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize("bad", [1, "yes", None, 1.0])
def test_progress_must_be_a_flag(bad):
    with pytest.raises(ValueError, match="progress must be True or False"):
        oscillator().integrate_sampled((0.0, 0.1), 1e-3, progress=bad)
