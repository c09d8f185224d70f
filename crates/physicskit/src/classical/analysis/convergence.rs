//! Measured convergence orders and trajectory separation.
//!
//! A method of order `p` has global error `err(dt) ≈ C dt^p`, a straight line of slope `p` on a
//! log–log plot. [`fit_order`] fits that line by least squares on `(ln dt, ln err)`:
//!
//! ```text
//! p = Σ (x_i - x̄)(y_i - ȳ) / Σ (x_i - x̄)^2,   ln C = ȳ - p x̄,   x = ln dt, y = ln err.
//! ```
//!
//! (E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I*, 2nd ed.,
//! Springer 1993, §II.1 on measuring orders from error tables.)
//!
//! [`log_separation`] gives `ln |y_a(t) - y_b(t)|` of two trajectories sampled on the same
//! grid; its initial slope estimates the largest Lyapunov exponent of a chaotic orbit.

use crate::classical::core::{Error, Result};

/// A least-squares fit `err ≈ prefactor * dt^order`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrderFit {
    /// The slope of `ln err` against `ln dt`: the measured order.
    pub order: f64,
    /// The constant `C`.
    pub prefactor: f64,
}

impl OrderFit {
    /// The fitted error at step `dt`.
    pub fn predict(&self, dt: f64) -> f64 {
        self.prefactor * dt.powf(self.order)
    }
}

/// Fits `errors ≈ C dts^p` by least squares in log–log space.
///
/// # Errors
/// [`Error::DimensionMismatch`] if the slices differ in length; [`Error::InvalidParameter`] for
/// fewer than two points, a non-positive or non-finite entry (logarithms need positive
/// numbers; an error of exactly zero means the run is below rounding and cannot be fitted), or
/// all `dts` equal.
///
/// # Example
/// ```
/// use physicskit::classical::analysis::convergence::fit_order;
/// let dts = [0.1, 0.05, 0.025];
/// let errs: Vec<f64> = dts.iter().map(|h: &f64| 3.0 * h.powi(4)).collect();
/// let fit = fit_order(&dts, &errs).unwrap();
/// assert!((fit.order - 4.0).abs() < 1e-12);
/// ```
pub fn fit_order(dts: &[f64], errors: &[f64]) -> Result<OrderFit> {
    if dts.len() != errors.len() {
        return Err(Error::DimensionMismatch {
            name: "errors".into(),
            expected: dts.len(),
            found: errors.len(),
        });
    }
    if dts.len() < 2 {
        return Err(Error::invalid(
            "dts",
            dts.len() as f64,
            "need at least two step sizes to fit an order",
        ));
    }
    for (name, values) in [("dts", dts), ("errors", errors)] {
        if let Some(&bad) = values.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
            return Err(Error::invalid(
                name,
                bad,
                "every entry must be finite and > 0",
            ));
        }
    }
    let n = dts.len() as f64;
    let xs: Vec<f64> = dts.iter().map(|h| h.ln()).collect();
    let ys: Vec<f64> = errors.iter().map(|e| e.ln()).collect();
    let xm = xs.iter().sum::<f64>() / n;
    let ym = ys.iter().sum::<f64>() / n;
    let sxx: f64 = xs.iter().map(|x| (x - xm).powi(2)).sum();
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - xm) * (y - ym)).sum();
    if sxx <= f64::EPSILON * xs.iter().map(|x| x * x).sum::<f64>() {
        return Err(Error::invalid(
            "dts",
            dts[0],
            "all step sizes are equal; an order needs different dt",
        ));
    }
    let order = sxy / sxx;
    Ok(OrderFit {
        order,
        prefactor: (ym - order * xm).exp(),
    })
}

/// `ln |a_i - b_i|` (Euclidean norm over each row) of two trajectories stored row-major with
/// `dim` values per sample; the floor `1e-300` keeps identical states finite.
///
/// # Errors
/// [`Error::DimensionMismatch`] if the trajectories differ in length or are not a whole number
/// of `dim`-long rows; [`Error::InvalidParameter`] for `dim == 0`.
pub fn log_separation(a: &[f64], b: &[f64], dim: usize) -> Result<Vec<f64>> {
    if dim == 0 {
        return Err(Error::invalid("dim", 0.0, "must be >= 1"));
    }
    if a.len() != b.len() || !a.len().is_multiple_of(dim) {
        return Err(Error::DimensionMismatch {
            name: "b".into(),
            expected: a.len(),
            found: b.len(),
        });
    }
    Ok(a.chunks_exact(dim)
        .zip(b.chunks_exact(dim))
        .map(|(ra, rb)| {
            let d2: f64 = ra.iter().zip(rb).map(|(x, y)| (x - y) * (x - y)).sum();
            d2.sqrt().max(1e-300).ln()
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::classical::examples::HarmonicOscillator;
    use crate::classical::{HamiltonianSystem, Method};

    /// Measured orders of verlet (2) and rk4 (4) on the harmonic oscillator against its exact
    /// solution. dt from 0.1 to 0.0125 stays in the asymptotic regime (errors 1e-3..1e-9, far
    /// above rounding), where the fitted slope is within 0.1 of the true order.
    #[test]
    fn measured_orders_of_verlet_and_rk4() {
        for (method, expected) in [(Method::Verlet, 2.0), (Method::Rk4, 4.0)] {
            let dts = [0.1, 0.05, 0.025, 0.0125];
            let mut errs = Vec::new();
            for &dt in &dts {
                let mut osc = HarmonicOscillator::new(1.0, 0.0, 1.0, 1.0).unwrap();
                let r = osc.integrate((0.0, 10.0), dt, method).unwrap();
                let (q, p) = osc.exact(1.0, 0.0, 10.0);
                let last = r.final_state();
                errs.push(((last[0] - q).powi(2) + (last[1] - p).powi(2)).sqrt());
            }
            let fit = fit_order(&dts, &errs).unwrap();
            assert!(
                (fit.order - expected).abs() < 0.1,
                "{method:?}: {}",
                fit.order
            );
        }
    }

    #[test]
    fn bad_inputs_are_errors() {
        assert!(fit_order(&[0.1], &[1.0]).is_err());
        assert!(fit_order(&[0.1, 0.2], &[1.0]).is_err());
        assert!(fit_order(&[0.1, 0.2], &[0.0, 1.0]).is_err());
        assert!(fit_order(&[0.1, 0.1], &[1.0, 2.0]).is_err());
        assert!(fit_order(&[0.1, f64::NAN], &[1.0, 2.0]).is_err());
        assert!(log_separation(&[1.0, 2.0], &[1.0], 1).is_err());
        assert!(log_separation(&[1.0, 2.0], &[1.0, 2.0], 0).is_err());
    }

    /// Separation of two rows differing by (3, 4) is ln 5.
    #[test]
    fn log_separation_is_the_euclidean_norm() {
        let s = log_separation(&[0.0, 0.0, 1.0, 1.0], &[3.0, 4.0, 1.0, 1.0], 2).unwrap();
        assert!((s[0] - 5.0_f64.ln()).abs() < 1e-15);
        assert!(s[1] < -600.0);
    }
}
