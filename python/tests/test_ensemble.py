"""Ensembles from Python: grid-shaped outputs, bit-identity with single runs and across thread
counts, bad members refused by index before any work, Python subclasses refused; the same for
the SymPy engines' systems."""

import multiprocessing
import os

import numpy as np
import pytest

import physicskit.classical as pc
from physicskit import _core

THETA = np.linspace(-3.0, 3.0, 5)


def _flips(threads=None, **kw):
    return pc.ensemble(
        pc.DoublePendulum([0.0, 0.0], [0.0, 0.0]), (0.0, 2.0), 0.01,
        grid={"theta0[0]": THETA, "theta0[1]": THETA[:4]},
        events={"flip": pc.abs_above(1, np.pi)}, energy_error=True, stride=50,
        threads=threads, **kw)


def test_a_two_dimensional_grid_gives_two_dimensional_outputs():
    out = _flips()
    assert out.shape == (5, 4)
    assert out.final_state.shape == (5, 4, 4)
    assert out.events["flip"].shape == (5, 4) and out.energy_error.shape == (5, 4)
    assert out.trajectory.shape == (5, 4, len(out.t), 4)
    # Outputs follow the grid's axes (indexing "ij"): the initial angles are the grid's.
    assert np.array_equal(out.trajectory[:, :, 0, 0], np.repeat(THETA[:, None], 4, axis=1))
    assert np.array_equal(out.trajectory[:, :, 0, 1], np.repeat(THETA[None, :4], 5, axis=0))


def test_members_equal_their_own_integrate_bit_for_bit():
    out = _flips()
    for i, j in [(0, 0), (2, 3), (4, 1)]:
        single = pc.DoublePendulum([THETA[i], THETA[j]], [0.0, 0.0])
        r = single.integrate((0.0, 2.0), 0.01)
        final = np.concatenate([r.q[-1], r.p[-1]])
        assert np.array_equal(out.final_state[i, j], final)
        e = np.asarray(r.energy)
        assert out.energy_error[i, j] == np.max(np.abs(e - e[0]) / abs(e[0]))


def test_one_two_and_three_threads_give_the_same_bits():
    runs = [_flips(threads=k) for k in (1, 2, 3)]
    for other in runs[1:]:
        for name in ("final_state", "trajectory", "energy_error"):
            assert getattr(runs[0], name).tobytes() == getattr(other, name).tobytes()
        assert runs[0].events["flip"].tobytes() == other.events["flip"].tobytes()


def _final_state_bytes():
    return _flips(threads=2).final_state.tobytes()


# Python 3.12+ warns on every fork of a process with threads; forking one is this test's point.
@pytest.mark.skipif(not hasattr(os, "fork"), reason="needs fork")
@pytest.mark.filterwarnings("ignore:.*fork.*:DeprecationWarning")
def test_a_process_forked_after_a_run_builds_its_own_threads():
    # Ensembles keep their thread pools between calls. A child forked after a run (the default
    # of `multiprocessing` on Linux) inherits the kept pools but none of their threads: it
    # must start its own, not wait forever on its parent's. A minute is ample for a run of a
    # few milliseconds; a hang ends the test there instead of blocking the suite.
    parent = _flips(threads=2)
    with multiprocessing.get_context("fork").Pool(1) as child:
        got = child.apply_async(_final_state_bytes).get(timeout=60)
    assert got == parent.final_state.tobytes()


def test_nan_in_member_731_of_1000_is_refused_by_index_before_any_integration():
    q0 = np.linspace(0.0, 1.0, 1000)
    q0[731] = np.nan
    calls = []
    # 731 members of 2e4 steps take well over the progress period (20 ms): had integration
    # started before the refusal, the progress callback would have been called.
    with pytest.raises(ValueError, match="member 731"):
        pc.ensemble("harmonic-oscillator", (0.0, 200.0), 0.01, sweep={"q0": q0},
                    progress=lambda done, total: calls.append(done))
    assert calls == []


def test_progress_callback_sees_every_member_done():
    calls = []
    pc.ensemble("harmonic-oscillator", (0.0, 100.0), 0.001, sweep={"q0": np.ones(64)},
                progress=lambda done, total: calls.append((done, total)))
    # The run takes far more than one 20 ms period; totals are the member count.
    assert calls and all(total == 64 for _, total in calls)


def test_python_subclasses_are_refused_with_a_clear_message():
    class Oscillator(pc.HamiltonianSystem):
        def __init__(self):
            super().__init__([1.0], [0.0])

        def kinetic_energy(self, p):
            return 0.5 * p[0] ** 2

        def potential_energy(self, q):
            return 0.5 * q[0] ** 2

    with pytest.raises(TypeError, match="Python subclass.*GIL"):
        pc.ensemble(Oscillator(), (0.0, 1.0), 0.1, sweep={"q0": [1.0, 2.0]})

    class MyPendulum(pc.DoublePendulum):
        pass

    with pytest.raises(TypeError, match="Python subclass"):
        pc.ensemble(MyPendulum([1.0, 1.0], [0.0, 0.0]), (0.0, 1.0), 0.1,
                    sweep={"theta0[0]": [1.0, 2.0]})


def test_states_shape_the_members():
    # Henon-Heiles from explicit states on a 2 x 3 member shape.
    states = np.zeros((2, 3, 4))
    states[..., 1] = np.linspace(0.0, 0.3, 6).reshape(2, 3)
    states[..., 2] = 0.3
    out = pc.ensemble(pc.HenonHeilesSystem([0.0, 0.0], [0.0, 0.0]), (0.0, 1.0), 0.01,
                      states=states)
    assert out.final_state.shape == (2, 3, 4)
    single = pc.HenonHeilesSystem(states[1, 2, :2], states[1, 2, 2:]).integrate((0.0, 1.0), 0.01)
    assert np.array_equal(out.final_state[1, 2], np.concatenate([single.q[-1], single.p[-1]]))


def test_bad_arguments_are_refused():
    with pytest.raises(ValueError, match="either grid .* or sweep"):
        pc.ensemble("harmonic-oscillator", (0, 1), 0.1, grid={"q0": [1]}, sweep={"p0": [1]})
    with pytest.raises(ValueError, match="no such parameter"):
        pc.ensemble("harmonic-oscillator", (0, 1), 0.1, grid={"nope": [1.0]})
    with pytest.raises(ValueError, match="beyond the state"):
        pc.ensemble("harmonic-oscillator", (0, 1), 0.1, grid={"q0": [1.0]},
                    events={"e": pc.crossing(5)})
    with pytest.raises(ValueError, match="direction"):
        pc.crossing(0, 0.0, "sideways")
    with pytest.raises(ValueError, match="unknown system"):
        pc.ensemble("nope", (0, 1), 0.1, grid={"q0": [1.0]})
    # Thread counts beyond the core's limit (which a Python int can exceed by any amount) are
    # refused before any thread starts, naming the limit the core refuses beyond.
    limit = _core.MAX_THREADS
    for bad in (0, limit + 1, 2**64, 10**30):
        match = "threads must be >= 1" if bad == 0 else f"threads must be <= {limit}"
        with pytest.raises(ValueError, match=match):
            pc.ensemble("harmonic-oscillator", (0, 1), 0.1, grid={"q0": [1.0]}, threads=bad)


def _henon_heiles_section(hh, energy, ys, pys):
    """States ``[0, y, p_x, p_y]`` on the section ``x = 0`` at ``energy``, on the grid of
    ``ys`` x ``pys``, ``p_x >= 0`` from the system's own potential: ``p_x^2 = 2 (E - V(0, y))
    - p_y^2``."""
    y, py = np.meshgrid(ys, pys, indexing="ij")
    potential = np.vectorize(lambda v: hh.potential_energy(np.array([0.0, v])))(y)
    px = np.sqrt(2 * (energy - potential) - py**2)
    return np.stack([np.zeros_like(y), y, px, py], axis=-1)


def test_chaos_reductions_equal_single_orbit_max_lyapunov_and_sali_bit_for_bit():
    # Henon-Heiles at E = 1/8 from the section x = 0 (p_x >= 0 from the energy), a 2 x 3 grid.
    hh = pc.HenonHeilesSystem([0.0, 0.0], [0.0, 0.0])
    states = _henon_heiles_section(hh, 0.125, [-0.2, 0.1], [-0.1, 0.0, 0.25])
    out = pc.ensemble(hh, (0.0, 40.0), 0.05, states=states, max_lyapunov=True, sali=True,
                      renormalize_every=5, energy_error=True, threads=2)
    assert out.max_lyapunov.shape == out.sali.shape == out.energy_error.shape == (2, 3)
    for i, j in [(0, 0), (1, 2)]:
        member = lambda: pc.HenonHeilesSystem(states[i, j, :2], states[i, j, 2:])  # noqa: E731
        lyap = pc.max_lyapunov(member(), (0.0, 40.0), 0.05, renormalize_every=5)
        sali = pc.sali(member(), (0.0, 40.0), 0.05, renormalize_every=5)
        assert out.max_lyapunov[i, j] == lyap.exponents[0]
        assert out.sali[i, j] == sali.index[-1]
    with pytest.raises(ValueError, match="renormalize_every"):
        pc.ensemble(hh, (0, 1), 0.1, states=states, sali=True, renormalize_every=0)


def test_events_only_without_final_state_stop_early_with_the_same_times():
    full = _flips()
    early = pc.ensemble(
        pc.DoublePendulum([0.0, 0.0], [0.0, 0.0]), (0.0, 2.0), 0.01,
        grid={"theta0[0]": THETA, "theta0[1]": THETA[:4]},
        events={"flip": pc.abs_above(1, np.pi)}, final_state=False)
    assert early.final_state is None
    assert np.array_equal(early.events["flip"], full.events["flip"], equal_nan=True)
    flipped = np.isfinite(full.events["flip"])
    assert flipped.any() and (~flipped).any()
    # A member stops on the step of its flip, the step k whose span [t_(k-1), t_k] holds the
    # flip time (t_k = k dt, as the engine's time grid computes it); one that never flips runs
    # the whole span.
    k, t_flip = early.steps[flipped], early.events["flip"][flipped]
    assert np.all(((k - 1) * 0.01 <= t_flip) & (t_flip <= k * 0.01))
    assert np.all(early.steps[~flipped] == 200) and np.all(full.steps == 200)


def test_final_state_false_with_nothing_else_says_which_options_give_an_output():
    with pytest.raises(ValueError, match="final_state=False .* stride, energy_error=True, events"):
        pc.ensemble("harmonic-oscillator", (0, 1), 0.1, sweep={"q0": [1.0]}, final_state=False)


def test_chaos_reductions_need_a_fixed_step_method():
    # dop853 has no fixed-step flow for the deviation vectors: refused before any work, naming
    # the methods that do.
    hh = pc.HenonHeilesSystem([0.0, 0.0], [0.0, 0.0])
    states = _henon_heiles_section(hh, 0.125, [0.1], [0.0])
    for flag in ("sali", "max_lyapunov"):
        with pytest.raises(ValueError, match="adaptive method.*use rk4"):
            pc.ensemble(hh, (0, 1), 0.1, "dop853", states=states, **{flag: True})
    # Without a chaos reduction dop853 runs (its dt the first step).
    assert pc.ensemble(hh, (0, 1), 0.1, "dop853", states=states).method == "dop853"


def test_splitting_methods_are_refused_on_a_lagrangian_system():
    with pytest.raises(ValueError, match="yoshida4"):
        pc.ensemble(pc.DoublePendulum([0.0, 0.0], [0.0, 0.0]), (0, 1), 0.1, "yoshida4",
                    grid={"theta0[0]": [0.1, 0.2]})


def test_ensemble_sali_runs_past_the_floor_where_chaos_map_stops():
    # A chaotic Henon-Heiles orbit at E = 1/6. chaos_map stops SALI once below its floor
    # (1e-14); the ensemble follows it to t1 like sali() does, so its value is below the one
    # chaos_map stopped at and equals sali()'s last value. max_lyapunov is the same loop in both.
    hh = pc.HenonHeilesSystem([0.0, 0.0], [0.0, 0.0])
    states = _henon_heiles_section(hh, 1 / 6, [-0.1], [0.0]).reshape(1, 4)
    span, dt = (0.0, 500.0), 0.05
    out = pc.ensemble(hh, span, dt, states=states, sali=True, max_lyapunov=True)
    mapped = pc.chaos_map(hh, states, span, dt, indicator="sali")
    assert 0.0 < mapped[0] < 1e-14
    assert out.sali[0] < mapped[0]
    lyapunov = pc.chaos_map(hh, states, span, dt, indicator="lyapunov")
    assert out.max_lyapunov[0] == lyapunov[0]


# -- the SymPy engines' systems ----------------------------------------------------------------

def _henon_heiles_engine(lam=1.0):
    """Henon-Heiles with its cubic terms scaled by a parameter ``lam``, in SymPy."""
    sp = pytest.importorskip("sympy")
    from physicskit.classical.utils import HamiltonianEngine

    x, y, px, py, lam_ = sp.symbols("x y p_x p_y lam")
    H = (px**2 + py**2) / 2 + (x**2 + y**2) / 2 + lam_ * (x**2 * y - y**3 / 3)
    return HamiltonianEngine([x, y], [px, py], H, params={"lam": lam})


def _lorenz_engine(rho=28.0):
    sp = pytest.importorskip("sympy")
    from physicskit.classical.utils import ODEEngine

    x, y, z, s, r, b = sp.symbols("x y z sigma rho beta")
    return ODEEngine([x, y, z], [s * (y - x), x * (r - z) - y, x * y - b * z],
                     params={"sigma": 10.0, "rho": rho, "beta": 8.0 / 3.0})


def test_sympy_engine_members_equal_their_own_integrate_bit_for_bit():
    lam = np.array([[0.5, 1.0, 1.5], [1.0, 0.8, 1.2]])
    states = np.zeros((2, 3, 4))
    states[..., 1] = np.linspace(0.0, 0.25, 6).reshape(2, 3)
    states[..., 2] = 0.35
    system = _henon_heiles_engine().system([0.0, 0.1], [0.3, 0.0])
    runs = [pc.ensemble(system, (0.0, 20.0), 0.01, sweep={"lam": lam}, states=states,
                        energy_error=True, threads=k) for k in (1, 2, 3)]
    out = runs[0]
    for other in runs[1:]:
        assert out.final_state.tobytes() == other.final_state.tobytes()
        assert out.energy_error.tobytes() == other.energy_error.tobytes()
    for i, j in [(0, 0), (1, 2)]:
        single = _henon_heiles_engine(lam[i, j]).system(states[i, j, :2], states[i, j, 2:])
        r = single.integrate((0.0, 20.0), 0.01)
        assert out.method == r.method == "yoshida4"
        assert np.array_equal(out.final_state[i, j], r.y[-1])
        e = np.asarray(r.energy)
        assert out.energy_error[i, j] == np.max(np.abs(e - e[0]) / abs(e[0]))
    # Without states the members start from the system's state; a parameter may be named by
    # its SymPy symbol.
    (lam_symbol,) = system.engine.params
    swept = pc.ensemble(system, (0.0, 20.0), 0.01, grid={lam_symbol: [0.7]})
    alone = _henon_heiles_engine(0.7).system([0.0, 0.1], [0.3, 0.0]).integrate((0.0, 20.0), 0.01)
    assert np.array_equal(swept.final_state[0], alone.y[-1])


def test_sympy_lorenz_chaos_reductions_equal_the_single_orbit_calls():
    rho = [10.0, 28.0]
    out = pc.ensemble(_lorenz_engine().system([1.0, 1.0, 1.0]), (0.0, 10.0), 0.01, "rk4",
                      grid={"rho": rho}, max_lyapunov=True, sali=True)
    for i, r in enumerate(rho):
        system = lambda: _lorenz_engine(r).system([1.0, 1.0, 1.0])  # noqa: E731
        alone = pc.max_lyapunov(system(), (0.0, 10.0), 0.01, method="rk4")
        assert out.max_lyapunov[i] == alone.exponents[0]
        assert out.sali[i] == pc.sali(system(), (0.0, 10.0), 0.01, method="rk4").index[-1]
    # rho = 10: a stable fixed point (negative exponent); rho = 28: chaos (about +0.9). Only
    # the signs are asked of these finite-time estimates.
    assert out.max_lyapunov[0] < 0.0 < out.max_lyapunov[1]


def test_sympy_lagrangian_members_and_method_refusal():
    from conftest import sympy_double_pendulum

    engine = sympy_double_pendulum()
    states = np.array([[0.3, 0.2, 0.0, 0.0], [2.0, 1.0, 0.0, 0.5]])
    system = engine.system([0.0, 0.0], [0.0, 0.0])
    out = pc.ensemble(system, (0.0, 1.0), 0.01, states=states)
    r = engine.system(states[1, :2], states[1, 2:]).integrate((0.0, 1.0), 0.01)
    assert out.method == r.method == "implicit_midpoint"
    assert np.array_equal(out.final_state[1], r.y[-1])
    with pytest.raises(ValueError, match="yoshida4"):
        pc.ensemble(system, (0.0, 1.0), 0.01, "yoshida4", states=states)


def test_sympy_engine_members_are_checked_by_index_and_names_listed():
    system = _henon_heiles_engine().system([0.0, 0.1], [0.3, 0.0])
    with pytest.raises(ValueError, match="no such parameter.*: lam"):
        pc.ensemble(system, (0, 1), 0.1, grid={"mu": [1.0]})
    lam = np.ones(50)
    lam[31] = np.nan
    with pytest.raises(ValueError, match="member 31: lam"):
        pc.ensemble(system, (0, 1), 0.1, sweep={"lam": lam})
    states = np.zeros((3, 4))
    states[2, 3] = np.inf
    with pytest.raises(ValueError, match="member 2"):
        pc.ensemble(system, (0, 1), 0.1, states=states)
    sp = pytest.importorskip("sympy")
    from physicskit.classical.utils import HamiltonianEngine

    q, p = sp.symbols("q p")
    oscillator = HamiltonianEngine([q], [p], p**2 / 2 + q**2 / 2).system([1.0], [0.0])
    with pytest.raises(ValueError, match="no parameters; vary the initial states"):
        pc.ensemble(oscillator, (0, 1), 0.1, grid={"k": [1.0]})

    class Mine(type(system)):
        pass

    with pytest.raises(TypeError, match="Python subclass"):
        pc.ensemble(Mine(system.engine, [0.0, 0.1], [0.3, 0.0]), (0, 1), 0.1,
                    grid={"lam": [1.0]})
