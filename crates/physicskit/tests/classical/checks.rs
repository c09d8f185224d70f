//! Numerical checks shared by the tests: a force against its potential by central differences,
//! zero crossings by Hermite interpolation, least-squares slopes.

use physicskit::classical::HamiltonianSystem;

/// Checks `force = -dV/dq` against central differences of `potential_energy`, and (when
/// supplied) `force_jacobian` against central differences of `force`.
///
/// Central differences with step `h` have truncation error `O(h^2 V''')` and rounding error
/// `O(eps V / h)`; with `h = 1e-5` both are below ~1e-8 for the O(1) potentials tested, so a
/// relative tolerance of 1e-6 can only fail on a wrong derivative.
pub fn check_force_against_potential<S: HamiltonianSystem>(sys: &S, q: &[f64]) {
    let n = q.len();
    let h = 1e-5;
    let mut force = vec![0.0; n];
    sys.force(q, 0.0, &mut force).unwrap();
    let mut qp = q.to_vec();
    let mut fp = vec![0.0; n];
    let mut fm = vec![0.0; n];
    let mut jac = vec![0.0; n * n];
    let has_jac = sys.force_jacobian(q, 0.0, &mut jac).is_some();
    for j in 0..n {
        qp[j] = q[j] + h;
        let vp = sys.potential_energy(&qp);
        sys.force(&qp, 0.0, &mut fp).unwrap();
        qp[j] = q[j] - h;
        let vm = sys.potential_energy(&qp);
        sys.force(&qp, 0.0, &mut fm).unwrap();
        qp[j] = q[j];
        let numeric = -(vp - vm) / (2.0 * h);
        let scale = 1.0 + force[j].abs();
        assert!(
            (numeric - force[j]).abs() < 1e-6 * scale,
            "force[{j}] = {} but -dV/dq = {numeric}",
            force[j]
        );
        if has_jac {
            for i in 0..n {
                let d = (fp[i] - fm[i]) / (2.0 * h);
                let scale = 1.0 + jac[i * n + j].abs();
                assert!(
                    (d - jac[i * n + j]).abs() < 1e-6 * scale,
                    "jacobian[{i},{j}] = {} but dF/dq = {d}",
                    jac[i * n + j]
                );
            }
        }
    }
}

/// Times at which `y` crosses zero upwards, located on each bracketing step by the cubic
/// Hermite interpolant built from the values `y` and their time derivatives `ydot`
/// (interpolation error O(dt^4), far below the tolerances of the callers), refined by Newton.
pub fn upward_zero_crossings(t: &[f64], y: &[f64], ydot: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    for i in 0..t.len().saturating_sub(1) {
        if y[i] < 0.0 && y[i + 1] >= 0.0 {
            out.push(hermite_root(
                t[i],
                t[i + 1],
                y[i],
                y[i + 1],
                ydot[i],
                ydot[i + 1],
            ));
        }
    }
    out
}

/// Root of the cubic Hermite interpolant on `[t0, t1]` (Newton from the linear estimate).
pub fn hermite_root(t0: f64, t1: f64, y0: f64, y1: f64, d0: f64, d1: f64) -> f64 {
    let h = t1 - t0;
    let eval = |s: f64| {
        let (s2, s3) = (s * s, s * s * s);
        let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
        let h10 = s3 - 2.0 * s2 + s;
        let h01 = -2.0 * s3 + 3.0 * s2;
        let h11 = s3 - s2;
        let v = h00 * y0 + h10 * h * d0 + h01 * y1 + h11 * h * d1;
        let dv = (6.0 * s2 - 6.0 * s) * y0
            + (3.0 * s2 - 4.0 * s + 1.0) * h * d0
            + (-6.0 * s2 + 6.0 * s) * y1
            + (3.0 * s2 - 2.0 * s) * h * d1;
        (v, dv)
    };
    let mut s = y0 / (y0 - y1);
    for _ in 0..20 {
        let (v, dv) = eval(s);
        let step = v / dv;
        s -= step;
        if step.abs() < 1e-15 {
            break;
        }
    }
    t0 + s * h
}

/// Least-squares slope of `y` against `x`.
pub fn fit_slope(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let mx = x.iter().sum::<f64>() / n;
    let my = y.iter().sum::<f64>() / n;
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

/// Slope of the least-squares line through `(ln x, ln y)`: a measured power law's exponent.
pub fn loglog_slope(x: &[f64], y: &[f64]) -> f64 {
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = y.iter().map(|v| v.ln()).collect();
    fit_slope(&lx, &ly)
}
