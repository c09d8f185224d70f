"""Type stubs of the native module ``physicskit._core`` (PyO3); checked against the compiled
module by mypy's stubtest (``bash python/dev.sh stubs``: names, parameters, defaults) and by
``tests/test_stubs.py`` (parameter and return types)."""

from typing import Any, Callable, Literal, TypedDict, final

import numpy as np
import numpy.typing as npt

__all__ = [
    "CHAOS_THRESHOLD",
    "DEFAULT_RENORMALIZE_EVERY",
    "MAX_THREADS",
    "ConvergenceError",
    "NativeSystem",
    "build",
    "catalog",
    "chaos_hamiltonian",
    "chaos_map",
    "chaos_native",
    "chaos_ode",
    "effective_potential_symmetric_top",
    "expr_hamiltonian",
    "ensemble",
    "expr_lagrangian",
    "expr_ode",
    "eulers_disk_theta_analytic",
    "expr_validate",
    "find_theta_equilibrium",
    "force_jacobian",
    "foucault_analytic_solution",
    "integrate_hamiltonian",
    "integrate_ode",
    "methods",
    "nutation_frequency",
    "pendulum_action_angle",
    "precession_frequency",
    "projectile_analytic_trajectory",
    "projectile_range_and_max_height",
    "sine_gordon_kink",
    "spin_reversal_time",
    "system_jacobian",
]

_ArrayF64 = npt.NDArray[np.float64]
_MatrixF64 = npt.NDArray[np.float64]
"""A two-dimensional float64 array (rows of states)."""

CHAOS_THRESHOLD: float
"""SALI or GALI below this value classifies an orbit as chaotic (the core's
`analysis::sali::CHAOS_THRESHOLD`)."""
DEFAULT_RENORMALIZE_EVERY: int
"""Steps between renormalizations when none is named (the core's
`analysis::lyapunov::DEFAULT_RENORMALIZE_EVERY`)."""
MAX_THREADS: int
"""The most worker threads an ensemble may ask for (the core's `ensemble::MAX_THREADS`)."""

_ResultTuple = tuple[_ArrayF64, _ArrayF64, int | None, _ArrayF64 | None, str, dict[str, Any]]
_ParamValue = float | int | _ArrayF64 | str | None
"""A checked parameter value: float (scalar), int (integer), float64 array (vector), str
(choice), or None (left out)."""

class _RangeInfo(TypedDict):
    min: tuple[float, bool] | None
    """Lower limit and whether it is included; None: unbounded."""
    max: tuple[float, bool] | None
    """Upper limit and whether it is included; None: unbounded."""
    text: str
    """The range in words, e.g. ``"> 0"``."""

class _ParamInfo(TypedDict):
    name: str
    kind: Literal["scalar", "integer", "vector", "choice"]
    default: float | int | list[float] | str | None
    """The spec's default (``default_kind == "value"``), the demonstration value
    (``"demo"``), else None."""
    default_kind: Literal["required", "value", "absent", "demo", "demo_absent"]
    spec_default: bool
    """True if the spec's signature has a default (a value, or None for ``"absent"``)."""
    unit: str
    range: _RangeInfo
    length: int | str | None
    """Vectors: a fixed length, ``"any"``, ``"same as <param>"`` or ``"count <param>"``."""
    choices: list[str] | None
    expectation: str
    help: str
    initial_state: bool
    """Part of the initial state (``q0``, ``theta0``), not a constant of the system."""

class _DrawingInfo(TypedDict, total=False):
    kind: Literal[
        "bobs", "hoop", "swarm", "chain", "field", "orbit", "inertia_box", "top_axis", "swing",
        "contact_spiral", "spin", "rolling", "plots",
    ]
    springs: bool
    """Bobs: hung on springs (coils), not rods."""
    scale: str
    """Bobs: the system's own length its positions are in units of (TeX, ``l``), if any."""
    ends: Literal["fixed", "free", "periodic"]
    """Chains: walls at both ends, free ends, or a ring."""
    central_body: bool
    """Orbits: a central body at the origin."""
    ground: bool
    """Orbits: level ground at y = 0 (a projectile's flight)."""
    shape: Literal["ellipsoid", "disk"]
    """Rolling bodies: the body's shape."""

class _PaceInfo(TypedDict, total=False):
    kind: Literal["own", "fixed", "time_lapse"]
    method: str
    """Fixed: the fixed-step method."""
    dt: float
    """Fixed or time-lapse: the step."""
    steps_per_frame: float
    """Fixed or time-lapse: steps a frame."""
    energy_error: float
    """Fixed: the bound on the relative energy error over a minute of frames (tested)."""

class _PresentationInfo(TypedDict):
    title: str
    """The system's name as a title for people (``"Hénon–Heiles"``)."""
    symbols: list[str]
    """TeX symbols of the coordinates: one each, or one for all (a chain's), or none."""
    time_unit: str
    """``"s"``, ``"time"`` (the user's own units) or ``""`` (dimensionless)."""
    state_units: list[str] | None
    """Units of a coordinate and a momentum or velocity, where no parameter gives them."""
    drawing: _DrawingInfo
    pace: _PaceInfo
    """How a frame-by-frame animation steps it (the browser lab's 60 frames a second)."""
    section_first: bool
    """The Poincaré section is the picture that matters: shown from the start."""
    energy_conserved: bool
    """Its equations conserve ``energy`` (False for the dissipative reduced models)."""

class _SystemInfo(TypedDict):
    name: str
    python: str | None
    summary: str
    family: Literal["hamiltonian", "lagrangian", "ode"]
    separable: bool
    methods: list[str]
    default_method: str
    note: str | None
    physics: str | None
    presentation: _PresentationInfo
    params: list[_ParamInfo]

class _MethodInfo(TypedDict):
    name: str
    label: str
    """The name in words, for titles and legends (``"implicit midpoint"``)."""
    order: int
    symplectic: bool
    separable_only: bool
    adaptive: bool
    needs_taylor_form: bool
    """Runs only on systems defined by expressions (the SymPy engines), which have a Taylor form."""
    evaluations_per_step: int
    evaluations: str
    reference: str
    summary: str

class ConvergenceError(RuntimeError):
    """The implicit solver of a step did not converge; reduce dt."""

@final
class NativeSystem:
    """A built-in Rust system, owned by the Python object that wraps it."""

    @property
    def name(self) -> str: ...
    @property
    def family(self) -> Literal["hamiltonian", "lagrangian", "ode"]: ...
    @property
    def params(self) -> dict[str, _ParamValue] | None: ...
    @property
    def capabilities(self) -> list[str]: ...
    @property
    def state(self) -> _ArrayF64: ...
    @property
    def t(self) -> float: ...
    @property
    def ndof(self) -> int | None: ...
    @property
    def separable(self) -> bool: ...
    @property
    def mass_inv(self) -> _ArrayF64 | None: ...
    @property
    def default_method(self) -> str: ...
    def reset(self, state: _ArrayF64, t0: float) -> None: ...
    def energy(self, state: _ArrayF64) -> float: ...
    def derivatives(self, t: float, state: _ArrayF64) -> _ArrayF64: ...
    def kinetic_energy(self, p: _ArrayF64) -> float: ...
    def potential_energy(self, q: _ArrayF64) -> float: ...
    def force(self, q: _ArrayF64, t: float) -> _ArrayF64: ...
    def acceleration(self, q: _ArrayF64, qdot: _ArrayF64, t: float) -> _ArrayF64: ...
    def momentum(self, q: _ArrayF64, qdot: _ArrayF64, t: float) -> _ArrayF64: ...
    def velocity(self, q: _ArrayF64, p: _ArrayF64, t: float) -> _ArrayF64: ...
    def canonical_derivatives(self, t: float, state: _ArrayF64) -> _ArrayF64: ...
    def integrate(
        self,
        state: _ArrayF64,
        t0: float,
        t_span: tuple[float, float],
        dt: float,
        method: str | None = None,
        stride: int = 1,
        final_only: bool = False,
        energy: bool = True,
        progress: Callable[[int, int], object] | None = None,
        rtol: float | None = None,
        atol: float | None = None,
        max_steps: int | None = None,
    ) -> _ResultTuple:
        """Integrate from `(state, t0)`; keep every `stride`-th step (and the last), or only the
        first and last with `final_only`; `energy=False` gives `None` energy; `progress(step,
        n_steps)` is called every few thousand steps; `rtol`, `atol`, `max_steps`: an adaptive
        method's tolerances and step budget (ValueError for a fixed-step method). ValueError when the stored samples
        would not fit in memory."""
    def positions(self, q: _ArrayF64) -> _ArrayF64: ...
    def lrl_vector(self, q: _ArrayF64, p: _ArrayF64) -> _ArrayF64: ...
    def angular_momentum(self, q: _ArrayF64, p: _ArrayF64) -> float: ...
    def per_particle_energy(self, q: _ArrayF64, p: _ArrayF64) -> _ArrayF64: ...
    def phase_space_area(self, q: _ArrayF64, p: _ArrayF64) -> float: ...
    def normal_mode_frequencies(self) -> _ArrayF64: ...
    def normal_mode_coordinates(self, q: _ArrayF64, p: _ArrayF64) -> tuple[_ArrayF64, _ArrayF64]: ...
    def modal_energies(self, q: _ArrayF64, p: _ArrayF64) -> _ArrayF64: ...
    def rotation_matrix(self, state: _ArrayF64) -> _ArrayF64: ...
    def angular_momentum_squared(self, state: _ArrayF64) -> float: ...
    def symmetry_axis(self, q: _ArrayF64) -> _ArrayF64: ...
    def body_angular_momentum(self, state: _ArrayF64) -> _ArrayF64: ...
    def inertia_box(self, mass: float) -> _ArrayF64: ...
    def separatrix_energies(self) -> _ArrayF64: ...
    def precession_nutation_rate(self, state: _ArrayF64) -> tuple[float, float]: ...
    def conserved_quantities(self, state: _ArrayF64) -> _ArrayF64: ...

def build(name: str, params: dict[str, Any]) -> NativeSystem:
    """Builds the catalogue system `name` from `params`; a value of None leaves a parameter out.
    ValueError for an unknown system or parameter, a value of the wrong kind, a missing value,
    a number out of range or a vector of the wrong length."""

def catalog() -> list[_SystemInfo]:
    """Every system of the catalogue, in listing order, with its typed parameters."""

def methods() -> list[_MethodInfo]:
    """Every integrator with its order, symplecticity and whether it needs a separable H."""

def effective_potential_symmetric_top(theta: _ArrayF64, p_phi: float, p_psi: float, I1: float, I3: float, Mgl: float) -> _ArrayF64:
    """`V_eff(theta)` of the heavy symmetric top at each angle."""

def expr_hamiltonian(sexpr: str, ndof: int, params: _ArrayF64, q0: _ArrayF64, p0: _ArrayF64) -> NativeSystem:
    """A Hamiltonian system from a prefix S-expression of `H(q, p, t)` with `ndof` degrees of"""

def expr_ode(components: list[str], params: _ArrayF64, y0: _ArrayF64, energy: str | None = None) -> NativeSystem:
    """A first-order system from prefix S-expressions of the components of `f(t, y)` and"""

def system_jacobian(system: NativeSystem, t: float, state: _ArrayF64) -> _ArrayF64:
    """The Jacobian `d(derivatives)/d(state)` of `system` at `(t, state)`, row-major as a square"""

def force_jacobian(system: NativeSystem, q: _ArrayF64, t: float) -> _ArrayF64:
    """The force Jacobian `dF/dq` of a separable Hamiltonian `system` at `(q, t)`."""

def ensemble(system: str | dict[str, Any], common: dict[str, Any], sweeps: list[tuple[str, _ArrayF64]], states: _MatrixF64 | None, n: int, t_span: tuple[float, float], dt: float, method: str | None = None, stride: int | None = None, energy_error: bool = False, events: list[tuple[int, str, float]] = ..., max_lyapunov: int | None = None, sali: int | None = None, final_state: bool = True, threads: int | None = None, progress: Callable[[int, int], Any] | None = None, check_only: bool = False, prechecked: bool = False, rtol: float | None = None, atol: float | None = None, max_steps: int | None = None) -> dict[str, Any]:
    """Integrates `n` members of `system` on all cores (GIL released): a catalogue name with
    its `common` values, or a SymPy engine's system as a dict (`family` hamiltonian /
    lagrangian / ode, `expressions`, `ndof`, `params` as (name, value) pairs, `energy`,
    `state`; `common` empty). `sweeps` of (parameter or "name[i]", n values), optional
    `states` (n x state length). Returns method, ndof, final_state, steps, t, trajectory (with
    `stride`) and reductions by name (`max_energy_error`, `event_time` per event `(index,
    kind, value)` with kind crosses/rising/falling/abs_above, `max_lyapunov`, `sali`; each a
    list of arrays). `rtol`, `atol`, `max_steps`: an adaptive method's tolerances for every
    member, checked as `integrate` checks them. ValueError naming a bad member's index before
    any integration."""

def expr_lagrangian(sexpr: str, ndof: int, params: _ArrayF64, q0: _ArrayF64, qdot0: _ArrayF64) -> NativeSystem:
    """A Lagrangian system from a prefix S-expression (see `physicskit::classical::lagrangian::Expr`)"""

def expr_validate(sexpr: str, ndof: int, nparams: int) -> None:
    """Parses `sexpr` and checks its variable and parameter indices against `ndof` and `nparams`."""

def find_theta_equilibrium(p_phi: float, p_psi: float, I1: float, I3: float, Mgl: float, bracket: tuple[float, float]) -> float:
    """Minimum of `V_eff` in `bracket`: the root of its analytic slope, to a few ulps."""

def chaos_native(native: NativeSystem, state: _ArrayF64, t0: float, t_span: tuple[float, float], dt: float, method: str | None, kind: str, **options: Any) -> dict[str, Any]:
    """Runs an analysis on a built-in system from `(state, t0)` over `t_span` with `dt` and"""

def chaos_map(systems: list[NativeSystem], states: _MatrixF64, t_span: tuple[float, float], dt: float, method: str | None, indicator_name: str, **options: Any) -> _ArrayF64:
    """One indicator per point: point `i` is the orbit of `systems[i]` (or of `systems[0]` for"""

def chaos_hamiltonian(obj: Any, state: _ArrayF64, t0: float, t_span: tuple[float, float], dt: float, method: str, ndof: int, separable: bool, mass_inv: _ArrayF64, kind: str, **options: Any) -> dict[str, Any]:
    """Runs a chaos analysis (`kind` and options as `chaos.chaos_native`) on a Python"""

def chaos_ode(obj: Any, state: _ArrayF64, t0: float, t_span: tuple[float, float], dt: float, method: str, kind: str, **options: Any) -> dict[str, Any]:
    """Runs a chaos analysis on a Python `ODESystem` (or engine-less `LagrangianSystem`) `obj`"""

def integrate_hamiltonian(obj: Any, state: _ArrayF64, t0: float, t_span: tuple[float, float], dt: float, method: str, ndof: int, separable: bool, mass_inv: _ArrayF64, stride: int = 1, final_only: bool = False, energy: bool = True, progress: Callable[[int, int], object] | None = None, rtol: float | None = None, atol: float | None = None, max_steps: int | None = None) -> _ResultTuple:
    """Integrates a Python `HamiltonianSystem` subclass `obj` from `(state, t0)` with the Rust"""

def integrate_ode(obj: Any, state: _ArrayF64, t0: float, t_span: tuple[float, float], dt: float, method: str, stride: int = 1, final_only: bool = False, energy: bool = True, progress: Callable[[int, int], object] | None = None, rtol: float | None = None, atol: float | None = None, max_steps: int | None = None) -> _ResultTuple:
    """Integrates a Python `ODESystem` (or engine-less `LagrangianSystem`) `obj` from"""

def nutation_frequency(p_phi: float, p_psi: float, I1: float, I3: float, Mgl: float, theta_eq: float | None, dtheta: float) -> float:
    """Small-oscillation nutation frequency about `theta_eq`."""

def pendulum_action_angle(E: float, g_over_l: float) -> tuple[float, float]:
    """Action and period of a librating pendulum orbit of energy `E`."""

def precession_frequency(p_phi: float, p_psi: float, I1: float, theta_eq: float) -> float:
    """Steady-precession rate at `theta_eq`."""

def foucault_analytic_solution(q0: _ArrayF64, v0: _ArrayF64, omega0: float, omega_z: float, t: _ArrayF64) -> tuple[_ArrayF64, _ArrayF64]:
    """The exact (x(t), y(t)) of Foucault's pendulum (`FoucaultPendulum::analytic_solution`)."""

def eulers_disk_theta_analytic(t: _ArrayF64, theta0: float, decay_rate: float) -> _ArrayF64:
    """theta(t) of the reduced Euler's disk, zero after the collapse."""

def spin_reversal_time(t: _ArrayF64, spin: _ArrayF64, window: float = ...) -> float | None:
    """First zero of a uniformly sampled spin history averaged over `window` (s; default two
    pitching periods of the default rolling rattleback), or None if it keeps its sign."""

def projectile_analytic_trajectory(speed: float, angle_deg: float, g: float, t: _ArrayF64, height: float) -> tuple[_ArrayF64, _ArrayF64]:
    """Galileo's parabola `(x(t), y(t))`."""

def projectile_range_and_max_height(speed: float, angle_deg: float, g: float, height: float) -> tuple[float, float]:
    """Vacuum range and maximum height."""

def sine_gordon_kink(n: int, center: float, width: float, velocity: float, polarity: int) -> tuple[_ArrayF64, _ArrayF64]:
    """`SineGordonChain.kink`: boosted single-kink initial data `(q0, p0)`."""
