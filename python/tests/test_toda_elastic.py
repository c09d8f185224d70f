"""The two systems added through the catalogue alone: the periodic Toda lattice and the
elastic (spring) pendulum, checked from Python against computations written here."""

import numpy as np
import pytest

import physicskit.classical as pc


def lax_matrix(q, p, a, b):
    """Flaschka's Lax matrix of the periodic Toda lattice in momentum units, built here from
    its definition: diagonal p_i, off-diagonal and corner sqrt(a/b) exp(-b (q_{i+1} - q_i)/2)
    (for n = 2 the two bonds share one element, which holds their sum)."""
    n = len(q)
    lax = np.diag(np.asarray(p, dtype=float))
    for i in range(n):
        j = (i + 1) % n
        c = np.sqrt(a / b) * np.exp(-b * (q[j] - q[i]) / 2)
        lax[i, j] += c
        lax[j, i] += c
    return lax


@pytest.mark.parametrize("n, a, b", [(2, 1.0, 1.0), (5, 0.7, 1.6), (8, 1.0, 1.0)])
def test_toda_lax_eigenvalues_match_numpy(n, a, b):
    rng = np.random.default_rng(n)
    q0, p0 = rng.normal(0, 0.5, n), rng.normal(0, 0.8, n)
    toda = pc.TodaLattice(q0, p0, a=a, b=b)
    expected = np.linalg.eigvalsh(lax_matrix(q0, p0, a, b))
    # Two backward-stable symmetric eigensolvers (nalgebra's, LAPACK's) on the same n x n
    # matrix (n <= 8, entries O(1)): each errs by O(n eps |L|) ~ 1e-15, so 1e-13 absolute is
    # 100x margin and still fails on any wrong matrix entry.
    np.testing.assert_allclose(toda.conserved_quantities(), expected, rtol=0, atol=1e-13)
    # tr L^2 = 2 H (+ 4 a/b for n = 2, where the corner and the off-diagonal coincide).
    extra = 4 * a / b if n == 2 else 0.0
    assert np.sum(expected**2) == pytest.approx(2 * toda.energy() + extra, rel=1e-13)


def test_toda_eigenvalues_conserved_over_1e5_yoshida4_steps():
    n, a, b = 6, 1.0, 1.0
    q0 = np.array([0.0, 0.4, -0.3, 0.8, 0.1, -0.5])
    p0 = np.array([1.2, -0.4, 0.0, 0.7, -1.1, 0.3])
    toda = pc.TodaLattice(q0, p0, a=a, b=b)
    res = toda.integrate((0.0, 100.0), dt=1e-3, method="yoshida4")
    assert len(res.t) == 100_001
    scale = np.max(np.abs(np.linalg.eigvalsh(lax_matrix(q0, p0, a, b))))
    start = np.linalg.eigvalsh(lax_matrix(q0, p0, a, b))
    for row in (res.y[len(res.t) // 3], res.y[-1]):
        now = np.linalg.eigvalsh(lax_matrix(row[:n], row[n:], a, b))
        # yoshida4 conserves each integral up to its O(dt^4) modified-integral oscillation:
        # (1e-3)^4 = 1e-12 times O(1) derivatives, plus rounding; 1e-10 leaves 10x margin over
        # the 9.5e-12 measured in the Rust test of the same kind.
        assert np.max(np.abs(now - start)) <= 1e-10 * scale
        np.testing.assert_allclose(toda.conserved_quantities(row), now, rtol=0, atol=1e-13)
    # ... while the energy of single particles moves by O(1) of the mean.
    e_first = toda.per_particle_energy(res.q[0], res.p[0])
    e_last = toda.per_particle_energy(res.q[-1], res.p[-1])
    assert e_first.sum() == pytest.approx(res.energy[0], rel=1e-13)
    assert np.max(np.abs(e_last - e_first)) > 0.1 * np.mean(np.abs(e_first))


def test_toda_refuses_bad_input():
    with pytest.raises(ValueError, match="n"):
        pc.TodaLattice([0.0], [0.0])
    with pytest.raises(ValueError, match="b"):
        pc.TodaLattice([0.0, 1.0], [0.0, 0.0], b=0.0)
    with pytest.raises(ValueError, match="p0"):
        pc.TodaLattice([0.0, 1.0], [0.0, 0.0, 1.0])
    with pytest.raises(ValueError, match="q0"):
        pc.TodaLattice([0.0, 1j], [0.0, 0.0])


def elastic_field(m, k, l0, g):
    """The equations of motion derived here from L = m (sd^2 + r^2 thd^2)/2 + m g r cos th
    - k s^2/2 in q = (s, th), r = l0 + s (so rd = sd): s'' = r thd^2 + g cos th - (k/m) s,
    th'' = -(2 sd thd + g sin th) / r, as the first-order field of (s, th, sd, thd)."""
    def f(_t, y):
        s, th, sd, thd = y
        r = l0 + s
        return [sd, thd, r * thd**2 + g * np.cos(th) - k / m * s,
                -(2 * sd * thd + g * np.sin(th)) / r]
    return f


def test_elastic_pendulum_equations_and_positions():
    m, k, l0, g = 1.3, 25.0, 0.8, 9.81
    bob = pc.ElasticPendulum([0.3, 0.4], [0.2, -0.5], m=m, k=k, L0=l0, g=g)
    (s, th), (sd, thd) = bob.q, bob.qdot
    r = l0 + s
    expected = elastic_field(m, k, l0, g)(0.0, [s, th, sd, thd])[2:]
    # Closed forms evaluate the same expressions in another order: rounding, 1e-13 relative.
    np.testing.assert_allclose(bob.acceleration(bob.q, bob.qdot, 0.0), expected, rtol=1e-13)
    # The bob is L0 + s from the pivot.
    np.testing.assert_allclose(bob.positions(), [r * np.sin(th), -r * np.cos(th)], rtol=1e-15)
    expected_e = 0.5 * m * (sd**2 + r**2 * thd**2) - m * g * r * np.cos(th) + 0.5 * k * s**2
    assert bob.energy() == pytest.approx(expected_e, rel=1e-14)
    # E_bounce + E_swing = E - E_eq exactly in real arithmetic; the two sides differ only by
    # the rounding of O(10) terms of size O(10) against a difference of O(1): 1e-12 relative.
    assert bob.mode_energies().sum() == pytest.approx(
        expected_e - (-m * g * (l0 + m * g / k) + 0.5 * k * (m * g / k) ** 2), rel=1e-12
    )


def test_elastic_pendulum_follows_the_hand_derived_equations():
    # A 0.6 rad swing with a bounce, the spring compressed at the start (s0 < 0: L0 + s0 =
    # 0.95 m), against scipy's DOP853 on the equations derived above at rtol = atol = 1e-12
    # (its own error 2e-11 over these 5 s, against a run at 1e-13). rk4 at dt = 1e-3 errs by
    # 1.2e-9 here (measured with the same equations stepped by a hand-written RK4); 1e-8
    # bounds it with margin, while mistaking s for the length (a shift of L0 in r) moves the
    # state by O(0.1) within the first swing.
    from scipy.integrate import solve_ivp

    m, k, l0, g = 1.0, 39.24, 1.2, 9.81
    q0, v0 = [-0.25, 0.6], [0.4, -0.3]
    bob = pc.ElasticPendulum(q0, v0, m=m, k=k, L0=l0, g=g)
    run = bob.integrate((0.0, 5.0), 1e-3, method="rk4")
    ref = solve_ivp(elastic_field(m, k, l0, g), (0.0, 5.0), q0 + v0, method="DOP853",
                    t_eval=run.t, rtol=1e-12, atol=1e-12)
    assert ref.success
    np.testing.assert_allclose(run.y, ref.y.T, rtol=0, atol=1e-8)
    # The hanging equilibrium is at the stretch m g / k: a bob started there stays (to the
    # rounding of g - (k/m)(m g/k), ~1e-15 m/s^2 over 1 s: 1e-14 m).
    rest = pc.ElasticPendulum([m * g / k, 0.0], [0.0, 0.0], m=m, k=k, L0=l0, g=g)
    still = rest.integrate((0.0, 1.0), 1e-3, method="rk4")
    np.testing.assert_allclose(still.y[-1], [m * g / k, 0, 0, 0], rtol=0, atol=1e-14)
    assert rest.positions(still.y[-1, :2])[1] == pytest.approx(-(l0 + m * g / k), rel=1e-15)


def test_elastic_pendulum_energy_bounded_under_implicit_midpoint():
    bob = pc.ElasticPendulum([0.3, 0.3], [0.0, 0.0], k=29.43)
    res = bob.integrate((0.0, 200.0), dt=1e-3)
    assert res.method == "implicit_midpoint"
    err = np.abs(res.energy - res.energy[0]) / abs(res.energy[0])
    half = len(err) // 2
    # Symplectic: the error oscillates at O(dt^2) (~1e-7 here) with the slow bounce-swing
    # exchange (period ~40 s, so each half of the run holds several), without drifting: the
    # second half's maximum stays within 1.5x the first half's (a linear drift would double
    # it), and at the O(dt^2) level.
    assert err[half:].max() <= 1.5 * err[:half].max()
    assert err.max() < 1e-6
    # The stretch must leave the spring a positive length L0 + s0 (s0 = -L0: the bob on the
    # pivot; below, past it).
    for s0 in (-1.0, -1.5):
        with pytest.raises(ValueError, match=r"q0.*L0 \+ s0 = .* must be > 0"):
            pc.ElasticPendulum([s0, 0.3], [0.0, 0.0])
    with pytest.raises(ValueError, match="q0"):
        pc.ElasticPendulum([0.0, 0.3], [0.0, 0.0], L0=0.0)
