//! Action and period of the librating simple pendulum.
//!
//! For `H = p^2/2 - (g/l) cos q` and an energy `-g/l < E < g/l`, with
//! `m = k^2 = (E + g/l) / (2 g/l)` (the parameter of the complete elliptic integrals
//! [`ellipk`](super::ellipk) `K` and [`ellipe`](super::ellipe) `E`, see [`super::elliptic`]):
//!
//! ```text
//! J(E) = (1 / 2 pi) closed-integral p dq = (8 / pi) sqrt(g/l) [E(m) - (1 - m) K(m)]
//! T(E) = dJ/dE * 2 pi                   = 4 K(m) / sqrt(g/l)
//! ```
//!
//! Reference: L. D. Landau and E. M. Lifshitz, *Mechanics* (3rd ed., 1976), §11 problem 1
//! and §49–50 (action variables); I. C. Percival and D. Richards, *Introduction to Dynamics*
//! (1982), ch. 7.

use super::elliptic::ellipke;
use crate::classical::core::error::check_positive;
use crate::classical::core::{Error, Result};

/// Action `J` and period `T` of a librating pendulum `H = p^2/2 - (g/l) cos q` at energy `E`.
///
/// Returns `(J, T)` with `J = (1/2 pi) closed-integral p dq`.
///
/// # Example
/// ```
/// use physicskit::classical::analysis::pendulum_action_angle;
/// // Small oscillations: T -> 2 pi / sqrt(g/l), J -> (E + g/l) / sqrt(g/l).
/// let (j, t) = pendulum_action_angle(-1.0 + 1e-8, 1.0).unwrap();
/// assert!((t - 2.0 * std::f64::consts::PI).abs() < 1e-7);
/// assert!((j - 1e-8).abs() < 1e-14);
/// ```
///
/// # Errors
/// [`Error::InvalidParameter`] if `g_over_l` is not finite and positive, or if `energy` is not
/// strictly inside the librating range `(-g/l, g/l)` (the separatrix `E = g/l` has an infinite
/// period; rotating orbits are not librations).
pub fn pendulum_action_angle(energy: f64, g_over_l: f64) -> Result<(f64, f64)> {
    let g = check_positive("g_over_l", g_over_l)?;
    if !(energy.is_finite() && energy > -g && energy < g) {
        return Err(Error::invalid(
            "E",
            energy,
            format!("pendulum_action_angle needs a librating orbit, -g/l < E < g/l = {g}"),
        ));
    }
    let m = (energy + g) / (2.0 * g);
    let (k_ell, e_ell) = ellipke(m)?;
    let omega0 = g.sqrt();
    let action = 8.0 / std::f64::consts::PI * omega0 * (e_ell - (1.0 - m) * k_ell);
    let period = 4.0 * k_ell / omega0;
    Ok((action, period))
}
