"""Type stubs of the native module ``physicskit._core`` (PyO3); checked against the compiled
module by mypy's stubtest (``bash python/dev.sh stubs``: names, parameters, defaults) and by
``tests/test_stubs.py`` (parameter and return types)."""

from typing import Any, final

import numpy as np
import numpy.typing as npt

ArrayF64 = npt.NDArray[np.float64]
ResultTuple = tuple[ArrayF64, ArrayF64, int | None, ArrayF64 | None, str, dict[str, Any]]

class ConvergenceError(RuntimeError):
    """The implicit solver of a step did not converge; reduce dt."""

@final
class NativeSystem:
    """A built-in Rust system, owned by the Python object that wraps it."""

    @property
    def state(self) -> ArrayF64: ...
    @property
    def t(self) -> float: ...
    @property
    def ndof(self) -> int | None: ...
    @property
    def separable(self) -> bool: ...
    @property
    def mass_inv(self) -> ArrayF64 | None: ...
    @property
    def default_method(self) -> str: ...
    def reset(self, state: ArrayF64, t0: float) -> None: ...
    def energy(self, state: ArrayF64) -> float: ...
    def derivatives(self, t: float, state: ArrayF64) -> ArrayF64: ...
    def kinetic_energy(self, p: ArrayF64) -> float: ...
    def potential_energy(self, q: ArrayF64) -> float: ...
    def force(self, q: ArrayF64, t: float) -> ArrayF64: ...
    def acceleration(self, q: ArrayF64, qdot: ArrayF64, t: float) -> ArrayF64: ...
    def momentum(self, q: ArrayF64, qdot: ArrayF64, t: float) -> ArrayF64: ...
    def integrate(
        self,
        state: ArrayF64,
        t0: float,
        t_span: tuple[float, float],
        dt: float,
        method: str | None = None,
        stride: int = 1,
        final_only: bool = False,
        energy: bool = True,
    ) -> ResultTuple:
        """Integrate from `(state, t0)`; keep every `stride`-th step (and the last), or only the
        first and last with `final_only`; `energy=False` gives `None` energy. ValueError when
        the stored samples would not fit in memory."""

def bead_on_hoop(theta0: float, thetadot0: float, R: float, omega: float, g: float) -> NativeSystem:
    """`BeadOnRotatingHoop(theta0, thetadot0, R, omega, g)`."""

def chain_modal_energies(sys: NativeSystem, q: ArrayF64, p: ArrayF64) -> ArrayF64:
    """Energy in each normal mode of a chain state."""

def chain_normal_mode_coords(sys: NativeSystem, q: ArrayF64, p: ArrayF64) -> tuple[ArrayF64, ArrayF64]:
    """Normal-mode coordinates `(Q, P)` of a chain state."""

def chain_normal_mode_frequencies(sys: NativeSystem) -> ArrayF64:
    """Normal-mode angular frequencies of a chain."""

def coupled_oscillators(q0: ArrayF64, qdot0: ArrayF64, n: int, m: float, k: float) -> NativeSystem:
    """`CoupledOscillators(q0, qdot0, n, m, k)`."""

def double_pendulum(theta0: ArrayF64, thetadot0: ArrayF64, m1: float, m2: float, l1: float, l2: float, g: float) -> NativeSystem:
    """`DoublePendulum(theta0, thetadot0, m1, m2, l1, l2, g)`."""

def double_pendulum_positions(sys: NativeSystem, q: ArrayF64) -> ArrayF64:
    """Cartesian bob positions `(x1, y1, x2, y2)`."""

def effective_potential_symmetric_top(theta: ArrayF64, p_phi: float, p_psi: float, I1: float, I3: float, Mgl: float) -> ArrayF64:
    """`V_eff(theta)` of the heavy symmetric top at each angle."""

def euler_top(omega0: ArrayF64, I1: float, I2: float, I3: float, quat0: ArrayF64 | None = None) -> NativeSystem:
    """`EulerTop(omega0, I1, I2, I3, quat0)`."""

def euler_top_angular_momentum_squared(sys: NativeSystem, state: ArrayF64) -> float:
    """`|L|^2` of an Euler-top state."""

def euler_top_rotation_matrix(sys: NativeSystem, state: ArrayF64) -> ArrayF64:
    """Body-to-world rotation matrix of an Euler-top state."""

def expr_lagrangian(sexpr: str, ndof: int, params: ArrayF64, q0: ArrayF64, qdot0: ArrayF64) -> NativeSystem:
    """A Lagrangian system from a prefix S-expression (see `physicskit::classical::lagrangian::Expr`)"""

def expr_validate(sexpr: str, ndof: int, nparams: int) -> None:
    """Parses `sexpr` and checks its variable and parameter indices against `ndof` and `nparams`."""

def find_theta_equilibrium(p_phi: float, p_psi: float, I1: float, I3: float, Mgl: float, bracket: tuple[float, float]) -> float:
    """Minimum of `V_eff` in `bracket`."""

def fput_chain(n: int, m: float, k: float, beta: float, mode: int, amplitude: float) -> NativeSystem:
    """`FPUTChain(n, m, k, beta, mode, amplitude)`."""

def harmonic_chain(q0: ArrayF64, p0: ArrayF64, m: float, k: float) -> NativeSystem:
    """`HarmonicChain(q0, p0, m, k)`."""

def heavy_symmetric_top(angles0: ArrayF64, angledots0: ArrayF64, I1: float, I3: float, M: float, l: float, g: float) -> NativeSystem:
    """`HeavySymmetricTop(angles0, angledots0, I1, I3, M, l, g)`."""

def henon_heiles(q0: ArrayF64, p0: ArrayF64) -> NativeSystem:
    """`HenonHeilesSystem(q0, p0)`."""

def integrate_hamiltonian(obj: Any, state: ArrayF64, t0: float, t_span: tuple[float, float], dt: float, method: str, ndof: int, separable: bool, mass_inv: ArrayF64, stride: int = 1, final_only: bool = False, energy: bool = True) -> ResultTuple:
    """Integrates a Python `HamiltonianSystem` subclass `obj` from `(state, t0)` with the Rust"""

def integrate_ode(obj: Any, state: ArrayF64, t0: float, t_span: tuple[float, float], dt: float, method: str, stride: int = 1, final_only: bool = False, energy: bool = True) -> ResultTuple:
    """Integrates a Python `ODESystem` (or engine-less `LagrangianSystem`) `obj` from"""

def kepler(q0: ArrayF64, p0: ArrayF64, k: float, mu: float, eps: float, c_eps: float, c_pn: float, softening: float) -> NativeSystem:
    """`KeplerSystem(q0, p0, k, mu, eps, c_eps, c_pn, softening)`."""

def kepler_angular_momentum(sys: NativeSystem, q: ArrayF64, p: ArrayF64) -> float:
    """Out-of-plane angular momentum `x p_y - y p_x`."""

def kepler_from_orbital_elements(a: float, e: float, k: float, mu: float, eps: float, c_eps: float, c_pn: float, softening: float) -> NativeSystem:
    """`KeplerSystem.from_orbital_elements`: start at perihelion of the orbit `(a, e)`."""

def kepler_lrl_vector(sys: NativeSystem, q: ArrayF64, p: ArrayF64) -> ArrayF64:
    """Laplace–Runge–Lenz vector."""

def nutation_frequency(p_phi: float, p_psi: float, I1: float, I3: float, Mgl: float, theta_eq: float | None, dtheta: float) -> float:
    """Small-oscillation nutation frequency about `theta_eq`."""

def pendulum_action_angle(E: float, g_over_l: float) -> tuple[float, float]:
    """Action and period of a librating pendulum orbit of energy `E`."""

def pendulum_swarm(q0: ArrayF64, p0: ArrayF64, g_over_l: float) -> NativeSystem:
    """`PendulumSwarm(q0, p0, g_over_l)`."""

def pendulum_swarm_from_box(q_center: float, p_center: float, dq: float, dp: float, n: int, g_over_l: float, seed: int) -> NativeSystem:
    """`PendulumSwarm.from_box`."""

def precession_frequency(p_phi: float, p_psi: float, I1: float, theta_eq: float) -> float:
    """Steady-precession rate at `theta_eq`."""

def projectile(q0: ArrayF64, p0: ArrayF64, m: float, g: float, drag_coeff: float) -> NativeSystem:
    """`ProjectileMotion(q0, p0, m, g, drag_coeff)`."""

def projectile_analytic_trajectory(speed: float, angle_deg: float, g: float, t: ArrayF64, height: float) -> tuple[ArrayF64, ArrayF64]:
    """Galileo's parabola `(x(t), y(t))`."""

def projectile_from_launch(speed: float, angle_deg: float, m: float, g: float, drag_coeff: float, height: float) -> NativeSystem:
    """`ProjectileMotion.from_launch`."""

def projectile_range_and_max_height(speed: float, angle_deg: float, g: float, height: float) -> tuple[float, float]:
    """Vacuum range and maximum height."""

def sine_gordon_chain(n: int, m: float, k: float, q0: ArrayF64 | None = None, p0: ArrayF64 | None = None) -> NativeSystem:
    """`SineGordonChain(n, m, k, q0, p0)`."""

def sine_gordon_kink(n: int, center: float, width: float, velocity: float, polarity: int) -> tuple[ArrayF64, ArrayF64]:
    """`SineGordonChain.kink`: boosted single-kink initial data `(q0, p0)`."""

def swarm_per_particle_energy(sys: NativeSystem, q: ArrayF64, p: ArrayF64) -> ArrayF64:
    """Energy of each pendulum of the swarm."""

def swarm_phase_space_area(sys: NativeSystem, q: ArrayF64, p: ArrayF64) -> float:
    """Convex-hull area of the swarm's `(q, p)` points."""

def top_precession_nutation_rate(sys: NativeSystem, state: ArrayF64) -> tuple[float, float]:
    """Instantaneous `(phidot, thetadot)` of a heavy top state."""
