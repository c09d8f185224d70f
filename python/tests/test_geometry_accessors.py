"""The geometry the plots draw, as the systems' own methods: the heavy top's symmetry axis, the
Euler top's body angular momentum and its box, the bead's position on the hoop, and the
separatrix energies of the pendulum family. Each is checked against an independent numpy
computation or an invariant (the Rust tests check the same against elementary rotations,
quadrature and numerically classified equilibria)."""

import numpy as np
import pytest

import physicskit.classical as pc


def _rot_z(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _rot_x(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def test_symmetry_axis_is_the_third_column_of_the_z_x_z_rotation():
    top = pc.HeavySymmetricTop([0.3, 0.5, 0.0], [0.0, 0.0, 20.0], l=0.4)
    for q in ([0.3, 0.5, 0.0], [-2.0, 2.9, 1.7], [4.0, 0.01, -3.0]):
        r = _rot_z(q[0]) @ _rot_x(q[1]) @ _rot_z(q[2])
        axis = top.symmetry_axis(q)
        # Products of order-1 factors in another order: a few ulps.
        np.testing.assert_allclose(axis, r[:, 2], atol=1e-15)
        assert np.dot(axis, axis) == pytest.approx(1.0, abs=4e-16)
    np.testing.assert_array_equal(top.symmetry_axis(), top.symmetry_axis(top.q))
    with pytest.raises(ValueError, match="q"):
        top.symmetry_axis([0.0, 0.5])


def test_body_angular_momentum_meets_the_invariants_and_is_fixed_in_space():
    top = pc.EulerTop([0.1, 1.0, 0.2], I1=1.0, I2=2.0, I3=3.0)
    run = top.integrate_sampled((0.0, 5.0), 1e-3, stride=100)
    space = []
    for s in run.y:
        big_l = top.body_angular_momentum(s)
        np.testing.assert_array_equal(big_l, np.array([1.0, 2.0, 3.0]) * s[:3])
        # |L|^2 and 2E = L . omega against the system's own invariants (a few ulps of ~1).
        assert big_l @ big_l == pytest.approx(top.angular_momentum_squared(s), rel=1e-15)
        assert big_l @ s[:3] == pytest.approx(2.0 * top.energy(s), rel=1e-15)
        space.append(top.rotation_matrix(s) @ big_l)
    # Torque-free: R L is constant. Implicit midpoint's O(dt^2) orientation error over t = 5
    # at dt = 1e-3 is ~1e-6 at most; 1e-5 still rejects the body frame, in which L moves by
    # order 1 on this tumbling orbit.
    space = np.array(space)
    assert np.abs(space - space[0]).max() < 1e-5
    np.testing.assert_array_equal(top.body_angular_momentum(), top.body_angular_momentum(top.state))


def test_inertia_box_reproduces_the_moments():
    top = pc.EulerTop([0.0, 0.0, 1.0], I1=0.7, I2=0.9, I3=1.3)
    for mass in (1.0, 2.5):
        a1, a2, a3 = top.inertia_box(mass)
        # A uniform box of half-extents a_i: I1 = M (a2^2 + a3^2) / 3, and cyclically;
        # a few roundings of order-1 numbers.
        moments = mass / 3.0 * np.array([a2**2 + a3**2, a1**2 + a3**2, a1**2 + a2**2])
        np.testing.assert_allclose(moments, [0.7, 0.9, 1.3], rtol=1e-14)
    # The default moments (1, 2, 3) are those of a plate: I3 = I1 + I2.
    assert pc.EulerTop([0.0, 0.0, 1.0]).inertia_box()[2] == 0.0
    for bad in (0.0, -1.0, np.nan):
        with pytest.raises(ValueError, match="mass"):
            top.inertia_box(bad)
    with pytest.raises(ValueError, match="I3"):
        pc.EulerTop([0.0, 0.0, 1.0], I1=1.0, I2=2.0, I3=10.0).inertia_box()


def test_bead_position_on_the_hoop():
    bead = pc.BeadOnRotatingHoop(0.3, 0.0, R=1.5)
    for theta in (0.0, 0.3, 2.0, np.pi):
        x, y = bead.positions([theta])
        # On the hoop, at the angle theta from the bottom: one product each.
        assert np.hypot(x, y) == pytest.approx(1.5, rel=1e-15)
        assert np.arctan2(x, -y) == pytest.approx(theta, abs=1e-15)
    np.testing.assert_array_equal(bead.positions(), bead.positions(bead.q))


def test_separatrix_energies_are_the_energies_of_the_saddles():
    swarm = pc.PendulumSwarm([0.1, 0.2], [0.0, 0.0], g_over_l=2.5)
    np.testing.assert_array_equal(swarm.separatrix_energies(), [2.5])
    assert swarm.per_particle_energy([np.pi, np.pi], [0.0, 0.0])[0] == pytest.approx(2.5,
                                                                                     rel=1e-15)
    below = pc.BeadOnRotatingHoop(0.3, 0.0, R=1.0, omega=2.0, g=9.81)
    above = pc.BeadOnRotatingHoop(0.3, 0.0, R=1.0, omega=5.0, g=9.81)
    # The top (theta = pi) is always a saddle here; the bottom only above sqrt(g/R) = 3.13.
    # Its level is the system's energy at rest there (sin(pi) ~ 1e-16 rounding).
    top_level = below.energy(np.array([np.pi, 0.0]))
    np.testing.assert_allclose(below.separatrix_energies(), [top_level], atol=1e-13)
    np.testing.assert_allclose(above.separatrix_energies(), [0.0, top_level], atol=1e-13)
