"""q and p of a native run are split off y on first access: same values, C-contiguous, cached."""

import dataclasses

import numpy as np

import physicskit.classical as pc


def test_q_and_p_are_the_halves_of_y_as_contiguous_float64_arrays():
    for system in (
        pc.KeplerSystem.from_orbital_elements(1.0, 0.5),
        pc.DoublePendulum([2.0, 1.0], [0.5, -0.3]),
    ):
        r = system.integrate((0.0, 0.1), 1e-3)
        n = system.ndof
        for half, cols in ((r.q, slice(0, n)), (r.p, slice(n, 2 * n))):
            assert half.dtype == np.float64 and half.flags.c_contiguous
            assert half.shape == (r.y.shape[0], n)
            assert np.array_equal(half, r.y[:, cols])
        # Split once, then kept: the same object on every access.
        assert r.q is r.q and r.p is r.p
        assert isinstance(r, pc.SimulationResult) and dataclasses.is_dataclass(r)
        assert dataclasses.asdict(r)["q"].shape == r.q.shape


def test_ode_results_still_have_no_q_or_p():
    r = pc.EulerTop([0.01, 1.0, 0.01]).integrate((0.0, 0.1), 1e-3)
    assert r.q is None and r.p is None
