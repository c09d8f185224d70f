"""The public API matches the spec: names, signatures (parameter names and defaults), base
classes, methods, static/class methods, properties and class attributes (spec_table.py)."""

import dataclasses
import inspect

import numpy as np
import pytest

import physicskit.classical as pc
from physicskit.classical.systems import chains

from spec_table import _, CHAIN_BASE_METHODS, CLASSES, FUNCTIONS, SIMULATION_RESULT


def params_of(fn, drop_self=True):
    """[(name, default)] of a callable, `_` for no default, `**name` for var-keyword."""
    out = []
    for p in inspect.signature(fn).parameters.values():
        if p.kind is p.VAR_KEYWORD:
            out.append(("**" + p.name, _))
        else:
            out.append((p.name, _ if p.default is p.empty else p.default))
    if drop_self and out and out[0][0] in ("self", "cls"):
        out = out[1:]
    return out


def test_all_names_exported():
    expected = set(CLASSES) | set(FUNCTIONS) | {"SimulationResult"}
    assert expected <= set(pc.__all__)
    for name in expected:
        assert getattr(pc, name) is not None


@pytest.mark.parametrize("name", sorted(CLASSES))
def test_class_signature_and_base(name):
    spec = CLASSES[name]
    cls = getattr(pc, name)
    assert params_of(cls.__init__) == spec["sig"], name
    assert cls.__bases__[0].__name__ == spec["base"], name
    assert cls.__doc__ and cls.__doc__.strip(), f"{name} has no docstring"


@pytest.mark.parametrize("name", sorted(CLASSES))
def test_methods_properties_attributes(name):
    spec = CLASSES[name]
    cls = getattr(pc, name)
    for meth, sig in spec.get("methods", {}).items():
        fn = getattr(cls, meth)
        assert callable(fn), (name, meth)
        assert params_of(fn) == sig, (name, meth)
        assert fn.__doc__, (name, meth)
    for meth, sig in spec.get("static", {}).items():
        assert isinstance(inspect.getattr_static(cls, meth), staticmethod), (name, meth)
        assert params_of(getattr(cls, meth), drop_self=False) == sig, (name, meth)
    for meth, sig in spec.get("classmethods", {}).items():
        assert isinstance(inspect.getattr_static(cls, meth), classmethod), (name, meth)
        assert params_of(getattr(cls, meth)) == sig, (name, meth)
    for prop in spec.get("properties", set()):
        assert isinstance(inspect.getattr_static(cls, prop), property), (name, prop)
        assert inspect.getattr_static(cls, prop).__doc__, (name, prop)
    for attr, value in spec.get("attrs", {}).items():
        assert getattr(cls, attr) == value, (name, attr)
    abstract = spec.get("abstract")
    if abstract is not None:
        assert set(cls.__abstractmethods__) == abstract, name


def test_chain_base():
    base = chains._ChainBase
    assert base.__bases__[0] is pc.HamiltonianSystem
    assert params_of(base.__init__) == [("q0", _), ("p0", _), ("m", 1.0), ("k", 1.0)]
    for meth, sig in CHAIN_BASE_METHODS.items():
        assert params_of(getattr(base, meth)) == sig, meth
    assert base.separable is True
    # The spec's three chains (the module also offers the Toda lattice, beyond the spec).
    assert {"HarmonicChain", "FPUTChain", "SineGordonChain"} <= set(chains.__all__)


@pytest.mark.parametrize("name", sorted(FUNCTIONS))
def test_function_signature(name):
    fn = getattr(pc, name)
    assert params_of(fn, drop_self=False) == FUNCTIONS[name]
    assert fn.__doc__


def test_simulation_result_dataclass():
    assert dataclasses.is_dataclass(pc.SimulationResult)
    fields = dataclasses.fields(pc.SimulationResult)
    got = []
    for f in fields:
        if f.default_factory is not dataclasses.MISSING:
            got.append((f.name, "<factory>"))
            assert f.default_factory() == {}
        else:
            got.append((f.name, _ if f.default is dataclasses.MISSING else f.default))
    assert got == SIMULATION_RESULT
    assert pc.SimulationResult.__bases__ == (object,)


def test_module_paths_import():
    import physicskit.classical.systems.chains as ch
    import physicskit.classical.utils.symbolic as sym

    assert ch.FPUTChain is pc.FPUTChain
    assert params_of(sym.LagrangianEngine.__init__) == [
        ("q", _), ("qdot", _), ("L", _), ("t", None), ("params", None)]


def test_state_properties_behave(system_name):
    from conftest import make_systems

    s = make_systems()[system_name]()
    assert s.state.dtype == np.float64 and s.t == 0.0
    if isinstance(s, pc.HamiltonianSystem):
        assert np.array_equal(np.concatenate([s.q, s.p]), s.state)
        q, p = s.split(s.state, s.ndof)
        assert np.array_equal(q, s.q) and np.array_equal(p, s.p)
    elif isinstance(s, pc.LagrangianSystem):
        assert np.array_equal(np.concatenate([s.q, s.qdot]), s.state)
    elif isinstance(s, pc.EulerTop):
        assert np.array_equal(np.concatenate([s.omega, s.quaternion]), s.state)
    # integrate continues from the state; reset restores it.
    start = s.state.copy()
    dt = 1e-3
    r = s.integrate((0.0, 10 * dt), dt)
    assert s.t == pytest.approx(10 * dt) and np.array_equal(s.state, r.y[-1])
    s.reset(start)
    assert np.array_equal(s.state, start) and s.t == 0.0
    # Editing the state in place is honoured by the next integrate, as in the spec.
    s.state[0] += 1e-3
    edited = s.state.copy()
    r2 = s.integrate((0.0, dt), dt)
    assert np.array_equal(r2.y[0], edited) and not np.array_equal(edited, start)


def test_every_public_name_has_a_docstring():
    import physicskit.classical.utils.symbolic as sym

    for name in pc.__all__:
        if name.startswith("__"):
            continue
        obj = getattr(pc, name)
        assert obj.__doc__ and obj.__doc__.strip(), name
    assert sym.LagrangianEngine.__doc__
