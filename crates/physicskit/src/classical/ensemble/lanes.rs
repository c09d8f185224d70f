//! Splitting-method members in SIMD lanes: members of a system whose force runs across lanes
//! ([`SplittingLanes`]: Kepler, Hénon–Heiles, the pendulum, the harmonic oscillator, the
//! projectile, the Toda lattice) with equal forces run `L` at a time
//! ([`native_lanes`]: 16 with AVX-512, 8 with AVX2, else 4), each with exactly the outputs of
//! its own `integrate` (`integrators/lanes.rs`).
//!
//! Members whose systems are the same apart from their initial states
//! ([`MemberSource::same_system`](super::MemberSource::same_system)), or whose forces compare equal
//! ([`SplittingLanes::same_force_as`]), share a group (`chunk.rs`); a member without a lanes
//! force, or whose lanes run fails (a state that is not finite), runs alone by `run_member`,
//! so its error is its own run's.

use std::sync::atomic::Ordering;

use super::chunk::{Kind, Lanes, Member};
use super::OBSERVE_EVERY;
use crate::classical::core::{Error, Result};
use crate::classical::integrators::lanes::{Batch, SplittingLanes};
use crate::classical::integrators::Method;
use crate::classical::model::DynSystem;
use crate::classical::symbolic::native_lanes;

/// Members per parallel chunk of the lanes path: four batches of lanes (every member takes
/// the same steps, so a chunk has no tail to balance; 1000 members make 16 chunks with 16
/// lanes, enough for two threads). The split changes no result.
pub(super) fn chunk() -> usize {
    4 * native_lanes()
}

/// Whether a plan with `method` runs its members in lanes: a splitting method, whatever it
/// keeps (reductions are computed from the lanes' states, `chunk.rs`). The engine runs a plan
/// of events only, or of no steps, member by member whatever the method.
pub(super) fn in_lanes(method: Method) -> bool {
    method.needs_separable()
}

/// The splitting methods' [`Kind`]: a group is the members of one lanes force, run by the
/// lead's [`SplittingLanes::run_lanes`], `L` members at a time.
pub(super) struct Splitting(pub Method);

impl Splitting {
    /// `system`'s lanes force, if it runs the method in lanes.
    fn force<'s>(&self, system: &'s dyn DynSystem) -> Option<&'s dyn SplittingLanes> {
        let force = system.dynamical().splitting_lanes()?;
        force.accepts(self.0).then_some(force)
    }
}

impl Kind for Splitting {
    type Form = ();

    fn form(&self, system: &dyn DynSystem) -> Option<()> {
        self.force(system).map(|_| ())
    }

    fn shares(&self, (lead, ()): Member<'_, ()>, (member, ()): Member<'_, ()>) -> bool {
        match (self.force(lead), self.force(member)) {
            (Some(a), Some(b)) => a.same_force_as(b),
            _ => false,
        }
    }

    fn run(&self, (lead, ()): Member<'_, ()>, mut run: Lanes<'_>) -> Result<()> {
        let dim = lead.dynamical().state_dim();
        let Some(force) = self.force(lead) else {
            // Not a lead `form` accepted: each member's own run says why.
            (0..run.starts.len() / dim).for_each(run.failed);
            return Ok(());
        };
        let width = native_lanes();
        let should_stop = || run.stop.load(Ordering::Relaxed);
        let folds = run.largest_error.is_some();
        for (b, batch_starts) in run.starts.chunks(width * dim).enumerate() {
            let base = b * width;
            let mut record = |m: usize, step: usize, y: &[f64], energy: Option<f64>| {
                (run.record)(base + m, step, y, energy);
            };
            let mut fold = |m: usize, error: f64| {
                if let Some(largest_error) = run.largest_error.as_deref_mut() {
                    largest_error(base + m, error);
                }
            };
            let failed = force.run_lanes(
                width,
                run.method,
                Batch {
                    starts: batch_starts,
                    grid: run.grid,
                    every: run.every,
                    check_every: OBSERVE_EVERY,
                    energy: run.energy,
                    record: &mut record,
                    largest_error: folds.then_some(&mut fold as &mut dyn FnMut(usize, f64)),
                    stop: &should_stop,
                },
            );
            let failed = match failed {
                Ok(failed) => failed,
                Err(e @ Error::Interrupted { .. }) => return Err(e),
                // Not run in lanes after all: each member's own run says why.
                Err(_) => vec![true; batch_starts.len() / dim],
            };
            for (m, failed) in failed.into_iter().enumerate() {
                if failed {
                    (run.failed)(base + m);
                }
            }
        }
        Ok(())
    }
}
