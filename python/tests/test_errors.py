"""Every ValueError case of the spec, wrong lengths and NaN inputs raise ValueError with a
message that says what to change; nothing reaches Python as a panic."""

import numpy as np
import pytest

import physicskit.classical as pc

from conftest import make_systems

NAN = float("nan")


@pytest.mark.parametrize("bad, match", [
    (lambda: pc.KeplerSystem([1.0, 0.0, 0.0], [0.0, 1.0]), "length"),
    (lambda: pc.KeplerSystem([1.0, 0.0], [0.0]), "length"),
    (lambda: pc.KeplerSystem([NAN, 0.0], [0.0, 1.0]), "NaN"),
    (lambda: pc.KeplerSystem([1.0, 0.0], [0.0, 1.0], mu=-1.0), "mu"),
    (lambda: pc.KeplerSystem.from_orbital_elements(1.0, 1.0), "e"),
    (lambda: pc.KeplerSystem.from_orbital_elements(-1.0, 0.5), "a"),
    (lambda: pc.DoublePendulum([1.0, 2.0, 3.0], [0.0, 0.0]), "length"),
    (lambda: pc.DoublePendulum([1.0, 2.0], [NAN, 0.0]), "NaN"),
    (lambda: pc.DoublePendulum([1.0, 2.0], [0.0, 0.0], l1=0.0), "l1"),
    (lambda: pc.CoupledOscillators([0.1, 0.2], [0.0, 0.0]), "length"),
    (lambda: pc.CoupledOscillators([0.1, 0.2, 0.3, 0.4], [0.0] * 4), "length"),
    (lambda: pc.HarmonicChain([1.0, 2.0, 3.0], [0.0, 0.0]), "length"),
    (lambda: pc.HenonHeilesSystem([np.inf, 0.0], [0.0, 0.0]), "NaN"),
    (lambda: pc.EulerTop([1.0, 2.0]), "length"),
    (lambda: pc.EulerTop([0.0, 1.0, 0.0], quat0=[0.0, 0.0, 0.0, 0.0]), "quat"),
    (lambda: pc.EulerTop([0.0, 1.0, 0.0], I1=-1.0), "I1"),
    (lambda: pc.HeavySymmetricTop([0.0, 0.5], [0.0, 0.0, 20.0]), "length"),
    (lambda: pc.BeadOnRotatingHoop(NAN, 0.0), "NaN"),
    (lambda: pc.ProjectileMotion([0.0, 0.0], [1.0, 1.0], m=0.0), "m"),
    (lambda: pc.PendulumSwarm([0.0, 1.0], [0.0]), "length"),
    (lambda: pc.PendulumSwarm.from_box(1.0, 0.0, 0.1, 0.1, n=-3), "n"),
    (lambda: pc.FPUTChain(n=8, mode=9), "mode"),
    (lambda: pc.FPUTChain(n=-1), "n"),
    (lambda: pc.SineGordonChain(5, q0=[0.0] * 4), "length"),
    (lambda: pc.SineGordonChain.kink(20, 10.0, velocity=1.0), "velocity"),
    (lambda: pc.SineGordonChain.kink(20, 10.0, velocity=-1.2), "velocity"),
    (lambda: pc.pendulum_action_angle(1.0), "energy|E"),
    (lambda: pc.pendulum_action_angle(-1.0), "energy|E"),
    (lambda: pc.pendulum_action_angle(2.0, g_over_l=1.0), "energy|E"),
    (lambda: pc.pendulum_action_angle(0.0, g_over_l=NAN), "g_over_l"),
    (lambda: pc.find_theta_equilibrium(1.0, 2.0, 1.0, 0.5, 9.81, bracket=(2.0, 1.0)), "bracket"),
])
def test_constructor_and_function_errors(bad, match):
    with pytest.raises(ValueError, match=match):
        bad()


@pytest.mark.parametrize("t_span, dt, match", [
    ((0.0, 1.0), 0.0, "dt"),
    ((0.0, 1.0), -0.1, "dt"),
    ((0.0, 1.0), NAN, "dt"),
    ((0.0, -1.0), 0.1, "t1 must be >= t0"),
    ((0.0, 1.0), 0.3, "whole number"),
    ((0.0, NAN), 0.1, "finite"),
    ((0.0, 1.0, 2.0), 0.1, "t_span"),
    (5.0, 0.1, "t_span"),
])
def test_integrate_time_span_errors(system_name, t_span, dt, match):
    s = make_systems()[system_name]()
    with pytest.raises(ValueError, match=match):
        s.integrate(t_span, dt)
    assert s.t == 0.0  # nothing changed


def test_unknown_and_unsupported_methods(system_name):
    s = make_systems()[system_name]()
    with pytest.raises(ValueError, match="unknown method `euler`; valid methods are") as info:
        s.integrate((0.0, 0.1), 0.01, method="euler")
    # The names listed are exactly the methods this system accepts: each listed one runs, each
    # other one of methods() is refused as unable to integrate the system.
    listed = str(info.value).split("valid methods are: ")[1].split(", ")
    # One step of 1 ms: the fastest motion of the catalogue's demonstration starts (the rolling
    # rattleback's rocking, about 100 rad/s) turns 0.1 rad in it, where every implicit solve
    # converges; at 10 ms (1 rad a step) the rolling bodies' implicit midpoint does not.
    for m in (m["name"] for m in pc.methods()):
        if m in listed:
            make_systems()[system_name]().integrate((0.0, 1e-3), 1e-3, method=m)
        else:
            with pytest.raises(ValueError, match="cannot integrate"):
                make_systems()[system_name]().integrate((0.0, 1e-3), 1e-3, method=m)
    with pytest.raises(ValueError, match="unknown method"):
        s.integrate((0.0, 0.1), 0.01, method="RK4")
    if not isinstance(s, pc.HamiltonianSystem):
        for m in ("verlet", "yoshida4"):
            with pytest.raises(ValueError, match="implicit_midpoint"):
                s.integrate((0.0, 0.1), 0.01, method=m)


def test_drag_refuses_splitting_methods():
    s = pc.ProjectileMotion.from_launch(20.0, 30.0, drag_coeff=0.1)
    for m in ("verlet", "yoshida4"):
        with pytest.raises(ValueError, match="rk4|implicit_midpoint"):
            s.integrate((0.0, 1.0), 0.01, method=m)
    r = s.integrate((0.0, 1.0), 0.01, method="rk4")
    assert np.all(np.diff(r.energy) < 0)  # drag only removes energy


def test_bad_state_before_integrate():
    s = pc.KeplerSystem.from_orbital_elements(1.0, 0.5)
    s.state[0] = NAN
    with pytest.raises(ValueError, match="NaN|non-finite"):
        s.integrate((0.0, 1.0), 0.01)
    with pytest.raises(ValueError, match="length"):
        s.reset([1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="length"):
        s.energy([1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="length"):
        s.potential_energy([1.0])
    with pytest.raises(ValueError, match="length"):
        s.lrl_vector(q=[1.0, 0.0, 0.0])


def test_blow_up_is_reported_not_propagated():
    # A force that overflows (V = exp(q^2) from q = 5 with a large step): the state becomes
    # non-finite and the run stops with a ValueError naming the time, not NaN arrays.
    class Steep(pc.HamiltonianSystem):
        def kinetic_energy(self, p):
            return 0.5 * float(p @ p)

        def potential_energy(self, q):
            return float(np.exp(min(q[0] ** 2, 700.0)))

        def force(self, q, t=0.0):
            with np.errstate(over="ignore"):
                return -2.0 * q * np.exp(q ** 2)

    with pytest.raises(ValueError, match="non-finite value in `state` at t ="):
        Steep([5.0], [0.0]).integrate((0.0, 10.0), 0.1)


def test_force_of_non_separable_is_not_implemented():
    class NonSeparable(pc.HamiltonianSystem):
        separable = False

        def kinetic_energy(self, p):
            return 0.5 * float(p @ p)

        def potential_energy(self, q):
            return 0.0

    with pytest.raises(NotImplementedError):
        NonSeparable([0.0], [1.0]).force(np.array([0.0]))
