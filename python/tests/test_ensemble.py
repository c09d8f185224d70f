"""Ensembles from Python: grid-shaped outputs, bit-identity with single runs and across thread
counts, bad members refused by index before any work, Python subclasses refused."""

import numpy as np
import pytest

import physicskit.classical as pc

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


def test_chaos_reductions_equal_single_orbit_max_lyapunov_and_sali_bit_for_bit():
    # Henon-Heiles at E = 1/8 from the section x = 0 (p_x >= 0 from the energy), a 2 x 3 grid.
    y, py = np.meshgrid([-0.2, 0.1], [-0.1, 0.0, 0.25], indexing="ij")
    px = np.sqrt(2 * 0.125 - py**2 - y**2 + 2 * y**3 / 3)
    states = np.stack([np.zeros_like(y), y, px, py], axis=-1)
    hh = pc.HenonHeilesSystem([0.0, 0.0], [0.0, 0.0])
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
    # A member stops on the step of its flip; one that never flips runs the whole span.
    assert np.all(early.steps[flipped] == np.ceil(full.events["flip"][flipped] / 0.01 - 1e-9))
    assert np.all(early.steps[~flipped] == 200) and np.all(full.steps == 200)
