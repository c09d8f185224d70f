//! The coefficient sets of the methods against their order conditions: the odd-power
//! conditions of every symmetric composition of Störmer–Verlet in the registry, and the
//! simplifying assumptions and symplecticity condition of the Gauss–Legendre tableaus. (The
//! kick and drift sums of every splitting method are checked in `methods.rs`; the full order
//! of each method, including the partitioned `blanes_moan6`, is measured in `convergence.rs`.)

use physicskit::classical::core::method::Scheme;
use physicskit::classical::integrators::gauss_legendre4::GaussLegendre4Tableau;
use physicskit::classical::integrators::gauss_legendre6::GaussLegendre6Tableau;
use physicskit::classical::integrators::implicit_midpoint::MidpointRule;
use physicskit::classical::integrators::splitting::Coefficients;
use physicskit::classical::integrators::{ButcherTableau, Tableau};
use physicskit::classical::Method;

/// The splitting methods that are symmetric compositions of Störmer–Verlet (their kicks are
/// the merged half-kicks of their drifts), with their drift weights.
fn compositions() -> Vec<(Method, &'static [f64])> {
    let mut out = Vec::new();
    for method in Method::ALL {
        let Scheme::Splitting { kicks, drifts } = method.info().scheme else {
            continue;
        };
        let merged: Vec<f64> = (0..=drifts.len())
            .map(|i| {
                let before = if i == 0 { 0.0 } else { drifts[i - 1] };
                let after = drifts.get(i).copied().unwrap_or(0.0);
                0.5 * (before + after)
            })
            .collect();
        if merged.iter().zip(kicks).all(|(a, b)| a == b) {
            out.push((method, drifts));
        }
    }
    out
}

#[test]
fn compositions_satisfy_the_odd_power_order_conditions() {
    // A symmetric composition of a symmetric second-order method with weights w_i has order p
    // only if sum w_i^m = 0 for every odd m with 3 <= m < p (the coefficient of the basic
    // method's own h^(m) error term; Hairer, Lubich, Wanner, GNI §V.3.2, and Yoshida 1990,
    // eq. (5.3)). Each w_i is accurate to 1e-15 (15-digit data for yoshida6) or to rounding,
    // so a sum is within ~m 1e-15 sum |w_i|^m of zero; 1e-13 sum |w_i|^m leaves a margin, while
    // one wrong digit in the 10th place of a weight breaks it by 1e-10.
    let found = compositions();
    let names: Vec<&str> = found.iter().map(|(m, _)| m.name()).collect();
    for expected in [
        "yoshida4",
        "yoshida6",
        "kahan_li6",
        "kahan_li8",
        "sofroniou_spaletta10",
    ] {
        assert!(
            names.contains(&expected),
            "{expected} not found in {names:?}"
        );
    }
    for (method, w) in found {
        let mut m = 3;
        while m < method.order() {
            let e = m as i32;
            let sum: f64 = w.iter().map(|x| x.powi(e)).sum();
            let scale: f64 = w.iter().map(|x| x.abs().powi(e)).sum();
            println!("{method}: sum w^{m} = {sum:e} (scale {scale:.3})");
            assert!(sum.abs() <= 1e-13 * scale, "{method}: sum w^{m} = {sum:e}");
            m += 2;
        }
    }
}

#[test]
fn blanes_moan6_has_independent_kicks_and_drifts() {
    // The partitioned method is not a composition of Störmer–Verlet: were it one, the loop
    // would run it with merged half-kicks, not the paper's a_i.
    assert!(compositions()
        .iter()
        .all(|(m, _)| *m != Method::BlanesMoan6));
    let Scheme::Splitting { kicks, drifts } = Method::BlanesMoan6.info().scheme else {
        panic!("blanes_moan6 is a splitting method");
    };
    assert_eq!((kicks.len(), drifts.len()), (11, 10));
    // The closing kick of the loop's weights is the paper's last a_i.
    let c = Coefficients::<10>::partitioned(kicks, drifts);
    assert_eq!(c.last_kick, kicks[10]);
}

/// Checks the simplifying assumptions `B(2s)`: `sum_i b_i c_i^(k-1) = 1/k` for `k <= 2s`,
/// `C(s)`: `sum_j a_ij c_j^(k-1) = c_i^k / k` for `k <= s` (which together give order `2s`,
/// Butcher 1964; GNI §II.1.3), and the symplecticity condition
/// `b_i a_ij + b_j a_ji = b_i b_j` (GNI Theorem VI.4.3).
fn check_gauss<const S: usize>(name: &str, t: &Tableau<S>) {
    // Entries rounded once, sums of at most 3 terms each below 1: a few ulps; 8 eps.
    let tol = 8.0 * f64::EPSILON;
    for k in 1..=2 * S {
        let sum: f64 = (0..S).map(|i| t.b[i] * t.c[i].powi(k as i32 - 1)).sum();
        assert!((sum - 1.0 / k as f64).abs() <= tol, "{name}: B({k}) {sum}");
    }
    for i in 0..S {
        for k in 1..=S {
            let sum: f64 = (0..S).map(|j| t.a[i][j] * t.c[j].powi(k as i32 - 1)).sum();
            let want = t.c[i].powi(k as i32) / k as f64;
            assert!((sum - want).abs() <= tol, "{name}: C({k}) row {i}");
        }
        for j in 0..S {
            let m = t.b[i] * t.a[i][j] + t.b[j] * t.a[j][i] - t.b[i] * t.b[j];
            assert!(m.abs() <= tol, "{name}: symplecticity ({i}, {j}) {m:e}");
        }
    }
    // The nodes are the zeros of the shifted Legendre polynomial: symmetric about 1/2.
    for i in 0..S {
        assert!(
            (t.c[i] + t.c[S - 1 - i] - 1.0).abs() <= tol,
            "{name}: nodes"
        );
    }
}

#[test]
fn gauss_legendre_tableaus_satisfy_their_order_and_symplecticity_conditions() {
    check_gauss("implicit_midpoint", &MidpointRule::TABLEAU);
    check_gauss("gauss_legendre4", &GaussLegendre4Tableau::TABLEAU);
    check_gauss("gauss_legendre6", &GaussLegendre6Tableau::TABLEAU);
}
