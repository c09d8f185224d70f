"""The Python classes are driven by the native catalogue: every constructor's signature agrees
with its catalogue entry (names, order, defaults), the spec table agrees with both, arguments
are converted by the rules of ``python/src/params.rs``, and ``methods()`` describes the
integrators ``integrate`` accepts."""

from fractions import Fraction

import numpy as np
import pytest

import physicskit.classical as pc
from physicskit import _core

from spec_table import _, CLASSES
from test_api import params_of

ENTRIES = [e for e in _core.catalog() if e["python"] is not None]


def resolve(path: str):
    """The callable a catalogue ``python`` path names: a class's ``__init__`` or a
    classmethod."""
    cls_name, _dot, method = path.partition(".")
    cls = getattr(pc, cls_name)
    return getattr(cls, method) if method else cls.__init__


def spec_signature(path: str):
    """The spec table's signature of a catalogue ``python`` path."""
    cls_name, _dot, method = path.partition(".")
    spec = CLASSES[cls_name]
    return spec["classmethods"][method] if method else spec["sig"]


def same_default(expected, got) -> bool:
    """Equal value and type (``32`` is not ``32.0`` in a signature)."""
    return type(expected) is type(got) and expected == got


def check_against_catalogue(sig, entry):
    """``sig`` ([(name, default)], ``_`` for none, ``("**kwargs", _)`` last) agrees with the
    entry's parameters: same names in the same order; a spec default value equals the
    catalogue's; ``absent`` is a default of None; demonstration, absent-in-demos and required
    parameters have no default; ``**kwargs`` stands for the remaining parameters, which must
    all have spec defaults (so leaving them out is the spec's default)."""
    params = entry["params"]
    named = [(n, d) for n, d in sig if not n.startswith("**")]
    var_kw = len(named) < len(sig)
    assert len(named) <= len(params), entry["name"]
    for (name, default), p in zip(named, params):
        assert name == p["name"], (entry["name"], name, p["name"])
        kind = p["default_kind"]
        if kind == "value":
            assert same_default(p["default"], default), (entry["name"], name, default, p)
        elif kind == "absent":
            assert default is None, (entry["name"], name, default)
        else:
            assert kind in ("demo", "demo_absent", "required"), kind
            assert default is _, (entry["name"], name, default)
        assert p["spec_default"] == (default is not _), (entry["name"], name)
    rest = params[len(named):]
    if var_kw:
        assert rest, entry["name"]
        assert all(p["default_kind"] == "value" for p in rest), entry["name"]
    else:
        assert not rest, (entry["name"], [p["name"] for p in rest])
    return [p["name"] for p in rest]


@pytest.mark.parametrize("entry", ENTRIES, ids=lambda e: e["python"])
def test_python_signature_matches_catalogue(entry):
    check_against_catalogue(params_of(resolve(entry["python"])), entry)


#: The entries of the spec's classes; the catalogue's other classes (the Toda lattice, the
#: elastic pendulum, the peer's systems, the rolling bodies) have no row in the spec table,
#: and everything else about them is checked like the spec's.
SPEC_ENTRIES = [e for e in ENTRIES if e["python"].split(".")[0] in CLASSES]


@pytest.mark.parametrize("entry", SPEC_ENTRIES, ids=lambda e: e["python"])
def test_spec_table_matches_catalogue(entry):
    check_against_catalogue(spec_signature(entry["python"]), entry)


def test_kepler_kwargs_are_the_perturbations():
    # from_orbital_elements(a, e, k=1.0, mu=1.0, **kwargs): the kwargs are exactly the
    # perturbation parameters, which KeplerSystem's own signature lists with the same defaults.
    entry = next(e for e in ENTRIES if e["python"] == "KeplerSystem.from_orbital_elements")
    rest = check_against_catalogue(params_of(resolve(entry["python"])), entry)
    assert rest == ["eps", "c_eps", "c_pn", "softening"]
    init = dict(params_of(pc.KeplerSystem.__init__))
    for p in entry["params"][4:]:
        assert same_default(p["default"], init[p["name"]]), p["name"]


def test_every_spec_constructor_has_a_catalogue_entry():
    # Each concrete spec class and each of its alternate constructors is built by exactly one
    # entry (the classes are those exported by `systems`, the constructors the spec's).
    constructors = set()
    for name, spec in CLASSES.items():
        if name in pc.systems.__all__:
            constructors.add(name)
            constructors.update(f"{name}.{m}" for m in spec.get("classmethods", {}))
    paths = [e["python"] for e in SPEC_ENTRIES]
    assert sorted(paths) == sorted(constructors)
    beyond = {e["python"].split(".")[0] for e in ENTRIES} - {p.split(".")[0] for p in paths}
    # Every class beyond the spec is exported like the spec's.
    assert beyond <= set(pc.systems.__all__), sorted(beyond - set(pc.systems.__all__))


def test_catalogue_listing_shape():
    for e in _core.catalog():
        assert e["family"] in ("hamiltonian", "lagrangian", "ode")
        assert e["default_method"] in e["methods"]
        for p in e["params"]:
            assert p["kind"] in ("scalar", "integer", "vector", "choice")
            assert (p["length"] is not None) == (p["kind"] == "vector"), p
            assert (p["choices"] is not None) == (p["kind"] == "choice"), p
            assert p["help"] and p["expectation"]


def test_physics_is_one_whole_paragraph_per_class():
    # `physics` is the system's physics paragraph (its catalogue entry's, which its gallery
    # demonstration opens with), which the lab shows as its caption: passed through whole (a
    # paragraph of sentences, the last ending with a full stop, no stray whitespace from the Rust
    # string's line continuations) and found by system, so the entries that build one Python
    # class two ways (KeplerSystem and KeplerSystem.from_orbital_elements, ...) carry the same
    # text. Every system with a Python class has one.
    texts_of: dict[str, set[str]] = {}
    for e in _core.catalog():
        text = e["physics"]
        if e["python"] is None and text is None:
            continue
        assert isinstance(text, str), e["name"]
        # The last sentence may stand in parentheses: "... (... excited.)".
        assert text.rstrip(")").endswith(".") and ". " in text, (e["name"], text[-40:])
        assert text == text.strip() and "  " not in text and "\n" not in text, e["name"]
        if e["python"] is not None:
            texts_of.setdefault(e["python"].split(".")[0], set()).add(text)
    assert texts_of and all(len(texts) == 1 for texts in texts_of.values()), \
        {cls: len(texts) for cls, texts in texts_of.items()}


# -- the checked values become the attributes ------------------------------------------------


def test_attributes_are_the_checked_values():
    dp = pc.DoublePendulum([0.1, 0.2], [0.0, 0.0], m1=2, l2=np.float32(0.5))
    assert (dp.m1, dp.m2, dp.l2, dp.g) == (2.0, 1.0, 0.5, 9.81)
    assert all(type(x) is float for x in (dp.m1, dp.l2))
    fput = pc.FPUTChain(n=np.int64(8), mode=np.uint8(2))
    assert (fput.ndof, fput.mode) == (8, 2) and type(fput.mode) is int
    assert pc.CoupledOscillators([0.1, 0.0], [0.0, 0.0], n=2).n_masses == 2
    k = pc.KeplerSystem.from_orbital_elements(1.0, 0.5, mu=2.0, c_pn=0.01)
    assert type(k) is pc.KeplerSystem and (k.mu, k.c_pn, k.eps) == (2.0, 0.01, 0.0)
    assert k.mass_inv == 0.5
    assert k._native.params["a"] == 1.0 and k._native.name == "kepler"


# -- conversion rules (python/src/params.rs) -------------------------------------------------

Q, P = [0.1, 0.2], [0.0, 0.0]


@pytest.mark.parametrize("bad, name, match", [
    # complex numbers, scalars and arrays, even with a zero imaginary part
    (lambda: pc.DoublePendulum(Q, P, m1=1 + 0j), "m1", "complex"),
    (lambda: pc.DoublePendulum(Q, P, m1=np.complex128(1.0)), "m1", "complex"),
    (lambda: pc.DoublePendulum(Q, P, m1=np.array([1 + 0j])), "m1", "complex"),
    (lambda: pc.KeplerSystem(np.array([1.0, 0.0], dtype=complex), [0.0, 1.0]), "q0", "complex"),
    (lambda: pc.KeplerSystem(np.array([1.0, 1j], dtype=object), [0.0, 1.0]), "q0", "complex"),
    (lambda: pc.KeplerSystem([1.0, 1j], [0.0, 1.0]), "q0", "complex"),
    # ints too large for a float: ValueError naming the parameter, not OverflowError
    (lambda: pc.DoublePendulum(Q, P, m1=10**400), "m1", "too large"),
    (lambda: pc.DoublePendulum([10**400, 0.0], P), "theta0", "too large"),
    (lambda: pc.FPUTChain(n=10**30), "n", "64-bit"),
    # floats where an integer belongs, even integral ones
    (lambda: pc.FPUTChain(n=5.4e16), "n", "must be an integer"),
    (lambda: pc.FPUTChain(n=8.0), "n", "must be an integer"),
    (lambda: pc.FPUTChain(mode=1.5), "mode", "must be an integer"),
    (lambda: pc.PendulumSwarm.from_box(1.0, 0.0, 0.1, 0.1, seed=np.float64(3.0)), "seed",
     "must be an integer"),
    # more than one dimension, or more than one number for a scalar
    (lambda: pc.HenonHeilesSystem([[0.1, 0.0]], [0.0, 0.3]), "q0", "one-dimensional"),
    (lambda: pc.HarmonicChain(np.zeros((2, 2)), np.zeros(4)), "q0", "one-dimensional"),
    (lambda: pc.BeadOnRotatingHoop([0.3, 0.1], 0.0), "theta0", "one real number"),
    (lambda: pc.BeadOnRotatingHoop([[0.3]], 0.0), "theta0", "one-dimensional"),
    # bools, strings, ragged input
    (lambda: pc.DoublePendulum(Q, P, m1=True), "m1", "bool"),
    (lambda: pc.FPUTChain(n=True), "n", "bool"),
    (lambda: pc.DoublePendulum([True, False], P), "theta0", "bool"),
    (lambda: pc.DoublePendulum(Q, P, m1="1.0"), "m1", "string"),
    (lambda: pc.DoublePendulum("ab", P), "theta0", "string"),
    (lambda: pc.DoublePendulum([[0.1], [0.1, 0.2]], P), "theta0", "real numbers"),
    # None leaves a parameter out: allowed only where the spec has a default
    (lambda: pc.DoublePendulum(None, P), "theta0", "got None"),
    (lambda: pc.HarmonicChain([0.1, 0.2], None), "p0", "got None"),
    # an unknown keyword of from_orbital_elements is the catalogue's to refuse
    (lambda: pc.KeplerSystem.from_orbital_elements(1.0, 0.5, c_gr=1.0), "c_gr",
     "no such parameter"),
])
def test_conversion_refusals(bad, name, match):
    with pytest.raises(ValueError, match=match) as info:
        bad()
    assert f"`{name}`" in str(info.value)


def test_conversion_accepts():
    # A scalar is a real number, a 0-d array, or one number in a 1-D sequence.
    for theta0 in (0.3, np.float32(0.3), np.array(0.3), [0.3], np.array([0.3]), (0.3,),
                   np.float64(0.3)):
        hoop = pc.BeadOnRotatingHoop(theta0, 0)
        assert hoop.state[0] == float(np.asarray(theta0).reshape(-1)[0]), theta0
    assert pc.BeadOnRotatingHoop(Fraction(1, 4), 0).state[0] == 0.25
    assert pc.BeadOnRotatingHoop(np.int64(1), 0).state[0] == 1.0
    # A vector is any 1-D array-like of reals: ints, unsigned, float32, object arrays of reals,
    # and ints beyond 64 bits that a float holds.
    dp = pc.DoublePendulum(np.array([1, 2], dtype=np.uint8), np.array([0.5, 0.25], np.float32))
    assert np.array_equal(dp.state, [1.0, 2.0, 0.5, 0.25])
    dp = pc.DoublePendulum(np.array([Fraction(1, 2), 2**70], dtype=object), P)
    assert np.array_equal(dp.q, [0.5, 2.0**70])
    # A single number is a vector of length 1.
    assert pc.HarmonicChain(0.1, 0.0).ndof == 1
    # None for a parameter whose spec default is None uses that default (None elsewhere is
    # refused: test_conversion_refusals).
    assert pc.EulerTop([0.0, 1.0, 0.0], quat0=None).quaternion.tolist() == [1.0, 0.0, 0.0, 0.0]


def test_nan_is_the_catalogues_to_refuse():
    with pytest.raises(ValueError, match="invalid parameter `m1` = NaN: must be finite"):
        pc.DoublePendulum(Q, P, m1=float("nan"))
    with pytest.raises(ValueError, match="`theta0`: contains NaN"):
        pc.DoublePendulum([np.inf, 0.0], P)


def test_build_errors():
    with pytest.raises(ValueError, match="unknown system `nope`; known systems are: .*kepler"):
        _core.build("nope", {})
    with pytest.raises(TypeError, match="parameter names must be strings"):
        _core.build("kepler", {1: 2.0})
    with pytest.raises(ValueError, match="`a`: is required"):
        _core.build("kepler", {"e": 0.5})


# -- capabilities -----------------------------------------------------------------------------


def test_capabilities_are_listed_and_missing_ones_are_not_implemented():
    dp = pc.DoublePendulum(Q, P)
    assert "positions" in dp._native.capabilities
    assert "lrl_vector" not in dp._native.capabilities
    with pytest.raises(NotImplementedError, match="`lrl_vector` is not available.*double-pendulum"):
        dp._native.lrl_vector(np.zeros(2), np.zeros(2))
    kepler = pc.KeplerSystem.from_orbital_elements(1.0, 0.5)
    assert {"lrl_vector", "angular_momentum"} <= set(kepler._native.capabilities)
    chain = pc.FPUTChain(n=4)
    assert {"normal_mode_frequencies", "modal_energies"} <= set(chain._native.capabilities)


# -- methods() ---------------------------------------------------------------------------------

KEYS = {
    "name", "label", "order", "symplectic", "separable_only", "adaptive", "needs_taylor_form",
    "evaluations_per_step", "evaluations", "reference",
}



def test_methods_have_the_required_keys_and_describe_integrate():
    methods = pc.methods()
    assert methods and all(KEYS <= set(m) for m in methods)
    for m in methods:
        assert isinstance(m["order"], int) and m["order"] >= 1
        assert isinstance(m["symplectic"], bool) and isinstance(m["separable_only"], bool)
    # `separable_only` is what integrate does: a separable system runs every method, a
    # Lagrangian one refuses exactly the separable-only ones. `needs_taylor_form` too: a
    # catalogue Hamiltonian with only a hand-written force (the Toda lattice) refuses such a
    # method, naming itself; Kepler, whose H is traced, and a Lagrangian system, whose L is,
    # run it.
    kepler = pc.KeplerSystem.from_orbital_elements(1.0, 0.5)
    toda = pc.TodaLattice([0.1, 0.0, -0.1], [0.0, 0.2, 0.0])
    for m in methods:
        dp = pc.DoublePendulum(Q, P)
        if m["needs_taylor_form"]:
            with pytest.raises(ValueError, match="cannot integrate.*`toda.*HamiltonianEngine"):
                toda.integrate((0.0, 0.01), 0.01, m["name"])
            kepler.integrate((0.0, 0.01), 0.01, m["name"])
            dp.integrate((0.0, 0.01), 0.01, m["name"])
            continue
        kepler.integrate((0.0, 0.01), 0.01, m["name"])
        if m["separable_only"]:
            with pytest.raises(ValueError, match="cannot integrate"):
                dp.integrate((0.0, 0.01), 0.01, m["name"])
        else:
            dp.integrate((0.0, 0.01), 0.01, m["name"])
    # `adaptive` is what integrate_sampled does with tolerances: an adaptive method takes
    # them, a fixed-step one refuses them.
    assert any(m["adaptive"] for m in methods)
    for m in methods:
        if m["needs_taylor_form"]:
            continue  # refused by the catalogue's systems, above
        if m["adaptive"]:
            kepler.integrate_sampled((0.0, 0.01), 0.01, m["name"], rtol=1e-8)
        else:
            with pytest.raises(ValueError, match="fixed-step"):
                kepler.integrate_sampled((0.0, 0.01), 0.01, m["name"], rtol=1e-8)
    # The catalogue's per-system method lists are drawn from the same names.
    names = {m["name"] for m in methods}
    for e in _core.catalog():
        assert set(e["methods"]) <= names


def test_methods_and_catalogue_agree_with_the_command_line(cargo_profile):
    """``physicskit list --json`` (the CLI) and ``methods()`` / ``catalog()`` (Python) are two
    renderings of the same core tables: every method fact and every system's parameters and
    defaults must be equal."""
    import json
    import os
    import pathlib
    import shutil
    import subprocess

    if shutil.which("cargo") is None:
        pytest.skip("cargo is not installed")
    repo = pathlib.Path(__file__).resolve().parents[2]
    out = subprocess.run(
        ["cargo", "run", "--quiet", *cargo_profile, "-p", "physicskit-cli", "--", "list", "--json"],
        cwd=repo, check=True, capture_output=True,
        env={**os.environ, "CARGO_BUILD_JOBS": os.environ.get("CARGO_BUILD_JOBS", "2")},
    ).stdout
    cli = json.loads(out)
    py_methods = pc.methods()
    assert [m["name"] for m in cli["methods"]] == [m["name"] for m in py_methods]
    for row, m in zip(cli["methods"], py_methods):
        for key in KEYS:
            assert row[key] == m[key], (m["name"], key)
    py_systems = {e["name"]: e for e in pc.catalog()}
    assert [s["name"] for s in cli["systems"]] == list(py_systems)
    for system in cli["systems"]:
        ours = py_systems[system["name"]]
        assert system["methods"] == ours["methods"], system["name"]
        assert system["default_method"] == ours["default_method"], system["name"]
        assert [p["name"] for p in system["params"]] == [p["name"] for p in ours["params"]]
        # The physics paragraph and the presentation: the catalogue entry's, through both.
        assert system["physics"] == ours["physics"], system["name"]
        assert system["presentation"] == ours["presentation"], system["name"]
        for p, q in zip(system["params"], ours["params"]):
            assert (p["unit"], p["default"], p["initial_state"]) == (
                q["unit"], q["default"], q["initial_state"]), (system["name"], p["name"])
    # The gallery shows (and so explains) most systems; the harmonic oscillator it does not.
    assert py_systems["double-pendulum"]["physics"].startswith("Two rigid rods")
    assert py_systems["harmonic-oscillator"]["physics"] is None
