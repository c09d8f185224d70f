//! Lattice chains: normal modes, harmonic invariants, FPUT recurrence, sine-Gordon kinks.

use std::f64::consts::PI;

use physicskit::classical::systems::{FPUTChain, HarmonicChain, NormalModes, SineGordonChain};
use physicskit::classical::{DynamicalSystem, HamiltonianSystem, IntegrateOptions, Method};

use crate::checks::{check_force_against_potential, fit_slope};
use crate::fixtures::pseudo_random;

#[test]
fn forces_are_minus_gradients() {
    // Every length the force code treats apart: one site (both ends), two (no interior
    // site), three (one), and longer chains whose interior loop has vector remainders.
    for n in [1, 2, 3, 7, 20] {
        let q = pseudo_random(n, 1);
        let p = vec![0.0; n];
        check_force_against_potential(&HarmonicChain::new(&q, &p, 1.5, 2.0).unwrap(), &q);
        let mut fput = FPUTChain::new(n, 1.5, 2.0, 0.7, 1, 0.3).unwrap();
        let mut state = q.clone();
        state.extend(&p);
        fput.reset(Some(&state), 0.0).unwrap();
        check_force_against_potential(&fput, &q);
        let q_big: Vec<f64> = q.iter().map(|x| 8.0 * x).collect();
        check_force_against_potential(
            &SineGordonChain::new(n, 1.5, 2.0, None, None).unwrap(),
            &q_big,
        );
    }
}

#[test]
fn sine_modes_are_eigenvectors_with_the_documented_frequencies() {
    // Independent of the transform: the pure mode q_i = sin(i j pi/(N+1)) must satisfy
    // F = -m omega_j^2 q (the eigen-equation of the stiffness matrix).
    let (n, m, k) = (9, 2.0, 3.0);
    let chain = HarmonicChain::new(&vec![0.0; n], &vec![0.0; n], m, k).unwrap();
    let omega = chain.normal_mode_frequencies().to_vec();
    let mut force = vec![0.0; n];
    for j in 1..=n {
        let q: Vec<f64> = (1..=n)
            .map(|i| (PI * (i * j) as f64 / (n + 1) as f64).sin())
            .collect();
        chain.force(&q, 0.0, &mut force).unwrap();
        let w2 = omega[j - 1] * omega[j - 1];
        for i in 0..n {
            assert!((force[i] + m * w2 * q[i]).abs() < 1e-13);
        }
        // The transform picks out exactly that mode, amplitude sqrt((N+1)/2).
        let (big_q, big_p) = chain.normal_mode_coords(&q, &vec![0.0; n]).unwrap();
        for (l, &ql) in big_q.iter().enumerate() {
            let expected = if l + 1 == j {
                ((n + 1) as f64 / 2.0).sqrt()
            } else {
                0.0
            };
            assert!((ql - expected).abs() < 1e-13);
        }
        assert!(big_p.iter().all(|x| x.abs() < 1e-15));
    }
}

#[test]
fn modal_energies_sum_to_the_harmonic_energy() {
    // Orthonormal transform (Parseval): sum_j E_j = H for the harmonic chain, at any state.
    let (q, p) = (pseudo_random(12, 3), pseudo_random(12, 4));
    let chain = HarmonicChain::new(&q, &p, 0.7, 1.9).unwrap();
    let total: f64 = chain.modal_energies(&q, &p).unwrap().iter().sum();
    assert!((total - chain.current_energy()).abs() < 1e-14 * total);
}

#[test]
fn harmonic_chain_modal_energies_are_constant() {
    let n = 16;
    let (q, p) = (pseudo_random(n, 5), pseudo_random(n, 6));
    let mut chain = HarmonicChain::new(&q, &p, 1.0, 1.0).unwrap();
    let e0 = chain.modal_energies(&q, &p).unwrap();
    let total: f64 = e0.iter().sum();
    let res = chain
        .integrate_with(
            (0.0, 50.0),
            1e-3,
            Method::Yoshida4,
            IntegrateOptions::stride(500),
        )
        .unwrap();
    let (qs, ps) = (res.q().unwrap(), res.p().unwrap());
    let mut worst = 0.0_f64;
    for i in 0..res.n_samples() {
        let e = chain
            .modal_energies(&qs.row(i).to_vec(), &ps.row(i).to_vec())
            .unwrap();
        for (a, b) in e.iter().zip(&e0) {
            worst = worst.max((a - b).abs() / total);
        }
    }
    println!("harmonic chain: worst modal energy change / total {worst:e}");
    // The bound. Yoshida4 is a linear map on each mode whose modified energy differs
    // from E_j by O((omega_j dt)^4) ~ (2e-3)^4 ~ 2e-11 for the fastest mode (omega < 2).
    assert!(worst < 1e-10);
}

#[test]
fn single_mode_oscillates_at_its_frequency() {
    let (n, m, k, mode) = (16, 1.3, 0.8, 3);
    let q: Vec<f64> = (1..=n)
        .map(|i| 0.1 * (PI * (i * mode) as f64 / (n + 1) as f64).sin())
        .collect();
    let mut chain = HarmonicChain::new(&q, &vec![0.0; n], m, k).unwrap();
    let omega = chain.normal_mode_frequencies()[mode - 1];
    let res = chain
        .integrate((0.0, 200.0), 1e-2, Method::Yoshida4)
        .unwrap();
    let (qs, ps) = (res.q().unwrap(), res.p().unwrap());
    // Q(t) = Q0 cos(omega t): fit the phase of (Q, P/(m omega)) rotating at -omega.
    let mut phases = Vec::new();
    let mut previous = 0.0_f64;
    for i in 0..res.n_samples() {
        let (big_q, big_p) = chain
            .normal_mode_coords(&qs.row(i).to_vec(), &ps.row(i).to_vec())
            .unwrap();
        let mut phase = (-big_p[mode - 1] / (m * omega)).atan2(big_q[mode - 1]);
        while phase - previous > PI {
            phase -= 2.0 * PI;
        }
        while phase - previous < -PI {
            phase += 2.0 * PI;
        }
        previous = phase;
        phases.push(phase);
    }
    let measured = fit_slope(res.t.as_slice().unwrap(), &phases);
    let rel = (measured - omega).abs() / omega;
    println!("harmonic chain mode {mode}: omega {omega}, measured {measured}, rel {rel:e}");
    // The bound; Yoshida4's phase error is O((omega dt)^4) ~ 1e-9.
    assert!(rel < 1e-4);
}

#[test]
fn fput_energy_drift_over_1e5_steps() {
    let mut chain = FPUTChain::new(32, 1.0, 1.0, 0.7, 1, 0.5).unwrap();
    let res = chain
        .integrate_with(
            (0.0, 5000.0),
            0.05,
            Method::Yoshida4,
            IntegrateOptions::stride(100),
        )
        .unwrap();
    let drift = res.max_relative_energy_error().unwrap();
    println!("fput: relative energy drift over 1e5 steps {drift:e}");
    // The bound; Yoshida4's bounded error (omega_max dt)^4 ~ 1e-4 times a small
    // constant, measured ~4e-11 because the energy sits in the slow mode 1.
    assert!(drift < 1e-6);
}

/// Slow envelope of the mode-3 energy fraction `E_3/E_1(0)`: maxima over consecutive windows
/// of `window` time units, with the window centres. Samples are one time unit apart.
fn fput_mode3_envelope(dt: f64, t_end: f64, window: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut chain = FPUTChain::new(32, 1.0, 1.0, 0.7, 1, 0.5).unwrap();
    let e0 = chain.modal_energies(chain.q(), chain.p()).unwrap()[0];
    let stride = (1.0 / dt).round() as usize;
    let res = chain
        .integrate_with(
            (0.0, t_end),
            dt,
            Method::Yoshida4,
            IntegrateOptions::stride(stride),
        )
        .unwrap();
    let (qs, ps) = (res.q().unwrap(), res.p().unwrap());
    let mut e1 = Vec::new();
    let mut e3 = Vec::new();
    for i in 0..res.n_samples() {
        let e = chain
            .modal_energies(&qs.row(i).to_vec(), &ps.row(i).to_vec())
            .unwrap();
        e1.push(e[0] / e0);
        e3.push(e[2] / e0);
    }
    let centres = (0..e3.len() / window)
        .map(|w| res.t[w * window + window / 2])
        .collect();
    let env = e3
        .chunks_exact(window)
        .map(|c| c.iter().copied().fold(0.0, f64::max))
        .collect();
    (centres, env, e1)
}

/// Recurrence time: the vertex of a least-squares parabola through the envelope around its
/// first minimum after the transfer peak.
fn recurrence_time(centres: &[f64], env: &[f64]) -> (f64, usize) {
    let peak = (0..env.len()).fold(0, |b, i| if env[i] > env[b] { i } else { b });
    let min = (peak..env.len()).fold(peak, |b, i| if env[i] < env[b] { i } else { b });
    // +-10 windows: the envelope ~ sin^2 is close to its quadratic Taylor form there.
    let lo = min.saturating_sub(10);
    let hi = (min + 10).min(env.len() - 1);
    let (x, y) = (&centres[lo..=hi], &env[lo..=hi]);
    // Fit y = a + b u + c u^2 with u = x - x_min (normal equations, 3x3 by Cramer's rule).
    let x0 = centres[min];
    let mut s = [0.0_f64; 5];
    let mut r = [0.0_f64; 3];
    for (&xi, &yi) in x.iter().zip(y) {
        let u = (xi - x0) / 1000.0;
        for (k, sk) in s.iter_mut().enumerate() {
            *sk += u.powi(k as i32);
        }
        for (k, rk) in r.iter_mut().enumerate() {
            *rk += yi * u.powi(k as i32);
        }
    }
    let det3 = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let a = [[s[0], s[1], s[2]], [s[1], s[2], s[3]], [s[2], s[3], s[4]]];
    let d = det3(a);
    let mut ab = a;
    let mut ac = a;
    for k in 0..3 {
        ab[k][1] = r[k];
        ac[k][2] = r[k];
    }
    let (b, c) = (det3(ab) / d, det3(ac) / d);
    (x0 - 1000.0 * b / (2.0 * c), peak)
}

/// The FPUT recurrence of mode 1 at n = 32, beta = 0.7, amplitude 0.5.
///
/// At this amplitude the chain is weakly non-linear (beta r^2 ~ 2e-3): mode 1 feeds mode 3
/// through the near-resonance 3 omega_1 ~ omega_3 (the only strong channel; even modes are
/// never excited by symmetry), and the transferred energy beats back with the period of the
/// two-mode resonance, `T_r = 2 pi / (3 omega_1' - omega_3')`. The linear detuning
/// `3 omega_1 - omega_3 = 8.62e-4` is shifted by mode 1's Duffing self-shift
/// `domega_1 = 9 beta omega_1^3 A^2 / 32` (reduce H_4 on the pure mode to
/// `(3/8) beta omega_1^4 Q^4/(N+1)`; Landau & Lifshitz, *Mechanics* §28) and by the
/// cross-shift of mode 3, `domega_3 = (3/8) beta A^2 omega_1^2 omega_3` (average of
/// `(3/2) beta sum r_1^2 r_3^2` over mode 1's phase). Both are derived by hand, independently
/// of the code. The measured recurrence must match that prediction, and a reference run at
/// dt/4 must give the same time (integration error far below the tolerance).
#[test]
fn fput_recurrence_time_and_return_fraction() {
    let (n, beta, amp) = (32.0_f64, 0.7_f64, 0.5_f64);
    let w = |j: f64| 2.0 * (j * PI / (2.0 * (n + 1.0))).sin();
    let (w1, w3) = (w(1.0), w(3.0));
    let dw1 = 9.0 * beta * w1.powi(3) * amp * amp / 32.0;
    let dw3 = 3.0 / 8.0 * beta * amp * amp * w1 * w1 * w3;
    let predicted = 2.0 * PI / (3.0 * (w1 + dw1) - (w3 + dw3));

    let window = 100;
    let (centres, env, e1) = fput_mode3_envelope(0.05, 9000.0, window);
    let (t_r, peak) = recurrence_time(&centres, &env);
    let (centres_ref, env_ref, _) = fput_mode3_envelope(0.0125, 9000.0, window);
    let (t_ref, _) = recurrence_time(&centres_ref, &env_ref);

    // Return fraction: how much of the energy that left mode 1 has come back at T_r, and
    // the mode-1 fraction there (its deepest point is at T_r/2).
    let at = |t: f64| ((t / window as f64) as usize).min(env.len() - 1);
    let returned = 1.0 - env[at(t_r)] / env[peak];
    let deepest = e1.iter().copied().fold(f64::INFINITY, f64::min);
    let e1_back = e1[(t_r as usize).saturating_sub(50)..(t_r as usize + 50).min(e1.len())]
        .iter()
        .copied()
        .fold(0.0, f64::max);
    println!(
        "fput recurrence: T_r = {t_r:.1} (dt/4 reference {t_ref:.1}, two-mode theory \
         {predicted:.1}); transferred at peak {:.3e} of E_1(0); deepest E_1 fraction \
         {deepest:.5}; E_1 fraction at T_r {e1_back:.6}; returned fraction {returned:.5}",
        env[peak]
    );
    // Integration error: the dt/4 run agrees to the fit's resolution (~0.1% of T_r).
    assert!((t_r - t_ref).abs() < 2e-3 * t_ref);
    // Theory: the two-mode reduction neglects O(beta A^2 omega^2) corrections to the shifts
    // and leakage to mode 5 (4e-4 of the exchange); measured agreement is 0.2%, and 1% allows
    // for the envelope fit, whose windows are 100 of ~7650 time units.
    assert!((t_r - predicted).abs() < 0.01 * predicted);
    // The exchange is small but real (mode 3 reaches > 1e-4 of E_1(0)) and nearly all of it
    // comes back: the two-mode beat returns completely, leakage to higher modes is ~1e-3 of it.
    assert!(env[peak] > 1e-4);
    assert!(returned > 0.99);
    assert!(e1_back > 1.0 - 1e-4 && deepest < 1.0 - 5e-4);
}

fn kink_centre(q: &[f64], width: f64, gamma: f64) -> f64 {
    // Invert the profile q = 4 atan(exp(gamma (x - c)/width)) at the site closest to q = pi:
    // c = i - (width/gamma) ln tan(q_i/4), exact for the travelling solution.
    let i = (0..q.len())
        .min_by(|&a, &b| (q[a] - PI).abs().total_cmp(&(q[b] - PI).abs()))
        .unwrap();
    i as f64 - width / gamma * (q[i] / 4.0).tan().ln()
}

/// Boosted kinks on a chain fine enough for the continuum claims: `m = k = 9` keeps the wave
/// speed `sqrt(k/m) = 1` site per unit time and makes the soliton `width = sqrt(k) = 3` sites
/// wide. Rescaling `x' = x/3`, `t' = t/3` maps `9 q_tt = 9 q_xx - sin q` onto the unit
/// sine-Gordon equation, so the exact travelling kink moves at `v` and has energy
/// `8 gamma * 3` (the `8 gamma` of the unit equation times the lattice spacing 1/3 in `x'`).
///
/// On the unit lattice (`m = k = 1`, width 1 site) the continuum claims do not hold: the
/// discrete gradient energy is short by `(1/24) int q_xx^2 = 1/9` (1.4%, tested below) and
/// the Peierls–Nabarro relief slows a v = 0.5 kink to ~0.27 within 160 time units. The issue's
/// 1% bounds are therefore tested in the continuum regime they describe.
#[test]
fn sine_gordon_kinks_travel_at_their_velocity_and_keep_their_energy() {
    let n = 300;
    let (mk, width) = (9.0_f64, 3.0_f64);
    for v in [0.2_f64, 0.5] {
        let gamma = 1.0 / (1.0 - v * v).sqrt();
        let (q0, mut p0) = SineGordonChain::kink(n, 80.0, width, v, 1).unwrap();
        // kink() returns dq/dt; the momentum is m dq/dt.
        p0.iter_mut().for_each(|p| *p *= mk);
        let mut chain = SineGordonChain::new(n, mk, mk, Some(&q0), Some(&p0)).unwrap();
        let continuum = 8.0 * gamma * width;
        let energy = chain.current_energy();
        let e_rel = (energy / continuum - 1.0).abs();
        let t_end = 160.0;
        let res = chain
            .integrate_with(
                (0.0, t_end),
                0.02,
                Method::Yoshida4,
                IntegrateOptions::stride(50),
            )
            .unwrap();
        let qs = res.q().unwrap();
        let centres: Vec<f64> = (0..res.n_samples())
            .map(|i| kink_centre(&qs.row(i).to_vec(), width, gamma))
            .collect();
        let speed = fit_slope(res.t.as_slice().unwrap(), &centres);
        let speed_err = (speed - v).abs() / v;
        // Shape: the final profile against the exact travelling kink at the fitted centre.
        let c_end = centres[centres.len() - 1];
        let last = qs.row(res.n_samples() - 1);
        let shape_err = (0..n)
            .map(|i| (last[i] - 4.0 * (gamma * (i as f64 - c_end) / width).exp().atan()).abs())
            .fold(0.0, f64::max);
        let drift = res.max_relative_energy_error().unwrap();
        println!(
            "sine-gordon v={v}: energy {energy} vs continuum {continuum} (rel {e_rel:e}), \
             speed {speed} (rel err {speed_err:e}), shape error {shape_err:e} rad, \
             energy drift {drift:e}"
        );
        // The bounds: energy within 1% of the continuum value (lattice correction
        // (1/24) int q_xx^2 / 8 ~ 0.15% at width 3), speed within 1% (measured ~0.5%).
        assert!(e_rel < 0.01);
        assert!(speed_err < 0.01);
        // Shape kept: within 0.05 rad (of the 2 pi step) of the exact kink; radiation from the
        // continuum initial data on the lattice is ~1e-2 rad.
        assert!(shape_err < 0.05);
        // Yoshida4 at dt = 0.02 with omega_max = sqrt(1 + 4 k/m)/... ~ 2: bounded ~1e-9.
        assert!(drift < 1e-6);
    }
}

/// On the unit lattice the static kink's energy is the continuum 8 minus the lattice
/// correction of the gradient term: `sum (q_{i+1} - q_i)^2 = int q_x^2 - (1/12) int q_xx^2 +
/// O(h^4)` (Euler–Maclaurin at the bond midpoints) with `int q_xx^2 = 8/3` for
/// `q = 4 atan(exp x)`, i.e. `E = 8 - 1/9`.
#[test]
fn sine_gordon_static_kink_energy_on_the_unit_lattice() {
    let (q0, p0) = SineGordonChain::kink(100, 50.0, 1.0, 0.0, -1).unwrap();
    let chain = SineGordonChain::new(100, 1.0, 1.0, Some(&q0), Some(&p0)).unwrap();
    let energy = chain.current_energy();
    println!(
        "unit-lattice static antikink energy {energy} vs 8 - 1/9 = {}",
        8.0 - 1.0 / 9.0
    );
    // The O(h^4) remainder ((1/360)-scale terms) is ~1e-2 absolute: 2e-3 relative.
    assert!((energy - (8.0 - 1.0 / 9.0)).abs() < 2e-3 * 8.0);
    assert!(
        q0[0] > -0.1 && q0[99] < -6.0,
        "antikink steps from 0 down to -2 pi"
    );
}

/// `boosted_kink` on a chain whose wave speed is not 1: `m = 4`, `k = 36` gives `c = 3` sites
/// per unit time and width `sqrt(k) = 6`. A kink launched at 1.5 sites per unit time (beta =
/// 1/2, gamma = 2/sqrt(3)) must move at 1.5: the same continuum regime as the test above (wide
/// kink), so the same 1% bound.
#[test]
fn boosted_kinks_move_at_their_velocity_on_any_chain() {
    let (n, m, k) = (400, 4.0_f64, 36.0_f64);
    let (c, width, v) = ((k / m).sqrt(), k.sqrt(), 1.5_f64);
    let gamma = 1.0 / (1.0 - (v / c).powi(2)).sqrt();
    let (q0, p0) = SineGordonChain::boosted_kink(n, m, k, 100.0, width, v, 1).unwrap();
    let mut chain = SineGordonChain::new(n, m, k, Some(&q0), Some(&p0)).unwrap();
    let t1 = 60.0;
    let r = chain.integrate((0.0, t1), 0.01, Method::Yoshida4).unwrap();
    let end = r.final_state();
    let moved = kink_centre(&end.as_slice().unwrap()[..n], width, gamma) - 100.0;
    assert!(
        (moved - v * t1).abs() < 0.01 * v * t1,
        "moved {moved}, expected {}",
        v * t1
    );
    // With m = k = 1 it is the spec's kink() exactly (p = m dq/dt with m = c = 1).
    assert_eq!(
        SineGordonChain::boosted_kink(20, 1.0, 1.0, 7.5, 1.0, 0.4, -1).unwrap(),
        SineGordonChain::kink(20, 7.5, 1.0, 0.4, -1).unwrap()
    );
    // Faster than the wave speed is refused.
    assert!(SineGordonChain::boosted_kink(n, m, k, 100.0, width, 3.0, 1).is_err());
    // The pair is the sum of a right-moving kink and a left-moving antikink.
    let (qp, pp) = SineGordonChain::kink_antikink(n, m, k, 100.0, 300.0, width, v).unwrap();
    let (qa, pa) = SineGordonChain::boosted_kink(n, m, k, 300.0, width, -v, -1).unwrap();
    // Bit for bit: the same additions in the same order.
    for i in 0..n {
        assert_eq!(qp[i].to_bits(), (q0[i] + qa[i]).to_bits());
        assert_eq!(pp[i].to_bits(), (p0[i] + pa[i]).to_bits());
    }
}
