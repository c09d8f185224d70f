"""A migrating user's imports: every public name of the physicskit 0.4.0 peer that the
package offers, at the peer's import path, with the peer's signature (parameter names, kinds,
order and defaults), the peer's properties, static and class methods, and the constructor
arguments kept as read-only attributes.

The table below is written from the peer's installed 0.4.0 (read with ``inspect.signature``
in a separate virtual environment); the peer is not installed here, so nothing is read from
it at test time.
"""

import importlib
import inspect

import numpy as np
import pytest

_ = inspect.Parameter.empty  # no default

#: (module under physicskit.classical, {name or Class.member: [(parameter, default)]}); a
#: parameter name "**kwargs" is a VAR_KEYWORD parameter; ``self``/``cls`` are left out.
PEER = [
    ('systems.newtonian', {
        'FoucaultPendulum': [('q0', _), ('v0', _), ('length', 67.0), ('g', 9.81), ('latitude_deg', 48.85), ('omega_earth', 7.292115857915991e-05)],
        'FoucaultPendulum.from_deflection': [('amplitude', _), ('angle_deg', 0.0), ('length', 67.0), ('g', 9.81), ('latitude_deg', 48.85), ('omega_earth', 7.292115857915991e-05)],
        'FoucaultPendulum.precession_period': [],
        'FoucaultPendulum.analytic_solution': [('q0', _), ('v0', _), ('omega0', _), ('omega_z', _), ('t', _)],
        'FoucaultPendulum.to_corotating_frame': [('x', _), ('y', _), ('t', _), ('omega_z', _)],
        'FoucaultPendulum.energy': [('state', None)],
        'ProjectileMotion': [('q0', _), ('p0', _), ('m', 1.0), ('g', 9.81), ('drag_coeff', 0.0)],
        'KeplerSystem': [('q0', _), ('p0', _), ('k', 1.0), ('mu', 1.0), ('eps', 0.0), ('c_eps', 0.0), ('c_pn', 0.0), ('softening', 0.0)],
    }),
    ('systems.lagrangian', {
        'ElasticPendulum': [('q0', _), ('qdot0', _), ('m', 1.0), ('k', 39.24), ('L0', 1.0), ('g', 9.81)],
        'ElasticPendulum.positions': [('q', None)],
        'ElasticPendulum.energy': [('state', None)],
        'DoublePendulum': [('theta0', _), ('thetadot0', _), ('m1', 1.0), ('m2', 1.0), ('l1', 1.0), ('l2', 1.0), ('g', 9.81)],
        'BeadOnRotatingHoop': [('theta0', _), ('thetadot0', _), ('R', 1.0), ('omega', 2.0), ('g', 9.81)],
        'CoupledOscillators': [('q0', _), ('qdot0', _), ('n', 3), ('m', 1.0), ('k', 1.0)],
    }),
    ('systems.rotations', {
        'EulersDisk': [('theta0', _), ('phi0', 0.0), ('decay_rate', 0.05), ('precession_const', 1.0), ('theta_floor', 0.001)],
        'EulersDisk.energy': [('state', None)],
        'Rattleback': [('n0', _), ('I1', 1.0), ('I2', 1.5), ('I3', 2.0), ('gamma', 1.0), ('mu', 0.01), ('eta', 0.01)],
        'Rattleback.energy': [('state', None)],
        'eulers_disk_theta_analytic': [('t', _), ('theta0', _), ('decay_rate', _)],
        'EulerTop': [('omega0', _), ('I1', 1.0), ('I2', 2.0), ('I3', 3.0), ('quat0', None)],
        'HeavySymmetricTop': [('angles0', _), ('angledots0', _), ('I1', 1.0), ('I3', 0.5), ('M', 1.0), ('l', 1.0), ('g', 9.81)],
    }),
    ('systems.hamiltonian', {
        'HenonHeilesSystem': [('q0', _), ('p0', _)],
        'PendulumSwarm': [('q0', _), ('p0', _), ('g_over_l', 1.0)],
    }),
    ('systems.chains', {
        'HarmonicChain': [('q0', _), ('p0', _), ('m', 1.0), ('k', 1.0)],
        'FPUTChain': [('n', 32), ('m', 1.0), ('k', 1.0), ('beta', 0.0), ('mode', 1), ('amplitude', 1.0)],
        'SineGordonChain': [('n', 200), ('m', 1.0), ('k', 1.0), ('q0', None), ('p0', None)],
    }),
    ('utils.conservation', {
        'energy_drift': [('energy', _)],
        'relative_energy_drift': [('energy', _)],
        'angular_momentum_2d': [('q', _), ('p', _)],
        'angular_momentum_drift': [('q', _), ('p', _)],
        'lrl_drift': [('system', _), ('q', _), ('p', _)],
    }),
    ('utils.stepsize', {
        'StepSizeEstimate': [('dt', _), ('achieved_drift', _), ('verified_at_steps', _), ('n_evaluations', _)],
        'estimate_dt': [('system_factory', _), ('method', _), ('tol', 1e-06), ('target_steps', 100000), ('probe_steps', 2000), ('dt_initial', 0.01), ('growth', 2.0), ('rel_precision', 0.05), ('max_iter', 40)],
    }),
    ('core.integrators', {
        'rk4_step': [('deriv_func', _), ('t', _), ('y', _), ('dt', _)],
        'rk4_integrate': [('deriv_func', _), ('y0', _), ('t0', _), ('n_steps', _), ('dt', _)],
        'velocity_verlet_step': [('force_func', _), ('mass_inv', _), ('q', _), ('p', _), ('dt', _), ('t', 0.0)],
        'velocity_verlet_integrate': [('force_func', _), ('mass_inv', _), ('q0', _), ('p0', _), ('t0', _), ('n_steps', _), ('dt', _)],
        'yoshida4_step': [('force_func', _), ('mass_inv', _), ('q', _), ('p', _), ('dt', _), ('t', 0.0)],
        'yoshida4_integrate': [('force_func', _), ('mass_inv', _), ('q0', _), ('p0', _), ('t0', _), ('n_steps', _), ('dt', _)],
        'implicit_midpoint_step': [('deriv_func', _), ('t', _), ('y', _), ('dt', _), ('tol', 1e-12), ('max_iter', 100)],
        'implicit_midpoint_integrate': [('deriv_func', _), ('y0', _), ('t0', _), ('n_steps', _), ('dt', _), ('tol', 1e-12), ('max_iter', 100)],
        'make_separable_derivatives': [('force_func', _), ('mass_inv', _), ('ndof', _)],
    }),
    ('visualizers.phase_space', {
        'plot_phase_portrait': [('q', _), ('p', _), ('ax', None), ('label', None), ('**kwargs', _)],
        'plot_phase_swarm': [('q', _), ('p', _), ('ax', None), ('s', 4), ('**kwargs', _)],
        'poincare_section': [('q', _), ('p', _), ('section_q', _), ('section_p', _), ('value', 0.0), ('direction', 1)],
        'plot_poincare_section': [('q', _), ('p', _), ('section_q', _), ('section_p', _), ('value', 0.0), ('direction', 1), ('ax', None), ('**kwargs', _)],
        'plot_so3_momentum_sphere': [('omega_trajectory', _), ('I1', _), ('I2', _), ('I3', _), ('ax', None), ('n_grid', 40)],
    }),
    ('visualizers.modal_analysis', {
        'plot_modal_energy_bars': [('system', _), ('q', _), ('p', _), ('ax', None), ('**kwargs', _)],
        'animate_modal_energies': [('system', _), ('result', _), ('stride', 1), ('interval', 30), ('fig', None), ('ax', None)],
    }),
    ('visualizers.animations', {
        'SideBySideAnimator': [('result', _), ('init_physical', _), ('update_physical', _), ('mode', 'phase'), ('dof_index', 0), ('figsize', (11, 5)), ('physical_3d', False), ('stride', 1), ('left_title', 'Physical space')],
        'SideBySideAnimator.build': [('interval', 30), ('blit', False)],
        'SideBySideAnimator.save': [('filename', _), ('fps', None), ('**kwargs', _)],
        'pendulum_animation': [('result', _), ('positions_func', _), ('**kwargs', _)],
        'orbit_trace_animation': [('result', _), ('**kwargs', _)],
        'animate_elastic_pendulum': [('system', _), ('result', _), ('interval', 30), ('trail', 200), ('n_coils', 12), ('coil_width', 0.06)],
        'animate_rigid_body_tumble': [('top', _), ('result', _), ('half_extents', (1.0, 0.6, 0.3)), ('interval', 30), ('stride', 1)],
        'animate_eulers_disk': [('system', _), ('result', _), ('radius', 1.0), ('interval', 30), ('trail', 400)],
        'animate_rattleback': [('system', _), ('result', _), ('interval', 30), ('stride', 1)],
    }),
    ('visualizers.interactive', {
        'interactive_orbit': [('result', _), ('system', None), ('title', None)],
        'interactive_so3_momentum_sphere': [('omega_trajectory', _), ('I1', _), ('I2', _), ('I3', _), ('n_grid', 40), ('title', None)],
    }),
]

ROWS = [(module, name, params) for module, names in PEER for name, params in names.items()]

#: The peer's properties and its static and class methods.
PROPERTIES = {
    ("systems.newtonian", "FoucaultPendulum"): ["position", "velocity"],
    ("systems.rotations", "EulersDisk"): ["theta", "phi"],
}
STATIC = [("systems.newtonian", "FoucaultPendulum", "analytic_solution"),
          ("systems.newtonian", "FoucaultPendulum", "to_corotating_frame")]
CLASSMETHODS = [("systems.newtonian", "FoucaultPendulum", "from_deflection")]

#: A constructor call per class and the peer's attributes of the instance (its constructor
#: arguments and what it derives from them; the peer's LagrangianEngine ``engine`` and
#: ``ndof`` are not parameters and are left out).
ATTRIBUTES = [
    ("systems.newtonian", "ProjectileMotion", ([0, 0], [1, 1]),
     ["drag_coeff", "g", "m", "mass_inv"]),
    ("systems.newtonian", "KeplerSystem", ([1, 0], [0, 1]),
     ["c_eps", "c_pn", "eps", "k", "mass_inv", "mu", "softening"]),
    ("systems.newtonian", "FoucaultPendulum", ([1, 0], [0, 0]),
     ["g", "latitude_deg", "length", "omega0", "omega_earth", "omega_z"]),
    ("systems.lagrangian", "DoublePendulum", ([0.1, 0.2], [0, 0]), ["g", "l1", "l2", "m1", "m2"]),
    ("systems.lagrangian", "BeadOnRotatingHoop", (0.1, 0.0), ["R", "g", "omega"]),
    ("systems.lagrangian", "CoupledOscillators", ([0.1, 0, 0], [0, 0, 0]), ["k", "m", "n_masses"]),
    ("systems.lagrangian", "ElasticPendulum", ([1.1, 0.2], [0, 0]), ["L0", "g", "k", "m"]),
    ("systems.hamiltonian", "PendulumSwarm", ([0.1, 0.2], [0.0, 0.0]), ["g_over_l", "mass_inv"]),
    ("systems.chains", "FPUTChain", (4,), ["beta", "k", "m", "mass_inv"]),
    ("systems.chains", "SineGordonChain", (4,), ["k", "m", "mass_inv"]),
    ("systems.chains", "HarmonicChain", (np.zeros(4), np.zeros(4)), ["k", "m", "mass_inv"]),
    ("systems.rotations", "EulerTop", ([0.1, 1, 0.1],), ["I1", "I2", "I3"]),
    ("systems.rotations", "HeavySymmetricTop", ([0, 0.5, 0], [0, 0, 10]),
     ["I1", "I3", "M", "g", "l"]),
    ("systems.rotations", "EulersDisk", (0.5,), ["decay_rate", "precession_const", "theta_floor"]),
    ("systems.rotations", "Rattleback", ([0, 0, 1],), ["I1", "I2", "I3", "eta", "gamma", "mu"]),
]


def resolve(module: str, name: str):
    """``(owner, raw, attribute)``: the object a dotted name reaches from the module, the raw
    class-dictionary entry (a property, staticmethod or classmethod) and its value."""
    mod = importlib.import_module(f"physicskit.classical.{module}")
    owner, raw, obj = None, None, mod
    for part in name.split("."):
        owner = obj
        raw = inspect.getattr_static(obj, part)
        obj = getattr(obj, part)
    return owner, raw, obj


def needs_matplotlib(module: str) -> bool:
    return module.startswith("visualizers.") and module != "visualizers.interactive"


@pytest.mark.parametrize("module, name, params", ROWS, ids=[f"{m}.{n}" for m, n, _p in ROWS])
def test_path_and_signature_are_the_peers(module, name, params):
    if needs_matplotlib(module):
        pytest.importorskip("matplotlib")
    _owner, _raw, obj = resolve(module, name)
    sig = inspect.signature(obj)
    got = []
    for p in sig.parameters.values():
        if p.name in ("self", "cls"):
            continue
        key = "**" + p.name if p.kind is p.VAR_KEYWORD else p.name
        assert p.kind in (p.POSITIONAL_OR_KEYWORD, p.VAR_KEYWORD), (name, p)
        got.append((key, p.default))
    assert [n for n, _d in got] == [n for n, _d in params], name
    for (n, want), (_n, have) in zip(params, got):
        # Equal value and type: a default of 32 is not 32.0, and 1e-3 must be exactly it.
        assert type(have) is type(want) and have == want, (name, n, have, want)


@pytest.mark.parametrize("where, names", PROPERTIES.items(), ids=lambda x: str(x))
def test_properties(where, names):
    cls = resolve(*where)[2]
    for n in names:
        assert isinstance(inspect.getattr_static(cls, n), property), n


@pytest.mark.parametrize("module, cls, name", STATIC + CLASSMETHODS)
def test_static_and_class_methods(module, cls, name):
    _owner, raw, _obj = resolve(module, f"{cls}.{name}")
    kind = classmethod if (module, cls, name) in CLASSMETHODS else staticmethod
    assert isinstance(raw, kind), (cls, name, raw)


@pytest.mark.parametrize("module, cls, args, attrs", ATTRIBUTES, ids=[a[1] for a in ATTRIBUTES])
def test_constructor_arguments_are_read_only_attributes(module, cls, args, attrs):
    system = resolve(module, cls)[2](*args)
    for a in attrs:
        value = getattr(system, a)
        with pytest.raises(AttributeError, match="read-only"):
            setattr(system, a, value)
        with pytest.raises(AttributeError, match="read-only"):
            delattr(system, a)
        assert getattr(system, a) == value
    # The state and the clock stay plain attributes (the spec edits them between runs).
    system.t = 0.0
    system.state = system.state.copy()


def test_given_arguments_are_the_attributes():
    from physicskit.classical.systems.lagrangian import ElasticPendulum
    from physicskit.classical.systems.newtonian import FoucaultPendulum, ProjectileMotion

    bob = ElasticPendulum([1.2, 0.1], [0.0, 0.0], L0=1.2, k=30.0)
    assert (bob.L0, bob.k, bob.m, bob.g) == (1.2, 30.0, 1.0, 9.81)
    ball = ProjectileMotion([0, 0], [1, 1], m=2.0, g=1.62)
    assert (ball.m, ball.g, ball.mass_inv) == (2.0, 1.62, 0.5)
    f = FoucaultPendulum([1, 0], [0, 0], length=10.0, g=9.8, latitude_deg=30.0)
    assert f.omega0 == np.sqrt(9.8 / 10.0)
    # sin(30 deg) rounds to 0.49999999999999994: the check allows its ulp.
    assert f.omega_z == pytest.approx(0.5 * f.omega_earth, rel=4e-16)


def test_elastic_pendulum_coordinates_are_the_peers():
    # The peer documents q = (s, theta) with s the spring's stretch beyond L0 (the bob
    # L0 + s from the pivot) and L = m (sdot^2 + (L0 + s)^2 thetadot^2)/2 - k s^2/2
    # + m g (L0 + s) cos(theta): the same q0 must mean the same start here.
    from physicskit.classical.systems.lagrangian import ElasticPendulum

    m, k, L0, g = 1.0, 39.24, 1.2, 9.81
    s, th, sd, thd = 0.05, 0.3, 0.1, -0.2
    bob = ElasticPendulum([s, th], [sd, thd], L0=L0)
    r = L0 + s
    # One rounding in L0 + s and in each product: 1e-15 relative.
    np.testing.assert_allclose(bob.positions(), [r * np.sin(th), -r * np.cos(th)], rtol=1e-15)
    want = 0.5 * m * (sd**2 + r**2 * thd**2) + 0.5 * k * s**2 - m * g * r * np.cos(th)
    # E = T + V: a dozen roundings on terms of size ~10 against E ~ -10: 1e-14 relative.
    assert bob.energy() == pytest.approx(want, rel=1e-14)


def test_python_subclasses_keep_plain_attributes():
    # Only the built-in systems' parameters are read-only; a user's own system is not.
    from physicskit.classical import ODESystem

    class Decay(ODESystem):
        def derivatives(self, t, y):
            return -self.rate * y

        def energy(self, state=None):
            return 0.0

    d = Decay([1.0])
    d.rate = 1.0
    d.rate = 2.0
    assert d.rate == 2.0


def test_visualizers_import_without_matplotlib_or_plotly():
    # The package resolves its names on first use: importing it loads neither library.
    import subprocess
    import sys

    code = (
        "import sys, physicskit.classical.visualizers as v, "
        "physicskit.classical.visualizers.interactive; "
        "assert 'matplotlib' not in sys.modules and 'plotly' not in sys.modules, "
        "sorted(m for m in sys.modules if m.startswith(('matplotlib', 'plotly'))); "
        "assert set(v.__all__) >= {'SideBySideAnimator', 'interactive_orbit'}"
    )
    subprocess.run([sys.executable, "-c", code], check=True)
