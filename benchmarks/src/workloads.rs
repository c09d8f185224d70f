//! The peer-comparison workloads through the Rust API: the peer's canonical cases, 10^5 steps
//! at the peer's dt, full trajectory and energy stored, from the peer's initial conditions.

use physicskit::classical::systems::*;
use physicskit::classical::{
    HamiltonianSystem, LagrangianSystem, Method, OdeSystem, Result, SimulationResult,
};

/// One benchmark case.
pub struct Workload {
    /// Name shared with the Python comparison script.
    pub name: &'static str,
    /// Integrator.
    pub method: Method,
    /// Step.
    pub dt: f64,
    /// Runs `steps` steps from the case's initial condition.
    pub run: fn(usize, f64, Method) -> Result<SimulationResult>,
}

fn span(steps: usize, dt: f64) -> (f64, f64) {
    (0.0, steps as f64 * dt)
}

fn kepler(a: f64, e: f64, c_pn: f64) -> Result<KeplerSystem> {
    KeplerSystem::from_orbital_elements(
        a,
        e,
        1.0,
        1.0,
        KeplerPerturbations::none().with_post_newtonian(c_pn),
    )
}

/// The double pendulum of both its workloads (implicit midpoint and rk4).
fn double_pendulum() -> Result<DoublePendulum> {
    DoublePendulum::new(&[2.0, 1.0], &[0.5, -0.3], Default::default())
}

/// The swarm workload's 200 pendulums (also the plain loop's start).
///
/// # Errors
/// None for these parameters; the constructor's otherwise.
pub fn swarm() -> Result<PendulumSwarm> {
    PendulumSwarm::from_box(1.0, 0.0, 0.05, 0.05, 200, 1.0, 0)
}

/// The sine-Gordon workload's kink on 100 sites, `(q0, p0)` (also the plain loop's start).
///
/// # Errors
/// None for these parameters; the constructor's otherwise.
pub fn sine_gordon_kink() -> Result<(Vec<f64>, Vec<f64>)> {
    SineGordonChain::kink(100, 50.0, 1.0, 0.2, 1)
}

/// Initial positions of an `n`-mass chain with fixed ends (the 16-mass harmonic chain, the
/// 32-mass FPUT chain): mode 1 with amplitude 0.5, as `FPUTChain::new` lays it out.
pub fn harmonic_chain_q0(n: usize) -> Vec<f64> {
    FPUTChain::new(n, 1.0, 1.0, 0.0, 1, 0.5)
        .expect("valid chain")
        .q()
        .to_vec()
}

/// Every workload, in the order of the issue.
pub fn all() -> Vec<Workload> {
    vec![
        Workload {
            name: "projectile",
            method: Method::Yoshida4,
            dt: 1e-3,
            run: |n, dt, m| {
                ProjectileMotion::from_launch(20.0, 45.0, 1.0, 9.81, 0.0, 0.0)?.integrate(
                    span(n, dt),
                    dt,
                    m,
                )
            },
        },
        Workload {
            name: "kepler",
            method: Method::Yoshida4,
            dt: 1e-3,
            run: |n, dt, m| kepler(1.0, 0.5, 0.0)?.integrate(span(n, dt), dt, m),
        },
        Workload {
            name: "kepler_verlet",
            method: Method::Verlet,
            dt: 1e-3,
            run: |n, dt, m| kepler(1.0, 0.5, 0.0)?.integrate(span(n, dt), dt, m),
        },
        Workload {
            name: "kepler_pn",
            method: Method::Yoshida4,
            dt: 1e-3,
            run: |n, dt, m| kepler(1.0, 0.3, 0.01)?.integrate(span(n, dt), dt, m),
        },
        Workload {
            name: "double_pendulum",
            method: Method::ImplicitMidpoint,
            dt: 3e-5,
            run: |n, dt, m| double_pendulum()?.integrate(span(n, dt), dt, m),
        },
        Workload {
            name: "double_pendulum_rk4",
            method: Method::Rk4,
            dt: 3e-5,
            run: |n, dt, m| double_pendulum()?.integrate(span(n, dt), dt, m),
        },
        Workload {
            name: "hoop",
            method: Method::ImplicitMidpoint,
            dt: 2.2e-5,
            run: |n, dt, m| {
                let params = HoopParams {
                    omega: 3.0,
                    ..Default::default()
                };
                BeadOnRotatingHoop::new(0.3, 0.0, params)?.integrate(span(n, dt), dt, m)
            },
        },
        Workload {
            name: "coupled_oscillators",
            method: Method::ImplicitMidpoint,
            dt: 1e-4,
            run: |n, dt, m| {
                CoupledOscillators::new(&[0.1, -0.2, 0.15], &[0.0; 3], Default::default())?
                    .integrate(span(n, dt), dt, m)
            },
        },
        Workload {
            name: "henon_heiles",
            method: Method::Yoshida4,
            dt: 5e-3,
            run: |n, dt, m| {
                HenonHeilesSystem::new(&[0.0, 0.3], &[0.3, 0.0])?.integrate(span(n, dt), dt, m)
            },
        },
        Workload {
            name: "swarm",
            method: Method::Yoshida4,
            dt: 1e-3,
            run: |n, dt, m| swarm()?.integrate(span(n, dt), dt, m),
        },
        Workload {
            name: "harmonic_chain",
            method: Method::Yoshida4,
            dt: 1e-2,
            run: |n, dt, m| {
                HarmonicChain::new(&harmonic_chain_q0(16), &[0.0; 16], 1.0, 1.0)?.integrate(
                    span(n, dt),
                    dt,
                    m,
                )
            },
        },
        Workload {
            name: "fput",
            method: Method::Yoshida4,
            dt: 5e-2,
            run: |n, dt, m| {
                FPUTChain::new(32, 1.0, 1.0, 0.7, 1, 0.5)?.integrate(span(n, dt), dt, m)
            },
        },
        Workload {
            name: "sine_gordon",
            method: Method::Yoshida4,
            dt: 1e-2,
            run: |n, dt, m| {
                let (q0, p0) = sine_gordon_kink()?;
                SineGordonChain::new(100, 1.0, 1.0, Some(&q0), Some(&p0))?.integrate(
                    span(n, dt),
                    dt,
                    m,
                )
            },
        },
        Workload {
            name: "euler_top",
            method: Method::ImplicitMidpoint,
            dt: 1e-3,
            run: |n, dt, m| {
                EulerTop::new(&[0.01, 1.0, 0.01], Default::default(), None)?.integrate(
                    span(n, dt),
                    dt,
                    m,
                )
            },
        },
        Workload {
            name: "heavy_top",
            method: Method::ImplicitMidpoint,
            dt: 5e-5,
            run: |n, dt, m| {
                HeavySymmetricTop::new(&[0.0, 0.5, 0.0], &[0.0, 0.0, 20.0], Default::default())?
                    .integrate(span(n, dt), dt, m)
            },
        },
    ]
}
