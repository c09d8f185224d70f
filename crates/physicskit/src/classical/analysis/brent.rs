//! Brent's method for the minimum of a function of one variable on a bracket.
//!
//! Golden-section search safeguarded, accelerated by successive parabolic interpolation once
//! the iterates behave (R. P. Brent, *Algorithms for Minimization without Derivatives*
//! (1973), ch. 5). Converges superlinearly on smooth functions and never slower than golden
//! section; the location is found to `tol |x| + abs_tol`, which cannot usefully be below
//! `sqrt(eps)` relative because a smooth function is flat to rounding there.

use crate::classical::core::{Error, Result};

/// `(3 - sqrt 5) / 2`, the golden-section fraction.
const GOLDEN: f64 = 0.381_966_011_250_105_1;

/// A located minimum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Minimum {
    /// Where the minimum is.
    pub x: f64,
    /// The function value there.
    pub fx: f64,
    /// Function evaluations spent.
    pub evaluations: usize,
}

/// Minimizes `f` on `[a, b]` by Brent's method, to a location tolerance of
/// `rel_tol |x| + abs_tol`.
///
/// The minimum must be interior: the result is accepted only if `f` there is strictly below
/// both end values.
///
/// # Errors
/// [`Error::InvalidParameter`] for a bracket with `a >= b`, non-finite ends or tolerances that
/// are not positive; [`Error::InvalidParameter`] naming `bracket` if the bracket holds no
/// interior minimum (the function decreases towards an end, or is not finite at the ends);
/// [`Error::SolverDidNotConverge`] after `max_evaluations`.
pub fn brent_minimize(
    mut f: impl FnMut(f64) -> f64,
    (a, b): (f64, f64),
    rel_tol: f64,
    abs_tol: f64,
    max_evaluations: usize,
) -> Result<Minimum> {
    if !(a.is_finite() && b.is_finite() && a < b) {
        return Err(Error::invalid("bracket", a, "needs finite ends with a < b"));
    }
    if !(rel_tol > 0.0 && abs_tol > 0.0 && rel_tol.is_finite() && abs_tol.is_finite()) {
        return Err(Error::invalid(
            "tolerance",
            rel_tol.min(abs_tol),
            "must be finite and > 0",
        ));
    }
    let (fa, fb) = (f(a), f(b));
    let (mut lo, mut hi) = (a, b);
    let mut x = lo + GOLDEN * (hi - lo);
    let mut fx = f(x);
    let (mut w, mut v, mut fw, mut fv) = (x, x, fx, fx);
    let (mut d, mut e) = (0.0_f64, 0.0_f64);
    let mut evaluations = 3;
    loop {
        let mid = 0.5 * (lo + hi);
        let tol1 = rel_tol * x.abs() + abs_tol;
        let tol2 = 2.0 * tol1;
        if (x - mid).abs() <= tol2 - 0.5 * (hi - lo) {
            break;
        }
        if evaluations >= max_evaluations {
            return Err(Error::SolverDidNotConverge {
                t: x,
                iterations: evaluations,
                residual: hi - lo,
            });
        }
        let mut parabolic = false;
        if e.abs() > tol1 {
            // Parabola through (v, fv), (w, fw), (x, fx); step p / q from x.
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            } else {
                q = -q;
            }
            let e_prev = e;
            e = d;
            if p.abs() < (0.5 * q * e_prev).abs() && p > q * (lo - x) && p < q * (hi - x) {
                d = p / q;
                let u = x + d;
                if u - lo < tol2 || hi - u < tol2 {
                    d = if x < mid { tol1 } else { -tol1 };
                }
                parabolic = true;
            }
        }
        if !parabolic {
            e = if x < mid { hi - x } else { lo - x };
            d = GOLDEN * e;
        }
        let u = if d.abs() >= tol1 {
            x + d
        } else if d > 0.0 {
            x + tol1
        } else {
            x - tol1
        };
        let fu = f(u);
        evaluations += 1;
        if fu <= fx {
            if u < x {
                hi = x;
            } else {
                lo = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                lo = u;
            } else {
                hi = u;
            }
            if fu <= fw || w.to_bits() == x.to_bits() {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v.to_bits() == x.to_bits() || v.to_bits() == w.to_bits() {
                (v, fv) = (u, fu);
            }
        }
    }
    // NaN end values fail these comparisons too, as they should.
    if !(fx < fa && fx < fb) {
        return Err(Error::invalid(
            "bracket",
            x,
            format!(
                "({a}, {b}) holds no interior minimum: f = {fx} at the best point, {fa} and \
                 {fb} at the ends"
            ),
        ));
    }
    Ok(Minimum { x, fx, evaluations })
}
