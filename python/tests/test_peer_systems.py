"""The systems and tools the physicskit 0.4.0 peer offers beyond the spec, checked against
independent references: Foucault's precession against 2 pi / (Omega sin(latitude)) and its
closed form against scipy's DOP853 on the stated equations; the reduced Euler's disk against
its closed form; the reduced rattleback's reversal and its symmetry; ``estimate_dt`` against a
fresh run; ``core.integrators`` against ``integrate`` bit for bit; the conservation helpers
against the systems' own invariants."""

import numpy as np
import pytest

import physicskit.classical as pc
from physicskit import _core
from physicskit.classical import HamiltonianSystem, ODESystem
from physicskit.classical.core import integrators as ci
from physicskit.classical.systems.newtonian import FoucaultPendulum
from physicskit.classical.systems.rotations import (
    EulersDisk,
    Rattleback,
    eulers_disk_theta_analytic,
)
from physicskit.classical.utils import conservation, stepsize

SIDEREAL_DAY = 86164.0905


# -- Foucault's pendulum ------------------------------------------------------------------


def swing_plane_angles(t, x, y):
    """The swing plane's direction at each turning point of the swing (the samples where the
    bob is farthest from the vertical), unwrapped modulo pi, with their times."""
    r2 = x * x + y * y
    turn = np.nonzero((r2[1:-1] > r2[:-2]) & (r2[1:-1] >= r2[2:]))[0] + 1
    # A plane's direction is defined modulo pi: unwrap the doubled angle.
    return t[turn], 0.5 * np.unwrap(2 * np.arctan2(y[turn], x[turn]))


def test_foucault_precession_period_is_sidereal_day_over_sin_latitude():
    # Foucault's Panthéon pendulum with the defaults, released from rest; runs over a quarter
    # of the precession period (the plane turns by pi/2, clockwise in the north).
    f = FoucaultPendulum.from_deflection(3.0)
    expected = SIDEREAL_DAY / np.sin(np.deg2rad(48.85))
    assert f.precession_period() == pytest.approx(expected, rel=1e-15)
    span = round(expected / 4 / 0.5) * 0.5  # a whole number of samples

    def measured_period(res):
        t, angle = swing_plane_angles(res.t, res.y[:, 0], res.y[:, 1])
        assert angle[-1] - angle[0] == pytest.approx(-np.pi / 2, abs=0.01)
        return -2 * np.pi / np.polyfit(t, angle, 1)[0]

    # At a turning point the bob is on the swing ellipse's major axis, which turns rigidly at
    # omega_z. Samples every 0.5 s place a turning point within 0.25 s: an angle error of
    # ~1e-5 rad per point (the turn itself, and the minor axis, omega_z / Omega ~ 1e-4 of the
    # major, seen 0.25 s off the tip), against a turn of pi/2 fitted over ~3500 points: the
    # fitted period is good to ~1e-7; 1e-6 is safely above that.
    accurate = FoucaultPendulum.from_deflection(3.0).integrate_sampled(
        (0.0, span), 0.5, method="dop853", rtol=1e-11, atol=1e-12, energy=False)
    assert measured_period(accurate) == pytest.approx(expected, rel=1e-6)
    # Implicit midpoint turns a mode of frequency nu into (2/h) atan(nu h / 2); the plane
    # turns at half the difference of the two modes' (Omega +- omega_z), so slower by the
    # factor 1 - (omega0 h)^2 / 4 (9e-5 at h = 0.05): the measured period shows exactly that.
    h = 0.05
    midpoint = FoucaultPendulum.from_deflection(3.0).integrate_sampled(
        (0.0, span), h, stride=10, energy=False)
    slowed = expected / (1 - (f.omega0 * h) ** 2 / 4)
    assert measured_period(midpoint) == pytest.approx(slowed, rel=1e-6)
    assert measured_period(midpoint) != pytest.approx(expected, rel=1e-5)


def test_foucault_energy_is_conserved_and_corotating_frame_unwinds_the_plane():
    f = FoucaultPendulum.from_deflection(2.0, angle_deg=30.0, omega_earth=2 * np.pi / 600.0)
    e0 = f.energy()
    res = f.integrate((0.0, 300.0), 0.02)
    # A quadratic invariant of a linear equation: implicit midpoint keeps it to the solver's
    # rounding (1e5 steps of ~1e-16 each, random-walk-like): 1e-12 relative.
    assert np.max(np.abs(res.energy - e0)) / e0 < 1e-12
    xr, yr = FoucaultPendulum.to_corotating_frame(res.y[:, 0], res.y[:, 1], res.t, f.omega_z)
    # Turning back by omega_z t leaves an ellipse with its major axis fixed at 30 degrees;
    # the minor axis is omega_z / Omega of the major (~2%): the distance from the 30-degree
    # line stays below 3% of the amplitude.
    normal = np.array([-np.sin(np.deg2rad(30.0)), np.cos(np.deg2rad(30.0))])
    assert np.max(np.abs(xr * normal[0] + yr * normal[1])) < 0.03 * 2.0
    # In the lab frame the plane has turned by omega_z * 300 s = pi: the bob has swept it.
    assert np.max(np.abs(res.y[:, 0] * normal[0] + res.y[:, 1] * normal[1])) > 1.0


def test_foucault_analytic_solution_against_scipy_dop853():
    scipy_integrate = pytest.importorskip("scipy.integrate")
    omega0, omega_z = 0.7, 0.05
    q0, v0 = np.array([0.3, -0.2]), np.array([0.1, 0.25])

    def rhs(t, s):  # the stated equations, written here independently of the package
        x, y, vx, vy = s
        return [vx, vy, -omega0**2 * x + 2 * omega_z * vy, -omega0**2 * y - 2 * omega_z * vx]

    t = np.linspace(0.0, 60.0, 601)
    sol = scipy_integrate.solve_ivp(rhs, (0.0, 60.0), np.r_[q0, v0], method="DOP853",
                                    t_eval=t, rtol=1e-12, atol=1e-14)
    x, y = FoucaultPendulum.analytic_solution(q0, v0, omega0, omega_z, t)
    assert x.shape == y.shape == t.shape
    # DOP853 at rtol 1e-12 over ~7 periods: global error ~1e-11 of the amplitude (~0.4).
    np.testing.assert_allclose(x, sol.y[0], atol=1e-10)
    np.testing.assert_allclose(y, sol.y[1], atol=1e-10)
    # And against the package's own run of the catalogue system (dop853, same tolerance).
    f = FoucaultPendulum(q0, v0, length=9.81 / omega0**2, g=9.81, latitude_deg=90.0,
                         omega_earth=omega_z)
    run = f.integrate_sampled((0.0, 60.0), 0.1, method="dop853", rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(run.y[:, 0], x, atol=1e-10)
    np.testing.assert_allclose(run.y[:, 1], y, atol=1e-10)


def test_foucault_attributes_and_members():
    f = FoucaultPendulum([1.0, 0.5], [0.1, 0.0])
    assert f.omega0 == np.sqrt(9.81 / 67.0)
    assert f.omega_earth == 2 * np.pi / SIDEREAL_DAY
    np.testing.assert_array_equal(f.position, [1.0, 0.5])
    np.testing.assert_array_equal(f.velocity, [0.1, 0.0])
    assert f.energy() == 0.5 * 0.1**2 + 0.5 * f.omega0**2 * (1.0 + 0.25)
    assert FoucaultPendulum([1, 0], [0, 0], latitude_deg=0.0).precession_period() == np.inf
    with pytest.raises(ValueError, match="latitude_deg"):
        FoucaultPendulum([1, 0], [0, 0], latitude_deg=91.0)


# -- the reduced Euler's disk ---------------------------------------------------------------


def test_eulers_disk_theta_follows_its_closed_form_up_to_the_collapse():
    theta0, rate, prec = 0.5, 0.05, 1.3
    t_collapse = theta0**2 / (2 * rate)
    disk = EulersDisk(theta0, decay_rate=rate, precession_const=prec)
    res = disk.integrate((0.0, 0.95 * t_collapse), 1e-4, method="rk4")
    exact = eulers_disk_theta_analytic(res.t, theta0, rate)
    # RK4 at dt = 1e-4 on theta' = -a/theta, theta >= 0.11: local error ~ dt^5 theta^(-9)
    # ~ 1e-12 per step near the end; 1e-9 bounds the accumulated error.
    np.testing.assert_allclose(res.y[:, 0], exact, atol=1e-9)
    # phi: dphi/dtheta = -prec/rate, so phi = (prec/rate)(theta0 - theta).
    np.testing.assert_allclose(res.y[:, 1], prec / rate * (theta0 - exact), atol=1e-7)
    # energy() is theta itself (as the peer's).
    np.testing.assert_array_equal(res.energy, res.y[:, 0])
    assert disk.theta == res.y[-1, 0] and disk.phi == res.y[-1, 1]
    # After the collapse the closed form is zero.
    assert eulers_disk_theta_analytic([t_collapse, 2 * t_collapse], theta0, rate).tolist() == [
        0.0, 0.0]


def test_eulers_disk_floor_bounds_the_rates():
    disk = EulersDisk(1e-5, decay_rate=0.05, precession_const=1.0, theta_floor=1e-3)
    np.testing.assert_array_equal(disk.derivatives(0.0, disk.state), [-50.0, 1000.0])


# -- the reduced rattleback ---------------------------------------------------------------


def test_rattleback_equations_are_the_stated_ones():
    r = Rattleback([0.0, 0.0, 1.0], I1=1.3, I2=1.7, I3=2.9, gamma=0.7, mu=0.03, eta=0.05)
    rng = np.random.default_rng(1)
    for s in rng.normal(size=(20, 3)):
        n1, n2, n3 = s
        want = [(1.7 - 2.9) / 1.3 * n2 * n3 + 0.7 * n3**2 - 0.03 * n1 - 0.05 * n1**3,
                (2.9 - 1.3) / 1.7 * n3 * n1 - 0.03 * n2 - 0.05 * n2**3,
                (1.3 - 1.7) / 2.9 * n1 * n2 - 0.03 * n3]
        # The same terms summed in another order: a few ulps of the largest term.
        np.testing.assert_allclose(r.derivatives(0.0, s), want, rtol=1e-13, atol=1e-14)


def reversal(res):
    # The library's one definition of a reversal time: the first zero of the spin n3 averaged
    # over its default window (two pitching periods of the rolling rattleback; this model's n3
    # has no faster swing, so the mean's zero lies within a few ms of n3's own).
    return _core.spin_reversal_time(res.t, res.y[:, 2])


def test_rattleback_reverses_and_mirrors_exactly():
    # A hard spin with a little rocking reverses within a few seconds (n3 changes sign).
    spun = Rattleback([0.01, 0.01, 3.0]).integrate((0.0, 20.0), 1e-3, method="rk4")
    t_rev = reversal(spun)
    assert t_rev is not None and 0.5 < t_rev < 5.0
    # The equations are invariant under (n1, n2, n3) -> (n1, -n2, -n3), and rounding is
    # symmetric under negation: the opposite spin's run is the exact mirror image, so it
    # reverses at the same time (the mean's sums and the zero's interpolation negate exactly
    # too). (The peer's model cannot single out one sense of spin.)
    mirror = Rattleback([0.01, -0.01, -3.0]).integrate((0.0, 20.0), 1e-3, method="rk4")
    np.testing.assert_array_equal(mirror.y[:, 0], spun.y[:, 0])
    np.testing.assert_array_equal(mirror.y[:, 1:], -spun.y[:, 1:])
    assert reversal(mirror) == t_rev
    # Without the symmetry-breaking coupling it is a damped Euler top: no reversal.
    plain = Rattleback([0.01, 0.01, 3.0], gamma=0.0).integrate((0.0, 20.0), 1e-3, method="rk4")
    assert reversal(plain) is None
    # The kinetic energy decays without gamma (damping only).
    assert np.all(np.diff(plain.energy) <= 0.0)


# -- core.integrators, bit for bit ----------------------------------------------------------


def duffing(t, y):
    return np.array([y[1], -y[0] - 0.3 * y[0] ** 3 + 0.1 * np.cos(t)])


def quartic_force(q, t):
    return -q - 0.5 * q**3


class Duffing(ODESystem):
    def derivatives(self, t, y):
        return duffing(t, y)

    def energy(self, state=None):
        return 0.0


class Quartic(HamiltonianSystem):
    separable = True
    mass_inv = np.array([0.5, 2.0])

    def __init__(self, q0, p0):
        super().__init__(q0, p0)

    def force(self, q, t):
        return quartic_force(q, t)

    def kinetic_energy(self, p):
        return 0.5 * float(self.mass_inv @ (p * p))

    def potential_energy(self, q):
        return float(np.sum(0.5 * q**2 + 0.125 * q**4))


@pytest.mark.parametrize("method, fn", [("rk4", ci.rk4_integrate),
                                        ("implicit_midpoint", ci.implicit_midpoint_integrate)])
def test_ode_functions_equal_integrate_bit_for_bit(method, fn):
    y0 = np.array([0.8, -0.1])
    t, y = fn(duffing, y0, 0.5, 400, 0.01)
    ref = Duffing(y0)
    ref.t = 0.5
    run = ref.integrate((0.5, 0.5 + 400 * 0.01), 0.01, method)
    assert t.shape == (401,) and y.shape == (401, 2)
    np.testing.assert_array_equal(y, run.y)
    np.testing.assert_array_equal(t, run.t)
    step = ci.rk4_step if method == "rk4" else ci.implicit_midpoint_step
    np.testing.assert_array_equal(step(duffing, 0.5, y0, 0.01), run.y[1])


@pytest.mark.parametrize("method, fn, step", [
    ("verlet", ci.velocity_verlet_integrate, ci.velocity_verlet_step),
    ("yoshida4", ci.yoshida4_integrate, ci.yoshida4_step),
])
def test_separable_functions_equal_integrate_bit_for_bit(method, fn, step):
    q0, p0 = np.array([0.7, -0.3]), np.array([0.1, 0.4])
    t, q, p = fn(quartic_force, [0.5, 2.0], q0, p0, 0.0, 300, 0.02)
    run = Quartic(q0, p0).integrate((0.0, 300 * 0.02), 0.02, method)
    assert t.shape == (301,) and q.shape == p.shape == (301, 2)
    np.testing.assert_array_equal(q, run.q)
    np.testing.assert_array_equal(p, run.p)
    q1, p1 = step(quartic_force, [0.5, 2.0], q0, p0, 0.02)
    np.testing.assert_array_equal(q1, run.q[1])
    np.testing.assert_array_equal(p1, run.p[1])


def test_make_separable_derivatives_and_scalar_mass_inv():
    deriv = ci.make_separable_derivatives(quartic_force, 0.5, 2)
    y = np.array([0.7, -0.3, 0.1, 0.4])
    np.testing.assert_array_equal(deriv(0.0, y), np.r_[0.5 * y[2:], quartic_force(y[:2], 0.0)])
    # RK4 on the wrapped field agrees with yoshida4 on the force to their joint accuracy.
    _t, yr = ci.rk4_integrate(deriv, y, 0.0, 500, 0.01)
    _t, q, p = ci.yoshida4_integrate(quartic_force, 0.5, y[:2], y[2:], 0.0, 500, 0.01)
    # Both fourth order at dt = 0.01 over 5 time units: errors ~1e-9; 1e-7 is safe.
    np.testing.assert_allclose(yr[:, :2], q, atol=1e-7)
    np.testing.assert_allclose(yr[:, 2:], p, atol=1e-7)


def test_functions_refuse_bad_input_clearly():
    with pytest.raises(TypeError, match="callable"):
        ci.rk4_integrate(42, [1.0], 0.0, 10, 0.1)
    with pytest.raises(ValueError, match="n_steps"):
        ci.rk4_integrate(duffing, [1.0, 0.0], 0.0, -1, 0.1)
    with pytest.raises(ValueError, match="tol"):
        ci.implicit_midpoint_integrate(duffing, [1.0, 0.0], 0.0, 10, 0.1, tol=0.0)
    with pytest.raises(ValueError, match="mass_inv"):
        ci.yoshida4_integrate(quartic_force, [1.0, 2.0, 3.0], [0.1, 0.2], [0.0, 0.0], 0.0, 5,
                              0.1)
    # A callback's own exception comes back unchanged.
    def broken(t, y):
        raise ZeroDivisionError("inside")
    with pytest.raises(ZeroDivisionError, match="inside"):
        ci.rk4_integrate(broken, [1.0], 0.0, 3, 0.1)
    t, y = ci.rk4_integrate(duffing, [1.0, 0.0], 2.0, 0, 0.1)
    assert t.tolist() == [2.0] and y.tolist() == [[1.0, 0.0]]


# -- utils.stepsize and utils.conservation ------------------------------------------------


def test_estimate_dt_reaches_the_drift_it_claims():
    def factory():
        return pc.KeplerSystem.from_orbital_elements(a=1.0, e=0.5)

    est = stepsize.estimate_dt(factory, "yoshida4", tol=1e-6, target_steps=20000,
                               probe_steps=2000, dt_initial=0.01)
    assert isinstance(est, stepsize.StepSizeEstimate)
    assert est.verified_at_steps == 20000 and est.n_evaluations >= 3
    run = factory().integrate((0.0, 20000 * est.dt), est.dt, "yoshida4")
    drift = conservation.relative_energy_drift(run.energy).max()
    assert drift <= 1e-6
    assert drift == est.achieved_drift  # the same run, bit for bit
    # Not needlessly small: twice the step (fourth order: ~16 times the drift) fails.
    run2 = factory().integrate((0.0, 20000 * 2 * est.dt), 2 * est.dt, "yoshida4")
    assert conservation.relative_energy_drift(run2.energy).max() > 1e-6


def test_conservation_helpers_against_the_system():
    k = pc.KeplerSystem.from_orbital_elements(a=1.0, e=0.6)
    run = k.integrate((0.0, 30.0), 1e-3, "yoshida4")
    ell = conservation.angular_momentum_2d(run.q, run.p)
    want = np.array([k.angular_momentum(q, p) for q, p in zip(run.q[:50], run.p[:50])])
    np.testing.assert_array_equal(ell[:50], want)
    # yoshida4 keeps L of a central force to rounding (each step's kicks are radial).
    assert conservation.angular_momentum_drift(run.q, run.p).max() < 1e-12
    e = run.energy
    np.testing.assert_array_equal(conservation.energy_drift(e), np.abs(e - e[0]))
    np.testing.assert_array_equal(conservation.relative_energy_drift(e),
                                  np.abs(e - e[0]) / abs(e[0]))
    # The LRL vector's magnitude drifts at the integrator's energy-error level (~1e-8 here).
    lrl = conservation.lrl_drift(k, run.q[::100], run.p[::100])
    assert lrl.shape == (len(run.q[::100]),) and lrl.max() < 1e-6
    assert np.all(np.isinf(conservation.relative_energy_drift([0.0, 1.0])))
    with pytest.raises(ValueError, match="shape"):
        conservation.angular_momentum_2d(np.zeros((3, 3)), np.zeros((3, 3)))
