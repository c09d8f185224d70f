//! One kick–drift–kick loop for every symmetric composition of Störmer–Verlet.
//!
//! A composition with drift weights `w_1..w_s` (summing to one) is executed as
//!
//! ```text
//! kick w_1/2, drift w_1, kick (w_1+w_2)/2, drift w_2, ..., drift w_s, kick w_s/2
//! ```
//!
//! which is `s` Verlet substeps with the touching half-kicks merged. The force after the last
//! drift is cached and reused as the first kick of the next step (first same as last), so a
//! step costs `s` force evaluations. As in OrdinaryDiffEq's symplectic tableaus, the methods
//! differ only in their weights ([`verlet::DRIFTS`](super::verlet::DRIFTS),
//! [`yoshida4::DRIFTS`](super::yoshida4::DRIFTS)).

use crate::classical::core::{Error, HamiltonianSystem, MassInv, Method, Result};

/// Kick–drift–kick stepper for a separable Hamiltonian system.
#[derive(Debug, Clone)]
pub struct SplittingStepper {
    drifts: &'static [f64],
    force: Vec<f64>,
    /// The cached force belongs to the current `q` (first same as last).
    force_valid: bool,
    force_evaluations: u64,
}

impl SplittingStepper {
    /// A stepper for `verlet` or `yoshida4` on `ndof` degrees of freedom.
    ///
    /// # Errors
    /// [`Error::UnsupportedMethod`] for a method that is not a splitting method.
    pub fn new(method: Method, ndof: usize) -> Result<Self> {
        let drifts: &'static [f64] = match method {
            Method::Verlet => &super::verlet::DRIFTS,
            Method::Yoshida4 => &super::yoshida4::DRIFTS,
            other => {
                return Err(Error::UnsupportedMethod {
                    method: other.name().into(),
                    reason: "not a splitting method".into(),
                })
            }
        };
        Ok(Self {
            drifts,
            force: vec![0.0; ndof],
            force_valid: false,
            force_evaluations: 0,
        })
    }

    /// Checks that `system` can be integrated by a splitting method.
    ///
    /// # Errors
    /// [`Error::UnsupportedMethod`] for non-separable or non-conservative systems.
    pub fn check_system<S: HamiltonianSystem + ?Sized>(method: Method, system: &S) -> Result<()> {
        let reason = if !system.separable() {
            "the system is not separable (H != T(p) + V(q)); use implicit_midpoint or rk4"
        } else if !system.conservative() {
            "the system has non-conservative forces (e.g. drag) that a splitting method would \
             silently drop; use rk4 or implicit_midpoint"
        } else {
            return Ok(());
        };
        Err(Error::UnsupportedMethod {
            method: method.name().into(),
            reason: reason.into(),
        })
    }

    /// Force evaluations so far.
    pub fn force_evaluations(&self) -> u64 {
        self.force_evaluations
    }

    /// Forgets the cached force (call after changing `q` outside the stepper).
    pub fn invalidate(&mut self) {
        self.force_valid = false;
    }

    /// Advances `(q, p)` from `t` to `t + h` (`h` may be negative).
    ///
    /// The force left by the previous step is reused as this step's first kick, so `q` must be
    /// the one the previous step returned; call [`invalidate`](Self::invalidate) after
    /// changing it in between.
    ///
    /// # Errors
    /// Whatever [`HamiltonianSystem::force`] returns.
    #[inline]
    pub fn step<S: HamiltonianSystem + ?Sized>(
        &mut self,
        system: &S,
        t: f64,
        q: &mut [f64],
        p: &mut [f64],
        h: f64,
    ) -> Result<()> {
        if !self.force_valid {
            system.force(q, t, &mut self.force)?;
            self.force_evaluations += 1;
        }
        // Until the step completes, the cache does not match q (an error mid-step leaves it
        // invalid).
        self.force_valid = false;
        let s = self.drifts.len();
        let mut elapsed = 0.0;
        kick(p, &self.force, 0.5 * self.drifts[0] * h);
        for i in 0..s {
            let w = self.drifts[i];
            drift(system.mass_inv(), q, p, w * h);
            elapsed += w;
            // The last substep ends exactly at t + h, whatever the rounding of the weights.
            let t_sub = if i + 1 == s { t + h } else { t + elapsed * h };
            system.force(q, t_sub, &mut self.force)?;
            self.force_evaluations += 1;
            let next = if i + 1 < s { self.drifts[i + 1] } else { 0.0 };
            kick(p, &self.force, 0.5 * (w + next) * h);
        }
        self.force_valid = true;
        Ok(())
    }
}

#[inline(always)]
fn kick(p: &mut [f64], force: &[f64], h: f64) {
    p.iter_mut().zip(force).for_each(|(pi, fi)| *pi += h * fi);
}

#[inline(always)]
fn drift(mass_inv: MassInv<'_>, q: &mut [f64], p: &[f64], h: f64) {
    match mass_inv {
        MassInv::Uniform(m) => {
            let hm = h * m;
            q.iter_mut().zip(p).for_each(|(qi, pi)| *qi += hm * pi);
        }
        MassInv::PerCoordinate(m) => q
            .iter_mut()
            .zip(p.iter().zip(m))
            .for_each(|(qi, (pi, mi))| *qi += h * mi * pi),
    }
}
