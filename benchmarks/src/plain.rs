//! Plain reference loops: what a careful person writes by hand for one system and one scheme.
//!
//! Allocation-free inside the loop, Yoshida-4 with merged kicks (three force evaluations per
//! step, the last force reused), storing `t`, `q`, `p` and the energy of every sample in
//! preallocated vectors; the potential of a stored sample comes from its step's last force
//! evaluation (the same `q`), as a careful hand-written loop would take it, and each force
//! loop is written without values carried from one site to the next, so it vectorizes. The
//! library must come within 1.25x of these. The force and energy are closures, which
//! monomorphization inlines exactly like hand-written code. The trig-bound loops use libm
//! unless `PHYSICSKIT_PLAIN_SLICE_TRIG` is set (see [`case`]).

use physicskit::classical::core::trig::{sin_into_scaled, sin_into_sum_cos};

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

/// Yoshida-4 over `n` steps of `dt` from `(q0, p0)`. `force(q, f, potential)` writes `-dV/dq`
/// into `f` and, when `potential` is true, returns `V(q)` (anything otherwise); `kinetic(p)`
/// is `T(p)`.
pub fn yoshida4(
    q0: &[f64],
    p0: &[f64],
    mass_inv: f64,
    dt: f64,
    n: usize,
    force: impl Fn(&[f64], &mut [f64], bool) -> f64,
    kinetic: impl Fn(&[f64]) -> f64,
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
    let record = |out: &mut Trajectory, t: f64, q: &[f64], p: &[f64], v: f64| {
        out.t.push(t);
        out.q.extend_from_slice(q);
        out.p.extend_from_slice(p);
        out.energy.push(kinetic(p) + v);
    };
    let v = force(&q, &mut f, true);
    record(&mut out, 0.0, &q, &p, v);
    let kicks = [
        0.5 * W1 * dt,
        0.5 * (W1 + W0) * dt,
        0.5 * (W0 + W1) * dt,
        0.5 * W1 * dt,
    ];
    let drifts = [W1 * dt * mass_inv, W0 * dt * mass_inv, W1 * dt * mass_inv];
    for step in 1..=n {
        let mut v = 0.0;
        for i in 0..3 {
            for j in 0..d {
                p[j] += kicks[i] * f[j];
                q[j] += drifts[i] * p[j];
            }
            v = force(&q, &mut f, i == 2);
        }
        for j in 0..d {
            p[j] += kicks[3] * f[j];
        }
        record(&mut out, step as f64 * dt, &q, &p, v);
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

/// `sum p_i^2 / 2` (unit masses).
fn half_sum_squares(p: &[f64]) -> f64 {
    0.5 * p.iter().map(|x| x * x).sum::<f64>()
}

/// A plain loop: `(q0, p0, steps, dt)` to the stored trajectory.
pub type Plain = fn(&[f64], &[f64], usize, f64) -> Trajectory;

/// The plain-loop version of a separable workload, by the workload's name, run from the
/// workload's initial condition ([`Workload::start`](crate::workloads::Workload::start));
/// `None` for non-separable workloads. The forces, with the table's parameters, are written
/// here by hand.
pub fn case(name: &str) -> Option<Plain> {
    Some(match name {
        "projectile" => |q0, p0, n, dt| {
            let g = 9.81;
            yoshida4(
                q0,
                p0,
                1.0,
                dt,
                n,
                |q, f, _| {
                    f[0] = 0.0;
                    f[1] = -g;
                    g * q[1]
                },
                half_sum_squares,
            )
        },
        "kepler" => |q0, p0, n, dt| kepler(q0, p0, 0.0, n, dt),
        "kepler_pn" => |q0, p0, n, dt| kepler(q0, p0, 0.01, n, dt),
        "henon_heiles" => |q0, p0, n, dt| {
            yoshida4(
                q0,
                p0,
                1.0,
                dt,
                n,
                |q, f, _| {
                    f[0] = -q[0] - 2.0 * q[0] * q[1];
                    f[1] = -q[1] - q[0] * q[0] + q[1] * q[1];
                    0.5 * (q[0] * q[0] + q[1] * q[1]) + q[0] * q[0] * q[1]
                        - q[1] * q[1] * q[1] / 3.0
                },
                half_sum_squares,
            )
        },
        "swarm" => |q0, p0, n, dt| {
            if slice_trig() {
                unit_masses(q0, p0, dt, n, |q, f, potential| {
                    if potential {
                        -sin_into_sum_cos(q, f, -1.0)
                    } else {
                        sin_into_scaled(q, f, -1.0);
                        0.0
                    }
                })
            } else {
                unit_masses(q0, p0, dt, n, |q, f, potential| {
                    if potential {
                        let mut v = 0.0;
                        for (fi, qi) in f.iter_mut().zip(q) {
                            let (s, c) = qi.sin_cos();
                            *fi = -s;
                            v -= c;
                        }
                        v
                    } else {
                        for (fi, qi) in f.iter_mut().zip(q) {
                            *fi = -qi.sin();
                        }
                        0.0
                    }
                })
            }
        },
        "harmonic_chain" => |q0, p0, n, dt| {
            yoshida4(
                q0,
                p0,
                1.0,
                dt,
                n,
                |q, f, potential| fixed_chain_force(q, f, 0.0, potential),
                half_sum_squares,
            )
        },
        "fput" => |q0, p0, n, dt| {
            yoshida4(
                q0,
                p0,
                1.0,
                dt,
                n,
                |q, f, potential| fixed_chain_force(q, f, 0.7, potential),
                half_sum_squares,
            )
        },
        "sine_gordon" => |q0, p0, n, dt| {
            if slice_trig() {
                unit_masses(q0, p0, dt, n, |q, f, potential| {
                    let onsite = if potential {
                        q.len() as f64 - sin_into_sum_cos(q, f, 1.0)
                    } else {
                        sin_into_scaled(q, f, 1.0);
                        0.0
                    };
                    sine_gordon_bonds(q, f, potential) + onsite
                })
            } else {
                unit_masses(q0, p0, dt, n, |q, f, potential| {
                    let mut onsite = 0.0;
                    if potential {
                        for (fi, qi) in f.iter_mut().zip(q) {
                            let (s, c) = qi.sin_cos();
                            *fi = s;
                            onsite += 1.0 - c;
                        }
                    } else {
                        for (fi, qi) in f.iter_mut().zip(q) {
                            *fi = qi.sin();
                        }
                    }
                    sine_gordon_bonds(q, f, potential) + onsite
                })
            }
        },
        _ => return None,
    })
}

fn kepler(q0: &[f64], p0: &[f64], c_pn: f64, n: usize, dt: f64) -> Trajectory {
    yoshida4(
        q0,
        p0,
        1.0,
        dt,
        n,
        |q, f, _| {
            let inv = 1.0 / (q[0] * q[0] + q[1] * q[1]).sqrt();
            let inv3 = inv * inv * inv;
            let s = -inv3 + 3.0 * c_pn * inv3 * inv * inv;
            f[0] = s * q[0];
            f[1] = s * q[1];
            -inv + c_pn * inv3
        },
        half_sum_squares,
    )
}

/// Yoshida-4 on unit masses (`T = sum p^2 / 2`) with the given force: the swarm and the
/// sine-Gordon chain.
fn unit_masses(
    q0: &[f64],
    p0: &[f64],
    dt: f64,
    n: usize,
    force: impl Fn(&[f64], &mut [f64], bool) -> f64,
) -> Trajectory {
    yoshida4(q0, p0, 1.0, dt, n, force, half_sum_squares)
}

/// Turns `f = sin q` into `F_i = (q_{i-1} - q_i) + (q_{i+1} - q_i) - sin q_i` with free ends
/// (the ends outside the loop, so it vectorizes); returns the springs' energy
/// `sum (q_{i+1} - q_i)^2 / 2` when `potential`, else 0.
fn sine_gordon_bonds(q: &[f64], f: &mut [f64], potential: bool) -> f64 {
    let n = q.len();
    for i in 1..n - 1 {
        f[i] = (q[i - 1] - q[i]) + (q[i + 1] - q[i]) - f[i];
    }
    f[0] = (q[1] - q[0]) - f[0];
    f[n - 1] = (q[n - 2] - q[n - 1]) - f[n - 1];
    if potential {
        q.windows(2)
            .map(|w| 0.5 * (w[1] - w[0]) * (w[1] - w[0]))
            .sum()
    } else {
        0.0
    }
}

/// `F_i = phi'(r_i) - phi'(r_{i-1})`, `phi'(r) = r + beta r^3`, `r_i = q_{i+1} - q_i`, walls at
/// both ends, each bond computed for both its sites (no value carried along, so the loop
/// vectorizes); returns `sum phi(r)`, `phi(r) = r^2/2 + beta r^4/4`, when `potential`, else 0.
fn fixed_chain_force(q: &[f64], f: &mut [f64], beta: f64, potential: bool) -> f64 {
    let n = q.len();
    let dphi = |r: f64| r + beta * r * r * r;
    for i in 1..n - 1 {
        f[i] = dphi(q[i + 1] - q[i]) - dphi(q[i] - q[i - 1]);
    }
    f[0] = dphi(q[1] - q[0]) - dphi(q[0]);
    f[n - 1] = dphi(-q[n - 1]) - dphi(q[n - 1] - q[n - 2]);
    if potential {
        let phi = |r: f64| 0.5 * r * r + 0.25 * beta * r * r * r * r;
        phi(q[0]) + phi(q[n - 1]) + q.windows(2).map(|w| phi(w[1] - w[0])).sum::<f64>()
    } else {
        0.0
    }
}
