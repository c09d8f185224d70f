//! The periodic Toda lattice: force and Jacobian against the potential, the Lax eigenvalues
//! against trace identities computed from `(q, p)` directly, their conservation under
//! yoshida4, the two-particle closed-form solution, and the energy per particle.

use physicskit::classical::systems::TodaLattice;
use physicskit::classical::{
    DynamicalSystem, Error, HamiltonianSystem, IntegrateOptions, Method, Sampling,
};

use crate::checks::check_force_against_potential;
use crate::fixtures::pseudo_random;

fn scaled(v: Vec<f64>, s: f64) -> Vec<f64> {
    v.into_iter().map(|x| s * x).collect()
}

fn state_of(q: &[f64], p: &[f64]) -> Vec<f64> {
    q.iter().chain(p).copied().collect()
}

#[test]
fn force_and_jacobian_are_derivatives_of_the_potential() {
    // n = 2 (both bonds join the same pair), 3 (every pair is a neighbour) and 7; stretches of
    // order 1 / b, where the exponential is far from its linearization.
    for n in [2, 3, 7] {
        let q = scaled(pseudo_random(n, 3), 2.0);
        let toda = TodaLattice::new(&q, &vec![0.0; n], 0.7, 1.3).unwrap();
        check_force_against_potential(&toda, &q);
    }
}

#[test]
fn fused_potential_is_the_potential_bit_for_bit() {
    // The splitting integrators store T + the fused potential as the sample's energy; it must
    // be exactly what `energy` computes.
    let q = scaled(pseudo_random(9, 5), 3.0);
    let toda = TodaLattice::new(&q, &[0.1; 9], 1.2, 0.8).unwrap();
    let mut f1 = vec![0.0; 9];
    let mut f2 = vec![0.0; 9];
    toda.force(&q, 0.0, &mut f1).unwrap();
    let v = toda.force_and_potential(&q, 0.0, &mut f2).unwrap();
    assert_eq!(
        v.map(f64::to_bits),
        Some(toda.potential_energy(&q).to_bits())
    );
    assert_eq!(f1, f2);
}

/// `(tr L, tr L^2, tr L^3)` from `q, p` directly, by counting the closed walks of length 1, 2
/// and 3 on the ring: with `c_i = sqrt(a/b) exp(-b (q_{i+1} - q_i)/2)` (indices mod n),
/// `tr L = sum p_i`, `tr L^2 = sum p_i^2 + 2 sum c_i^2`,
/// `tr L^3 = sum p_i^3 + 3 sum c_i^2 (p_i + p_{i+1}) (+ 6 c_1 c_2 c_3 for n = 3, the walks
/// once around the triangle)`, for `n >= 3`.
fn traces(q: &[f64], p: &[f64], a: f64, b: f64) -> [f64; 3] {
    let n = q.len();
    assert!(n >= 3);
    let c: Vec<f64> = (0..n)
        .map(|i| (a / b).sqrt() * (-0.5 * b * (q[(i + 1) % n] - q[i])).exp())
        .collect();
    let t1 = p.iter().sum();
    let t2 = p.iter().map(|x| x * x).sum::<f64>() + 2.0 * c.iter().map(|x| x * x).sum::<f64>();
    let mut t3 = p.iter().map(|x| x * x * x).sum::<f64>();
    for i in 0..n {
        t3 += 3.0 * c[i] * c[i] * (p[i] + p[(i + 1) % n]);
    }
    if n == 3 {
        t3 += 6.0 * c[0] * c[1] * c[2];
    }
    [t1, t2, t3]
}

#[test]
fn lax_eigenvalues_satisfy_the_trace_identities() {
    // Power sums of the eigenvalues against the traces of L computed from (q, p) without the
    // library's matrix: for n = 3 the three power sums determine the three eigenvalues, so
    // this checks the spectrum completely; for n = 5 it checks three of five invariants
    // (the eigensolver is then the one code path not re-derived here). Rounding: the
    // symmetric QR eigensolver is backward stable, eigenvalues within ~n eps |L| (~1e-15 for
    // |L| ~ 3), and the power sums of degree 3 amplify that by 3 |lambda|^2 ~ 30: 1e-12 of the
    // scale leaves a margin of ~30 while any wrong element of L is O(1).
    for (n, a, b, seed) in [(3, 1.0, 1.0, 11), (3, 0.6, 2.0, 12), (5, 1.7, 0.4, 13)] {
        let q = scaled(pseudo_random(n, seed), 2.0);
        let p = scaled(pseudo_random(n, seed + 100), 3.0);
        let toda = TodaLattice::new(&q, &p, a, b).unwrap();
        let lambda = toda.conserved_quantities(None).unwrap();
        assert!(lambda.windows(2).all(|w| w[0] <= w[1]), "not sorted");
        let sums = [1, 2, 3].map(|k| lambda.iter().map(|l| l.powi(k)).sum::<f64>());
        let expected = traces(&q, &p, a, b);
        let scale = lambda.iter().fold(0.0_f64, |m, l| m.max(l.abs()));
        for k in 0..3 {
            let tol = 1e-12 * scale.powi(k as i32 + 1).max(1.0);
            assert!(
                (sums[k] - expected[k]).abs() < tol,
                "n = {n}: tr L^{} = {} from q, p but {} from the eigenvalues",
                k + 1,
                expected[k],
                sums[k]
            );
        }
        // tr L^2 = 2 H: the normalization of the module documentation.
        assert!((sums[1] - 2.0 * toda.current_energy()).abs() < 1e-12 * scale * scale);
    }
}

#[test]
fn two_particle_lax_matrix_sums_the_two_bonds() {
    // For n = 2 the eigenvalues are (p1 + p2)/2 -+ sqrt(((p1 - p2)/2)^2 + (c1 + c2)^2), and
    // their squares sum to 2 H + 4 a/b (module documentation).
    let (a, b) = (0.8, 1.5);
    let (q, p) = ([0.3, -0.9], [0.7, -0.2]);
    let toda = TodaLattice::new(&q, &p, a, b).unwrap();
    let lambda = toda.conserved_quantities(None).unwrap();
    let x = q[1] - q[0];
    let c = (a / b).sqrt() * ((-0.5 * b * x).exp() + (0.5 * b * x).exp());
    let mean = 0.5 * (p[0] + p[1]);
    let half = (0.25 * (p[0] - p[1]).powi(2) + c * c).sqrt();
    // A 2x2 symmetric eigenproblem: a few ulps of |L| ~ 3.
    assert!((lambda[0] - (mean - half)).abs() < 1e-14 * 4.0);
    assert!((lambda[1] - (mean + half)).abs() < 1e-14 * 4.0);
    let sq = lambda[0] * lambda[0] + lambda[1] * lambda[1];
    assert!((sq - (2.0 * toda.current_energy() + 4.0 * a / b)).abs() < 1e-13);
}

#[test]
fn every_lax_eigenvalue_is_conserved_over_1e5_yoshida4_steps() {
    // Six particles, displacements up to 1.5/b and momenta up to 2.5: bond energies from
    // e^{-1.5} to e^{+1.5} of a/b, far from the harmonic regime, with the total energy spread
    // unevenly. Yoshida-4 is symplectic, and for an integrable system it conserves every
    // action to O(dt^4) without drift (backward error analysis: it follows the exact flow of a
    // nearby integrable Hamiltonian, Hairer, Lubich & Wanner, Geometric Numerical Integration,
    // ch. X); at dt = 1e-3 and frequencies ~2 that is ~(2e-3)^4 ~ 1e-11 of the scale, and the
    // rounding random walk of 1e5 steps adds ~sqrt(1e5) 1e-16 ~ 3e-14. Hence 1e-10 of the
    // spectral scale is reachable with a margin of ~10 (measured: 9.5e-12), and a
    // non-conserved quantity (any single particle energy) moves by O(1).
    let n = 6;
    let q = scaled(pseudo_random(n, 21), 3.0);
    let p = scaled(pseudo_random(n, 22), 5.0);
    let mut toda = TodaLattice::new(&q, &p, 1.0, 1.0).unwrap();
    let lambda0 = toda.conserved_quantities(None).unwrap();
    let scale = lambda0.iter().fold(0.0_f64, |m, l| m.max(l.abs()));
    let options = IntegrateOptions {
        sampling: Sampling::Stride(1000),
        ..IntegrateOptions::default()
    };
    let r = toda
        .integrate_with((0.0, 100.0), 1e-3, Method::Yoshida4, options)
        .unwrap();
    assert_eq!(r.t.len(), 101);
    let mut worst = 0.0_f64;
    for row in r.y.rows() {
        let lambda = toda
            .conserved_quantities(Some(row.as_slice().unwrap()))
            .unwrap();
        for (l, l0) in lambda.iter().zip(&lambda0) {
            worst = worst.max((l - l0).abs() / scale);
        }
    }
    println!("Toda n = {n}: eigenvalues {lambda0:?}, worst relative drift {worst:e}");
    assert!(worst < 1e-10, "eigenvalue drift {worst:e}");
}

/// Jacobi's `cn(u, k)` by the arithmetic–geometric mean and descending Landen
/// transformation (Abramowitz & Stegun 16.4.3), written here independently of the library.
fn jacobi_cn(u: f64, k: f64) -> f64 {
    let mut a = vec![1.0];
    let mut c = vec![k];
    let mut b = (1.0 - k * k).sqrt();
    while c.last().unwrap().abs() > 1e-16 {
        let (an, bn) = (*a.last().unwrap(), b);
        a.push(0.5 * (an + bn));
        c.push(0.5 * (an - bn));
        b = (an * bn).sqrt();
    }
    let levels = a.len() - 1;
    let mut phi = 2f64.powi(levels as i32) * a[levels] * u;
    for j in (1..=levels).rev() {
        phi = 0.5 * (phi + (c[j] / a[j] * phi.sin()).asin());
    }
    phi.cos()
}

#[test]
fn two_particles_follow_the_closed_form_solution_at_fourth_order() {
    // n = 2: x = q2 - q1 obeys x'' = F2 - F1 = -4 a sinh(b x) (both bonds stretch by -+x), with
    // energy x'^2/2 + (4a/b) cosh(b x). From rest at the turning point X, u = sinh(b x/2)
    // satisfies u'^2 = 4 a b (1 + u^2)(U^2 - u^2), U = sinh(b X/2), whose solution is
    //   sinh(b x/2) = sinh(b X/2) cn(Omega t, k),
    //   Omega = 2 sqrt(a b) cosh(b X/2),   k = tanh(b X/2)
    // (harmonic limit: cn -> cos, Omega -> 2 sqrt(a b)); the centre of mass drifts at
    // (p1 + p2)/2. b X = 3 makes k = 0.905, strongly anharmonic.
    let (a, b, big_x, p_total): (f64, f64, f64, f64) = (0.8, 1.5, 2.0, 0.3);
    let omega = 2.0 * (a * b).sqrt() * (0.5 * b * big_x).cosh();
    let k = (0.5 * b * big_x).tanh();
    let u0 = (0.5 * b * big_x).sinh();
    let exact = |t: f64| -> [f64; 2] {
        let x = 2.0 / b * (u0 * jacobi_cn(omega * t, k)).asinh();
        let centre = 0.5 * p_total * t;
        [centre - 0.5 * x, centre + 0.5 * x]
    };
    // Sanity of the closed form against its own ODE at t = 0: x'' = -4 a sinh(b X).
    let h = 1e-4;
    let x_of = |t: f64| {
        let [q1, q2] = exact(t);
        q2 - q1
    };
    let xdd = (x_of(h) - 2.0 * x_of(0.0) + x_of(-h)) / (h * h);
    assert!((xdd + 4.0 * a * (b * big_x).sinh()).abs() < 1e-5 * xdd.abs());

    let t1 = 10.0; // about 3 periods (4 K(k) / Omega = 3.3)
    let error = |dt: f64| -> f64 {
        let q0 = exact(0.0);
        let p0 = [0.5 * p_total, 0.5 * p_total];
        let mut toda = TodaLattice::new(&q0, &p0, a, b).unwrap();
        let r = toda.integrate((0.0, t1), dt, Method::Yoshida4).unwrap();
        let q = r.q().unwrap();
        let mut worst = 0.0_f64;
        for (i, &t) in r.t.iter().enumerate() {
            let e = exact(t);
            worst = worst.max((q[[i, 0]] - e[0]).abs().max((q[[i, 1]] - e[1]).abs()));
        }
        worst
    };
    let (coarse, fine) = (error(0.01), error(0.005));
    let ratio = coarse / fine;
    println!("Toda n = 2 vs closed form: errors {coarse:e}, {fine:e}, ratio {ratio:.2}");
    // Order 4: halving dt divides the error by 16; 12..20 allows for the next order's share at
    // this dt while excluding order 3 (8) and 5 (32). The fine error is itself small in
    // absolute terms (measured 1.0e-6 at dt = 0.005, 1.6e-5 at 0.01), so the comparison is not
    // between two wrong curves.
    assert!((12.0..20.0).contains(&ratio), "ratio {ratio}");
    assert!(fine < 1e-5, "error {fine:e}");
}

#[test]
fn particle_energies_sum_to_h_and_slosh_around_the_ring() {
    // One particle of eight kicked: its energy must leave it and reach the far side of the
    // ring, while the total stays H (a sum of eight terms: rounding ~8 eps H).
    let n = 8;
    let mut p = vec![0.0; n];
    p[0] = 3.0;
    let (a, b) = (1.0, 1.0);
    let mut toda = TodaLattice::new(&vec![0.0; n], &p, a, b).unwrap();
    let r = toda
        .integrate_with(
            (0.0, 20.0),
            1e-3,
            Method::Yoshida4,
            IntegrateOptions {
                sampling: Sampling::Stride(100),
                ..IntegrateOptions::default()
            },
        )
        .unwrap();
    let energy = r.energy.as_ref().unwrap();
    let mut kicked_min = f64::INFINITY;
    let mut far_max = 0.0_f64;
    let kick = 0.5 * 9.0; // the kicked particle's kinetic energy above a/b
    for (row, &h) in r.y.rows().into_iter().zip(energy) {
        let e = toda
            .particle_energies(Some(row.as_slice().unwrap()))
            .unwrap();
        let sum: f64 = e.iter().sum();
        assert!((sum - h).abs() < 1e-14 * h.abs() * n as f64, "{sum} vs {h}");
        kicked_min = kicked_min.min(e[0] - a / b);
        far_max = far_max.max(e[n / 2] - a / b);
    }
    println!("kicked particle keeps at least {kicked_min:.3}, far particle gets up to {far_max:.3} of {kick}");
    // The kick travels as a pulse (a Toda soliton) at speed ~1 site per unit time: particle 0
    // gives away most of it and particle 4 receives a large share within t = 20.
    assert!(kicked_min < 0.2 * kick, "{kicked_min}");
    assert!(far_max > 0.5 * kick, "{far_max}");
    // At rest in equilibrium every particle holds a/b.
    let rest = TodaLattice::new(&[0.0; 4], &[0.0; 4], 2.0, 0.5).unwrap();
    assert_eq!(rest.particle_energies(None).unwrap(), vec![4.0; 4]);
}

#[test]
fn bad_inputs_are_refused() {
    let invalid = |r: Result<TodaLattice, Error>, what: &str| match r {
        Err(Error::InvalidParameter { name, .. }) => assert_eq!(name, what),
        other => panic!("{what}: {other:?}"),
    };
    invalid(TodaLattice::new(&[0.0], &[0.0], 1.0, 1.0), "n");
    invalid(TodaLattice::new(&[], &[], 1.0, 1.0), "n");
    invalid(TodaLattice::new(&[0.0; 3], &[0.0; 3], 0.0, 1.0), "a");
    invalid(TodaLattice::new(&[0.0; 3], &[0.0; 3], -1.0, 1.0), "a");
    invalid(TodaLattice::new(&[0.0; 3], &[0.0; 3], 1.0, 0.0), "b");
    invalid(TodaLattice::new(&[0.0; 3], &[0.0; 3], 1.0, f64::NAN), "b");
    assert!(matches!(
        TodaLattice::new(&[0.0; 3], &[0.0; 2], 1.0, 1.0),
        Err(Error::DimensionMismatch { .. })
    ));
    assert!(matches!(
        TodaLattice::new(&[0.0, f64::INFINITY, 0.0], &[0.0; 3], 1.0, 1.0),
        Err(Error::NonFinite { .. })
    ));
    let toda = TodaLattice::new(&[0.0; 3], &[0.0; 3], 1.0, 1.0).unwrap();
    assert!(matches!(
        toda.conserved_quantities(Some(&[0.0; 5])),
        Err(Error::DimensionMismatch { .. })
    ));
    assert!(matches!(
        toda.particle_energies(Some(&[0.0, 0.0, f64::NAN, 0.0, 0.0, 0.0])),
        Err(Error::NonFinite { .. })
    ));
    // A stretch of 2000/b overflows exp(b r/2): an error, not infinities in the eigensolver.
    assert!(matches!(
        toda.conserved_quantities(Some(&state_of(&[0.0, 2000.0, 0.0], &[0.0; 3]))),
        Err(Error::NonFinite { .. })
    ));
    let mut out = [0.0; 2];
    assert!(matches!(
        toda.particle_energies_into(&[0.0; 3], &[0.0; 3], &mut out),
        Err(Error::DimensionMismatch { .. })
    ));
}
