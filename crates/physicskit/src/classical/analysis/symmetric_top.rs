//! Slow dynamics of the heavy symmetric top from its conserved momenta.
//!
//! With `p_phi` and `p_psi` conserved, `theta` moves like a particle of "mass" `I1` in the
//! effective potential (Goldstein, *Classical Mechanics*, 3rd ed., §5.7, eq. 5.63)
//!
//! ```text
//! V_eff(theta) = (p_phi - p_psi cos theta)^2 / (2 I1 sin^2 theta) + p_psi^2 / (2 I3)
//!                + M g l cos theta
//! ```
//!
//! Its minimum `theta_eq` is the angle of steady precession and the centre of nutation; the
//! small-oscillation (nutation) frequency is `sqrt(V_eff''(theta_eq) / I1)` and the mean
//! precession rate `phi' = (p_phi - p_psi cos theta_eq) / (I1 sin^2 theta_eq)`.
//!
//! `theta_eq` is the root of the analytic slope, with `a = p_phi - p_psi cos theta`,
//!
//! ```text
//! V_eff'(theta) = a (p_psi sin^2 theta - a cos theta) / (I1 sin^3 theta) - M g l sin theta
//!               = -sin theta (I1 phi'^2 cos theta - p_psi phi' + M g l),  phi' = a / (I1 sin^2)
//! ```
//!
//! (the second form is Goldstein's steady-precession condition, eq. 5.75), found by bisection
//! down to adjacent floating-point numbers: `theta_eq` is where the computed slope changes
//! sign, to a few ulps. Minimizing `V_eff` instead could not locate it better than
//! `sqrt(eps) ~ 1e-8` relative, because `V_eff` is flat to rounding that close to a minimum.
use crate::classical::core::error::{check_finite_scalar, check_positive};
use crate::classical::core::{Error, Result};

/// The spec's default search interval of [`find_theta_equilibrium`]: `(0.001, pi - 0.001)`.
pub const DEFAULT_THETA_BRACKET: (f64, f64) = (0.001, std::f64::consts::PI - 0.001);

/// The spec's default finite-difference step of [`nutation_frequency`]: at `1e-5` the
/// truncation error (`~1e-10`) and the cancellation error (`~eps V / dtheta^2 ~ 1e-6`
/// relative) of the second difference are both far below 1%.
pub const DEFAULT_NUTATION_DTHETA: f64 = 1e-5;

fn veff(theta: f64, p_phi: f64, p_psi: f64, i1: f64, i3: f64, mgl: f64) -> f64 {
    let (s, c) = theta.sin_cos();
    let a = p_phi - p_psi * c;
    a * a / (2.0 * i1 * s * s) + p_psi * p_psi / (2.0 * i3) + mgl * c
}

fn check_top(p_phi: f64, p_psi: f64, i1: f64, i3: f64, mgl: f64) -> Result<()> {
    check_finite_scalar("p_phi", p_phi)?;
    check_finite_scalar("p_psi", p_psi)?;
    check_positive("I1", i1)?;
    check_positive("I3", i3)?;
    check_finite_scalar("Mgl", mgl)?;
    Ok(())
}

/// `V_eff(theta)` of the heavy symmetric top (see the module documentation). At
/// `sin theta = 0` it is `+inf` (or `NaN` when also `p_phi = p_psi cos theta`).
///
/// # Errors
/// Non-finite `theta`, `p_phi`, `p_psi` or `Mgl`; `I1 <= 0` or `I3 <= 0`.
pub fn effective_potential_symmetric_top(
    theta: f64,
    p_phi: f64,
    p_psi: f64,
    i1: f64,
    i3: f64,
    mgl: f64,
) -> Result<f64> {
    check_top(p_phi, p_psi, i1, i3, mgl)?;
    check_finite_scalar("theta", theta)?;
    Ok(veff(theta, p_phi, p_psi, i1, i3, mgl))
}

/// [`effective_potential_symmetric_top`] at each angle of `theta`.
///
/// # Errors
/// As [`effective_potential_symmetric_top`].
pub fn effective_potential_symmetric_top_many(
    theta: &[f64],
    p_phi: f64,
    p_psi: f64,
    i1: f64,
    i3: f64,
    mgl: f64,
) -> Result<Vec<f64>> {
    check_top(p_phi, p_psi, i1, i3, mgl)?;
    theta
        .iter()
        .map(|&th| {
            check_finite_scalar("theta", th)?;
            Ok(veff(th, p_phi, p_psi, i1, i3, mgl))
        })
        .collect()
}

/// `V_eff'(theta)` (see the module documentation).
fn veff_slope(theta: f64, p_phi: f64, p_psi: f64, i1: f64, mgl: f64) -> f64 {
    let (s, c) = theta.sin_cos();
    let a = p_phi - p_psi * c;
    a * (p_psi * s * s - a * c) / (i1 * s * s * s) - mgl * s
}

/// Subintervals of the scan for a sign change of `V_eff'` when the bracket's ends do not
/// already show one (`V_eff` of a top has one minimum on `(0, pi)`, so the ends normally do;
/// the scan serves brackets that also hold a maximum, as with `Mgl < 0`).
const SCAN_INTERVALS: usize = 64;

/// Bisects `f`, negative at `lo` and positive at `hi`, until the two are adjacent floats;
/// returns the one where `|f|` is smaller (or a point where `f` is exactly zero).
fn bisect_sign_change(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    // Each halving removes one bit of the gap: 64 bisections cover any gap in (0, pi), and
    // the loop also stops once the midpoint is an end.
    for _ in 0..128 {
        let mid = lo + 0.5 * (hi - lo);
        if mid <= lo || mid >= hi {
            break;
        }
        let v = f(mid);
        if v < 0.0 {
            lo = mid;
        } else if v > 0.0 {
            hi = mid;
        } else {
            return mid;
        }
    }
    if f(lo).abs() <= f(hi).abs() {
        lo
    } else {
        hi
    }
}

/// The nutation angle `theta_eq` of the minimum of `V_eff` on `bracket`: the root of the
/// analytic `V_eff'` where it changes sign from negative to positive, bisected to adjacent
/// floats (a few ulps; see the module documentation). If the bracket holds several minima,
/// the lowest.
///
/// # Errors
/// Invalid top parameters; a bracket not inside `(0, pi)` with `a < b`; an
/// [`Error::InvalidParameter`] naming `bracket` if `V_eff` has no interior minimum in it
/// (its slope does not go from negative to positive at the ends nor at any of 64 evenly
/// spaced points between them).
pub fn find_theta_equilibrium(
    p_phi: f64,
    p_psi: f64,
    i1: f64,
    i3: f64,
    mgl: f64,
    bracket: (f64, f64),
) -> Result<f64> {
    check_top(p_phi, p_psi, i1, i3, mgl)?;
    let (a, b) = bracket;
    if !(a > 0.0 && b < std::f64::consts::PI && a < b) {
        return Err(Error::invalid(
            "bracket",
            if a > 0.0 && a < b { b } else { a },
            "must satisfy 0 < a < b < pi",
        ));
    }
    let slope = |th: f64| veff_slope(th, p_phi, p_psi, i1, mgl);
    let v = |th: f64| veff(th, p_phi, p_psi, i1, i3, mgl);
    let (sa, sb) = (slope(a), slope(b));
    if sa < 0.0 && sb > 0.0 {
        return Ok(bisect_sign_change(slope, a, b));
    }
    let at = |k: usize| {
        if k == SCAN_INTERVALS {
            b
        } else {
            a + (b - a) * k as f64 / SCAN_INTERVALS as f64
        }
    };
    let mut best: Option<f64> = None;
    let mut previous = (a, sa);
    for k in 1..=SCAN_INTERVALS {
        let x = at(k);
        let s = slope(x);
        if previous.1 < 0.0 && s > 0.0 {
            let root = bisect_sign_change(slope, previous.0, x);
            if best.is_none_or(|r| v(root) < v(r)) {
                best = Some(root);
            }
        }
        previous = (x, s);
    }
    best.ok_or_else(|| {
        Error::invalid(
            "bracket",
            a,
            format!(
                "({a}, {b}) holds no interior minimum of V_eff: its slope does not change \
                 sign from negative to positive there ({sa} and {sb} at the ends)"
            ),
        )
    })
}

/// Small-oscillation nutation frequency `sqrt(V_eff''(theta_eq) / I1)` (rad per unit time),
/// with `V_eff''` from a central second difference of step `dtheta` (see
/// [`DEFAULT_NUTATION_DTHETA`]). `theta_eq` defaults to [`find_theta_equilibrium`] on
/// [`DEFAULT_THETA_BRACKET`].
///
/// # Errors
/// Invalid top parameters; `dtheta` not positive; `theta_eq ± dtheta` outside `(0, pi)`;
/// `V_eff'' <= 0` there (not a minimum); errors of [`find_theta_equilibrium`].
pub fn nutation_frequency(
    p_phi: f64,
    p_psi: f64,
    i1: f64,
    i3: f64,
    mgl: f64,
    theta_eq: Option<f64>,
    dtheta: f64,
) -> Result<f64> {
    check_top(p_phi, p_psi, i1, i3, mgl)?;
    check_positive("dtheta", dtheta)?;
    let th = match theta_eq {
        Some(th) => check_finite_scalar("theta_eq", th)?,
        None => find_theta_equilibrium(p_phi, p_psi, i1, i3, mgl, DEFAULT_THETA_BRACKET)?,
    };
    if !(th - dtheta > 0.0 && th + dtheta < std::f64::consts::PI) {
        return Err(Error::invalid(
            "theta_eq",
            th,
            "theta_eq ± dtheta must lie inside (0, pi)",
        ));
    }
    let v = |x: f64| veff(x, p_phi, p_psi, i1, i3, mgl);
    let curvature = (v(th + dtheta) - 2.0 * v(th) + v(th - dtheta)) / (dtheta * dtheta);
    if !(curvature > 0.0 && curvature.is_finite()) {
        return Err(Error::invalid(
            "theta_eq",
            th,
            format!("V_eff'' = {curvature} there: not a minimum of the effective potential"),
        ));
    }
    Ok((curvature / i1).sqrt())
}

/// Steady precession rate `(p_phi - p_psi cos theta_eq) / (I1 sin^2 theta_eq)`, exact when the
/// top does not nutate and the mean `phi'` of a small nutation.
///
/// # Errors
/// Non-finite momenta or `theta_eq`, `I1 <= 0`, or `sin theta_eq = 0`.
pub fn precession_frequency(p_phi: f64, p_psi: f64, i1: f64, theta_eq: f64) -> Result<f64> {
    check_finite_scalar("p_phi", p_phi)?;
    check_finite_scalar("p_psi", p_psi)?;
    check_positive("I1", i1)?;
    check_finite_scalar("theta_eq", theta_eq)?;
    let (s, c) = theta_eq.sin_cos();
    let rate = (p_phi - p_psi * c) / (i1 * s * s);
    if !rate.is_finite() {
        return Err(Error::invalid(
            "theta_eq",
            theta_eq,
            "sin(theta_eq) = 0: the precession rate is undefined on the axis",
        ));
    }
    Ok(rate)
}
