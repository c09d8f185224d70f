//! Test systems that the library does not ship: a non-separable Hamiltonian, a damped
//! oscillator, a free rigid body, a hand-written Lagrangian pendulum and ODEs that blow up.

// A mass of exactly zero is the singular case the Lagrangian pendulum refuses: an exact float
// comparison is intended.
#![allow(clippy::float_cmp)]

use physicskit::classical::integrators::{
    hamiltonian_energy, lagrangian_derivatives, separable_derivatives,
};
use physicskit::classical::model::erased::Capabilities;
use physicskit::classical::symbolic::Backend;
use physicskit::classical::systems::HenonHeilesSystem;
use physicskit::classical::{
    DynamicalSystem, Error, HamiltonianSystem, LagrangianSystem, Method, OdeSystem, Phase, Result,
};

/// `H = (p^2 / 2) (1 + q^2) + q^2 / 2`: non-separable (the kinetic term depends on `q`).
pub struct NonSeparable {
    pub phase: Phase,
}

impl NonSeparable {
    pub fn new(q0: f64, p0: f64) -> Self {
        Self {
            phase: Phase::new(vec![q0, p0], 0.0).unwrap(),
        }
    }
}

impl DynamicalSystem for NonSeparable {
    fn phase(&self) -> &Phase {
        &self.phase
    }
    fn phase_mut(&mut self) -> &mut Phase {
        &mut self.phase
    }
    fn derivatives(&self, _t: f64, y: &[f64], out: &mut [f64]) -> Result<()> {
        let (q, p) = (y[0], y[1]);
        out[0] = p * (1.0 + q * q);
        out[1] = -(p * p * q + q);
        Ok(())
    }
    fn energy(&self, y: &[f64]) -> f64 {
        0.5 * y[1] * y[1] * (1.0 + y[0] * y[0]) + 0.5 * y[0] * y[0]
    }
    fn default_method(&self) -> Method {
        Method::ImplicitMidpoint
    }
}

impl HamiltonianSystem for NonSeparable {
    fn ndof(&self) -> usize {
        1
    }
    fn kinetic_energy(&self, p: &[f64]) -> f64 {
        0.5 * p[0] * p[0]
    }
    fn potential_energy(&self, q: &[f64]) -> f64 {
        0.5 * q[0] * q[0]
    }
    fn separable(&self) -> bool {
        false
    }
}

/// A harmonic oscillator with linear damping `dp/dt = -q - gamma p`; `force` holds only the
/// conservative part, so `conservative()` is false.
pub struct Damped {
    pub phase: Phase,
    pub gamma: f64,
}

impl DynamicalSystem for Damped {
    fn phase(&self) -> &Phase {
        &self.phase
    }
    fn phase_mut(&mut self) -> &mut Phase {
        &mut self.phase
    }
    fn derivatives(&self, t: f64, y: &[f64], out: &mut [f64]) -> Result<()> {
        separable_derivatives(self, t, y, out)?;
        out[1] -= self.gamma * y[1];
        Ok(())
    }
    fn energy(&self, y: &[f64]) -> f64 {
        hamiltonian_energy(self, y)
    }
    fn default_method(&self) -> Method {
        Method::Rk4
    }
}

impl HamiltonianSystem for Damped {
    fn ndof(&self) -> usize {
        1
    }
    fn kinetic_energy(&self, p: &[f64]) -> f64 {
        0.5 * p[0] * p[0]
    }
    fn potential_energy(&self, q: &[f64]) -> f64 {
        0.5 * q[0] * q[0]
    }
    fn conservative(&self) -> bool {
        false
    }
    fn force(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<()> {
        out[0] = -q[0];
        Ok(())
    }
}

/// Euler's equations of a torque-free rigid body, `I dw/dt = (I w) x w`, written here from
/// Landau & Lifshitz, *Mechanics*, §36, independently of the library's EulerTop.
pub struct FreeRigidBody {
    pub phase: Phase,
    pub inertia: [f64; 3],
}

impl FreeRigidBody {
    pub fn angular_momentum_squared(&self, w: &[f64]) -> f64 {
        (0..3).map(|i| (self.inertia[i] * w[i]).powi(2)).sum()
    }
}

impl DynamicalSystem for FreeRigidBody {
    fn phase(&self) -> &Phase {
        &self.phase
    }
    fn phase_mut(&mut self) -> &mut Phase {
        &mut self.phase
    }
    fn derivatives(&self, _t: f64, w: &[f64], out: &mut [f64]) -> Result<()> {
        let [i1, i2, i3] = self.inertia;
        out[0] = (i2 - i3) / i1 * w[1] * w[2];
        out[1] = (i3 - i1) / i2 * w[2] * w[0];
        out[2] = (i1 - i2) / i3 * w[0] * w[1];
        Ok(())
    }
    fn energy(&self, w: &[f64]) -> f64 {
        0.5 * (0..3).map(|i| self.inertia[i] * w[i] * w[i]).sum::<f64>()
    }
    fn jacobian(&self, _t: f64, w: &[f64], j: &mut [f64]) -> Option<Result<()>> {
        let [i1, i2, i3] = self.inertia;
        let (a, b, c) = ((i2 - i3) / i1, (i3 - i1) / i2, (i1 - i2) / i3);
        j.copy_from_slice(&[
            0.0,
            a * w[2],
            a * w[1],
            b * w[2],
            0.0,
            b * w[0],
            c * w[1],
            c * w[0],
            0.0,
        ]);
        Some(Ok(()))
    }
    fn default_method(&self) -> Method {
        Method::ImplicitMidpoint
    }
}

impl OdeSystem for FreeRigidBody {}

/// A first-order ODE from a plain function, with no Jacobian.
pub struct Scalar {
    pub phase: Phase,
    pub f: fn(f64) -> f64,
}

impl DynamicalSystem for Scalar {
    fn phase(&self) -> &Phase {
        &self.phase
    }
    fn phase_mut(&mut self) -> &mut Phase {
        &mut self.phase
    }
    fn derivatives(&self, _t: f64, y: &[f64], out: &mut [f64]) -> Result<()> {
        out[0] = (self.f)(y[0]);
        Ok(())
    }
    fn energy(&self, y: &[f64]) -> f64 {
        y[0]
    }
    fn default_method(&self) -> Method {
        Method::Rk4
    }
}

impl OdeSystem for Scalar {}

/// The pendulum as a Lagrangian, `L = qdot^2 / 2 + (g/l) cos q`, with its Euler–Lagrange
/// equation `qddot = -(g/l) sin q` and Legendre map `p = qdot` written by hand.
pub struct LagrangianPendulum {
    pub phase: Phase,
    pub g_over_l: f64,
    /// Mass-matrix value; 0 makes the Lagrangian degenerate.
    pub mass: f64,
}

impl LagrangianPendulum {
    pub fn new(q0: f64, qdot0: f64) -> Self {
        Self {
            phase: Phase::new(vec![q0, qdot0], 0.0).unwrap(),
            g_over_l: 1.0,
            mass: 1.0,
        }
    }
}

impl DynamicalSystem for LagrangianPendulum {
    fn phase(&self) -> &Phase {
        &self.phase
    }
    fn phase_mut(&mut self) -> &mut Phase {
        &mut self.phase
    }
    fn derivatives(&self, t: f64, y: &[f64], out: &mut [f64]) -> Result<()> {
        lagrangian_derivatives(self, t, y, out)
    }
    fn energy(&self, y: &[f64]) -> f64 {
        0.5 * self.mass * y[1] * y[1] - self.g_over_l * y[0].cos()
    }
    fn default_method(&self) -> Method {
        Method::ImplicitMidpoint
    }
}

impl LagrangianSystem for LagrangianPendulum {
    fn ndof(&self) -> usize {
        1
    }
    fn acceleration(&self, q: &[f64], _qdot: &[f64], t: f64, out: &mut [f64]) -> Result<()> {
        if self.mass == 0.0 {
            return Err(Error::SingularMatrix {
                what: "mass matrix".into(),
                t,
            });
        }
        out[0] = -self.g_over_l * q[0].sin() / self.mass;
        Ok(())
    }
    fn momentum(&self, _q: &[f64], qdot: &[f64], _t: f64, out: &mut [f64]) -> Result<()> {
        out[0] = self.mass * qdot[0];
        Ok(())
    }
    fn velocity(&self, _q: &[f64], p: &[f64], t: f64, out: &mut [f64]) -> Result<()> {
        if self.mass == 0.0 {
            return Err(Error::SingularMatrix {
                what: "mass matrix".into(),
                t,
            });
        }
        out[0] = p[0] / self.mass;
        Ok(())
    }
    fn canonical_derivatives(&self, t: f64, y: &[f64], out: &mut [f64]) -> Result<()> {
        self.velocity(&y[..1], &y[1..], t, &mut out[..1])?;
        out[1] = -self.g_over_l * y[0].sin();
        Ok(())
    }
}

/// Independent pendulums `H = sum_i p_i^2/2 - cos q_i`, written for the ensemble tests.
#[derive(Clone)]
pub struct PendulumBank {
    pub phase: Phase,
    pub n: usize,
}

impl PendulumBank {
    pub fn new(n: usize) -> Self {
        // Spread of amplitudes so that members follow different trajectories.
        let q: Vec<f64> = (0..n).map(|i| 0.1 + 2.9 * i as f64 / n as f64).collect();
        let p: Vec<f64> = (0..n)
            .map(|i| ((i * 7919) % 101) as f64 / 100.0 - 0.5)
            .collect();
        Self {
            phase: Phase::from_halves("q0", &q, "p0", &p).unwrap(),
            n,
        }
    }
}

impl HamiltonianSystem for PendulumBank {
    fn ndof(&self) -> usize {
        self.n
    }
    fn kinetic_energy(&self, p: &[f64]) -> f64 {
        p.iter().map(|v| 0.5 * v * v).sum()
    }
    fn potential_energy(&self, q: &[f64]) -> f64 {
        q.iter().map(|v| -v.cos()).sum()
    }
    fn force(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<()> {
        out.iter_mut().zip(q).for_each(|(f, v)| *f = -v.sin());
        Ok(())
    }
}

physicskit::impl_separable_dynamics!(PendulumBank);

impl physicskit::classical::integrators::Ensemble for PendulumBank {
    fn members(&self, start: usize, len: usize) -> Result<Self> {
        let (q, p) = self.phase.state().split_at(self.n);
        let mut sub = Self {
            phase: Phase::from_halves("q0", &q[start..start + len], "p0", &p[start..start + len])?,
            n: len,
        };
        sub.phase.set_t(self.phase.t())?;
        Ok(sub)
    }
}

/// Whether this build and host get the Taylor recurrences written as AVX code
/// (`symbolic/tape/taylor_asm.rs`: x86-64 with AVX, System V calls, the JIT built) for
/// `lanes` lanes (1: one state, the scalar program).
pub fn avx_code(lanes: usize) -> bool {
    #[cfg(all(target_arch = "x86_64", not(windows)))]
    {
        native() == Backend::Native
            && (lanes == 1 || lanes.is_multiple_of(4))
            && std::arch::is_x86_feature_detected!("avx")
    }
    #[cfg(not(all(target_arch = "x86_64", not(windows))))]
    {
        let _ = lanes;
        false
    }
}

/// The backend `compile_native` gives in this build: machine code with the feature `jit`,
/// the interpreter without it (the JIT tests then check that every tape stays interpreted).
pub fn native() -> Backend {
    if cfg!(feature = "jit") {
        Backend::Native
    } else {
        Backend::Interpreter
    }
}

/// The same bits; any NaN matches any NaN (Rust leaves NaN payloads unspecified, and `0/0`
/// or `ln(-1)` make NaNs in both).
pub fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

/// A fixed linear congruential sequence in `[-0.5, 0.5)`: deterministic test data.
pub fn pseudo_random(n: usize, seed: u64) -> Vec<f64> {
    let mut s = seed;
    (0..n)
        .map(|_| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect()
}

/// A Hénon–Heiles system at energy `e` from `(x, y, p_x)`, with `p_y >= 0` from the energy.
pub fn henon_heiles_at(e: f64, x: f64, y: f64, px: f64) -> HenonHeilesSystem {
    let v = 0.5 * (x * x + y * y) + x * x * y - y * y * y / 3.0;
    let py = (2.0 * (e - v) - px * px).sqrt();
    HenonHeilesSystem::new(&[x, y], &[px, py]).unwrap()
}

/// The Lorenz system `x' = σ (y - x)`, `y' = x (ρ - z) - y`, `z' = x y - β z` at the classic
/// σ = 10, ρ = 28, β = 8/3, with no analytic Jacobian (the tangent dynamics use central
/// differences). Its divergence is the constant `-(σ + 1 + β)`.
pub struct Lorenz {
    pub phase: Phase,
}

impl Lorenz {
    pub const SIGMA: f64 = 10.0;
    pub const RHO: f64 = 28.0;
    pub const BETA: f64 = 8.0 / 3.0;

    pub fn new(state: [f64; 3]) -> Self {
        Self {
            phase: Phase::new(state.to_vec(), 0.0).unwrap(),
        }
    }
}

impl DynamicalSystem for Lorenz {
    fn phase(&self) -> &Phase {
        &self.phase
    }
    fn phase_mut(&mut self) -> &mut Phase {
        &mut self.phase
    }
    fn derivatives(&self, _t: f64, s: &[f64], out: &mut [f64]) -> Result<()> {
        out[0] = Self::SIGMA * (s[1] - s[0]);
        out[1] = s[0] * (Self::RHO - s[2]) - s[1];
        out[2] = s[0] * s[1] - Self::BETA * s[2];
        Ok(())
    }
    fn energy(&self, _state: &[f64]) -> f64 {
        0.0
    }
    fn default_method(&self) -> Method {
        Method::Rk4
    }
}

impl OdeSystem for Lorenz {}
impl Capabilities for Lorenz {}
