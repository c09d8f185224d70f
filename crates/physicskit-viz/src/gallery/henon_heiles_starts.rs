//! Starts on a Hénon–Heiles surface of section at a given energy, shared by demonstrations 2,
//! 18 and 21.
//!
//! The section is `q_k = 0` crossed with `p_k >= 0`; a point `(q, p)` of its plane (the other
//! degree of freedom) starts the orbit with
//!
//! ```text
//! p_k = sqrt(2 (E - H(q_k = 0, p_k = 0, q, p)))
//! ```
//!
//! from the system's own energy `H` (unit masses: the kinetic energy of `p_k` is `p_k^2 / 2`).
//! Points where the root is imaginary lie outside the energy curve `H(q_k = 0, p_k = 0, q, p) = E`
//! and start nothing. The curve's extent is found on the same function, by marching out from
//! the origin (the potential's minimum) and bisecting, so no root of the potential is typed.

use physicskit::classical::systems::HenonHeilesSystem;
use physicskit::classical::DynamicalSystem;

use crate::error::Result;

/// March steps per `sqrt(2E)` when looking for the energy curve. A step could jump over the
/// region outside the curve only where it is narrower than the step: on the section `x = 0`
/// that is the gap before the saddle at `y = 1`, `2 sqrt(2 (1/6 - E))` wide (the potential
/// there is `1/6 - (y - 1)^2 / 2 + ...`), wider than the step `sqrt(2E) / 256` for every
/// energy more than 1e-6 below 1/6; on `y = 0` the curve is the circle `x^2 + p_x^2 = 2E`.
const MARCH_STEPS: f64 = 256.0;
/// The most march steps before giving up (an energy above the saddles: unbounded curve).
const MAX_MARCH: usize = 64 * 256;

/// The starts on the section `q_axis = 0`, `p_axis >= 0`, at one energy.
pub(crate) struct SectionStarts {
    hh: HenonHeilesSystem,
    /// The coordinate held at zero: 0 for the section `x = 0` (plane `(y, p_y)`), 1 for
    /// `y = 0` (plane `(x, p_x)`).
    axis: usize,
    energy: f64,
}

impl SectionStarts {
    /// The section `q_axis = 0` (`axis` 0 or 1) at `energy`.
    pub(crate) fn new(axis: usize, energy: f64) -> Result<Self> {
        Ok(Self {
            hh: HenonHeilesSystem::new(&[0.0, 0.0], &[0.0, 0.0])?,
            axis,
            energy,
        })
    }

    /// The state `[x, y, p_x, p_y]` on the section at `(q, p)` with `p_axis = p_k`.
    fn state(&self, q: f64, p: f64, p_k: f64) -> [f64; 4] {
        let other = 1 - self.axis;
        let mut s = [0.0; 4];
        s[other] = q;
        s[2 + other] = p;
        s[2 + self.axis] = p_k;
        s
    }

    /// The state `[x, y, p_x, p_y]` starting at `(q, p)` of the section's plane with
    /// `p_axis > 0` at the energy; `None` outside the energy curve (or on it).
    pub(crate) fn start(&self, q: f64, p: f64) -> Option<[f64; 4]> {
        let p_k2 = 2.0 * (self.energy - self.hh.energy(&self.state(q, p, 0.0)));
        (p_k2 > 0.0).then(|| self.state(q, p, p_k2.sqrt()))
    }

    /// Where the ray from the origin along `dir` first leaves the energy curve (the distance,
    /// bisected to adjacent floats).
    fn edge(&self, dir: (f64, f64)) -> f64 {
        let inside = |t: f64| self.start(t * dir.0, t * dir.1).is_some();
        let h = (2.0 * self.energy).sqrt() / MARCH_STEPS;
        let mut hi = h;
        for _ in 0..MAX_MARCH {
            if !inside(hi) {
                break;
            }
            hi += h;
        }
        let mut lo = hi - h;
        loop {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                return lo;
            }
            if inside(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
    }

    /// The extent of the energy curve in the section's plane, `((q_lo, q_hi), (p_lo, p_hi))`:
    /// `q` along `p = 0`, and `p` along `q = 0`, where the potential on the section is least.
    pub(crate) fn extent(&self) -> ((f64, f64), (f64, f64)) {
        let p_max = self.edge((0.0, 1.0));
        (
            (-self.edge((-1.0, 0.0)), self.edge((1.0, 0.0))),
            (-p_max, p_max),
        )
    }

    /// Start `k` of `n` spread over the section: even `k` along `p = 0` across the curve, odd
    /// `k` along `q = 0` with `p > 0`, each set evenly spaced and clear of the curve's ends.
    pub(crate) fn spread(&self, k: usize, n: usize) -> Option<[f64; 4]> {
        let ((q_lo, q_hi), (_, p_hi)) = self.extent();
        let f = (k / 2) as f64 / (n / 2).max(1) as f64;
        if k.is_multiple_of(2) {
            self.start(q_lo + (q_hi - q_lo) * (0.025 + 0.95 * f), 0.0)
        } else {
            self.start(0.0, p_hi * (0.05 + 0.9 * f))
        }
    }
}
