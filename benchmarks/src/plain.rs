//! Plain reference loops: what a careful person writes by hand for one system and one scheme.
//!
//! Allocation-free inside the loop, Yoshida-4 with merged kicks (three force evaluations per
//! step, the last force reused), storing `t`, `q`, `p` and the energy of every sample in
//! preallocated vectors. The library must come within 1.25x of these (issue 7). The force and
//! energy are closures, which monomorphization inlines exactly like hand-written code. The
//! trig-bound loops use libm unless `PHYSICSKIT_PLAIN_SLICE_TRIG` is set (see [`case`]).

use physicskit::classical::core::trig::{sin_into, sum_cos};

/// `w1 = 1/(2 - 2^(1/3))` (Yoshida 1990).
const W1: f64 = 1.351_207_191_959_657_6;
/// `w0 = 1 - 2 w1`.
const W0: f64 = -1.702_414_383_919_315_3;

/// A stored trajectory.
pub struct Trajectory {
    /// Sample times.
    pub t: Vec<f64>,
    /// Positions, row-major `(n + 1) x d`.
    pub q: Vec<f64>,
    /// Momenta, row-major `(n + 1) x d`.
    pub p: Vec<f64>,
    /// Energy of each sample.
    pub energy: Vec<f64>,
}

/// Yoshida-4 over `n` steps of `dt` from `(q0, p0)`; `force(q, f)` writes `-dV/dq`.
pub fn yoshida4(
    q0: &[f64],
    p0: &[f64],
    mass_inv: f64,
    dt: f64,
    n: usize,
    force: impl Fn(&[f64], &mut [f64]),
    energy: impl Fn(&[f64], &[f64]) -> f64,
) -> Trajectory {
    let d = q0.len();
    let mut out = Trajectory {
        t: Vec::with_capacity(n + 1),
        q: Vec::with_capacity((n + 1) * d),
        p: Vec::with_capacity((n + 1) * d),
        energy: Vec::with_capacity(n + 1),
    };
    let (mut q, mut p) = (q0.to_vec(), p0.to_vec());
    let mut f = vec![0.0; d];
    let record = |out: &mut Trajectory, t: f64, q: &[f64], p: &[f64]| {
        out.t.push(t);
        out.q.extend_from_slice(q);
        out.p.extend_from_slice(p);
        out.energy.push(energy(q, p));
    };
    record(&mut out, 0.0, &q, &p);
    force(&q, &mut f);
    let kicks = [
        0.5 * W1 * dt,
        0.5 * (W1 + W0) * dt,
        0.5 * (W0 + W1) * dt,
        0.5 * W1 * dt,
    ];
    let drifts = [W1 * dt * mass_inv, W0 * dt * mass_inv, W1 * dt * mass_inv];
    for step in 1..=n {
        for i in 0..3 {
            for j in 0..d {
                p[j] += kicks[i] * f[j];
                q[j] += drifts[i] * p[j];
            }
            force(&q, &mut f);
        }
        for j in 0..d {
            p[j] += kicks[3] * f[j];
        }
        record(&mut out, step as f64 * dt, &q, &p);
    }
    out
}

/// Whether the trig-bound plain loops (swarm, sine-Gordon) call physicskit's slice sine and
/// cosine sum instead of libm element by element: `PHYSICSKIT_PLAIN_SLICE_TRIG` set. By default
/// they use libm, as a hand-written loop would; with it, both sides share the trig code and the
/// ratio isolates the integrator.
fn slice_trig() -> bool {
    std::env::var_os("PHYSICSKIT_PLAIN_SLICE_TRIG").is_some()
}

/// The plain-loop version of a separable workload, by the workload's name, with the same
/// initial condition as [`crate::workloads`]; `None` for non-separable workloads.
pub fn case(name: &str) -> Option<fn(usize, f64) -> Trajectory> {
    Some(match name {
        "projectile" => |n, dt| {
            let v = 20.0 * std::f64::consts::FRAC_1_SQRT_2;
            let g = 9.81;
            yoshida4(
                &[0.0, 0.0],
                &[v, v],
                1.0,
                dt,
                n,
                |_, f| {
                    f[0] = 0.0;
                    f[1] = -g;
                },
                |q, p| 0.5 * (p[0] * p[0] + p[1] * p[1]) + g * q[1],
            )
        },
        "kepler" | "kepler_pn" => {
            if name == "kepler" {
                |n, dt| kepler(0.5, 0.0, n, dt)
            } else {
                |n, dt| kepler(0.3, 0.01, n, dt)
            }
        }
        "henon_heiles" => |n, dt| {
            yoshida4(
                &[0.0, 0.3],
                &[0.3, 0.0],
                1.0,
                dt,
                n,
                |q, f| {
                    f[0] = -q[0] - 2.0 * q[0] * q[1];
                    f[1] = -q[1] - q[0] * q[0] + q[1] * q[1];
                },
                |q, p| {
                    0.5 * (p[0] * p[0] + p[1] * p[1] + q[0] * q[0] + q[1] * q[1])
                        + q[0] * q[0] * q[1]
                        - q[1] * q[1] * q[1] / 3.0
                },
            )
        },
        "swarm" => |n, dt| {
            if slice_trig() {
                swarm(
                    n,
                    dt,
                    |q, f| {
                        sin_into(q, f);
                        f.iter_mut().for_each(|fi| *fi = -*fi);
                    },
                    |q, p| p.iter().map(|p| 0.5 * p * p).sum::<f64>() - sum_cos(q),
                )
            } else {
                swarm(
                    n,
                    dt,
                    |q, f| {
                        for (fi, qi) in f.iter_mut().zip(q) {
                            *fi = -qi.sin();
                        }
                    },
                    |q, p| q.iter().zip(p).map(|(q, p)| 0.5 * p * p - q.cos()).sum(),
                )
            }
        },
        "harmonic_chain" => |n, dt| {
            let q0 = crate::workloads::harmonic_chain_q0(16);
            yoshida4(
                &q0,
                &[0.0; 16],
                1.0,
                dt,
                n,
                |q, f| fixed_chain_force(q, f, 0.0),
                |q, p| fixed_chain_energy(q, p, 0.0),
            )
        },
        "fput" => |n, dt| {
            let q0 = crate::workloads::harmonic_chain_q0(32);
            yoshida4(
                &q0,
                &[0.0; 32],
                1.0,
                dt,
                n,
                |q, f| fixed_chain_force(q, f, 0.7),
                |q, p| fixed_chain_energy(q, p, 0.7),
            )
        },
        "sine_gordon" => |n, dt| {
            let bond_energy =
                |q: &[f64]| -> f64 { q.windows(2).map(|w| 0.5 * (w[1] - w[0]).powi(2)).sum() };
            if slice_trig() {
                sine_gordon(
                    n,
                    dt,
                    |q, f| {
                        sin_into(q, f);
                        sine_gordon_force(q, f);
                    },
                    |q, p| {
                        let kinetic: f64 = p.iter().map(|p| 0.5 * p * p).sum();
                        bond_energy(q) + kinetic + q.len() as f64 - sum_cos(q)
                    },
                )
            } else {
                sine_gordon(
                    n,
                    dt,
                    |q, f| {
                        for (fi, qi) in f.iter_mut().zip(q) {
                            *fi = qi.sin();
                        }
                        sine_gordon_force(q, f);
                    },
                    |q, p| {
                        let sites: f64 = q
                            .iter()
                            .zip(p)
                            .map(|(q, p)| 0.5 * p * p + 1.0 - q.cos())
                            .sum();
                        bond_energy(q) + sites
                    },
                )
            }
        },
        _ => return None,
    })
}

fn kepler(e: f64, c_pn: f64, n: usize, dt: f64) -> Trajectory {
    let r0 = 1.0 - e;
    let p0 = ((1.0 + e) / r0).sqrt();
    yoshida4(
        &[r0, 0.0],
        &[0.0, p0],
        1.0,
        dt,
        n,
        |q, f| {
            let inv = 1.0 / (q[0] * q[0] + q[1] * q[1]).sqrt();
            let inv3 = inv * inv * inv;
            let s = -inv3 + 3.0 * c_pn * inv3 * inv * inv;
            f[0] = s * q[0];
            f[1] = s * q[1];
        },
        |q, p| {
            let inv = 1.0 / (q[0] * q[0] + q[1] * q[1]).sqrt();
            0.5 * (p[0] * p[0] + p[1] * p[1]) - inv + c_pn * inv * inv * inv
        },
    )
}

/// The workloads' swarm (n = 200) with the given force and energy.
fn swarm(
    n: usize,
    dt: f64,
    force: impl Fn(&[f64], &mut [f64]),
    energy: impl Fn(&[f64], &[f64]) -> f64,
) -> Trajectory {
    let s =
        physicskit::classical::systems::PendulumSwarm::from_box(1.0, 0.0, 0.05, 0.05, 200, 1.0, 0)
            .expect("valid swarm");
    let (q0, p0) = physicskit::classical::DynamicalSystem::state(&s).split_at(200);
    yoshida4(q0, p0, 1.0, dt, n, force, energy)
}

/// The workloads' sine-Gordon kink (n = 100) with the given force and energy.
fn sine_gordon(
    n: usize,
    dt: f64,
    force: impl Fn(&[f64], &mut [f64]),
    energy: impl Fn(&[f64], &[f64]) -> f64,
) -> Trajectory {
    let (q0, p0) = physicskit::classical::systems::SineGordonChain::kink(100, 50.0, 1.0, 0.2, 1)
        .expect("valid kink");
    yoshida4(&q0, &p0, 1.0, dt, n, force, energy)
}

/// `F_i = (q_{i-1} - q_i) + (q_{i+1} - q_i) - sin q_i` with free ends, from `f = sin q`.
fn sine_gordon_force(q: &[f64], f: &mut [f64]) {
    let last = q.len() - 1;
    for i in 0..=last {
        let left = if i > 0 { q[i - 1] - q[i] } else { 0.0 };
        let right = if i < last { q[i + 1] - q[i] } else { 0.0 };
        f[i] = left + right - f[i];
    }
}

/// `F_i = (r_i - r_{i-1}) + beta (r_i^3 - r_{i-1}^3)`, `r_i = q_{i+1} - q_i`, walls at both ends.
fn fixed_chain_force(q: &[f64], f: &mut [f64], beta: f64) {
    let n = q.len();
    let mut left = q[0];
    for i in 0..n {
        let right = if i + 1 < n { q[i + 1] - q[i] } else { -q[i] };
        f[i] = right - left + beta * (right * right * right - left * left * left);
        left = right;
    }
}

fn fixed_chain_energy(q: &[f64], p: &[f64], beta: f64) -> f64 {
    let n = q.len();
    let bond = |r: f64| 0.5 * r * r + 0.25 * beta * r * r * r * r;
    let mut v = bond(q[0]) + bond(q[n - 1]);
    for i in 0..n - 1 {
        v += bond(q[i + 1] - q[i]);
    }
    v + p.iter().map(|x| 0.5 * x * x).sum::<f64>()
}
