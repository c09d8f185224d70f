//! Splitting-method members in SIMD lanes: members of a system whose force runs across lanes
//! ([`SplittingLanes`](crate::classical::integrators::lanes::SplittingLanes): Kepler,
//! Hénon–Heiles) with equal forces run `L` at a time
//! ([`native_lanes`]: 16 with AVX-512, 8 with AVX2, else 4), each with exactly the outputs of
//! its own `integrate` (`integrators/lanes.rs`).
//!
//! Members whose systems are the same apart from their initial states
//! ([`MemberSource::same_system`]), or whose forces compare equal
//! ([`SplittingLanes::same_force_as`](crate::classical::integrators::lanes::SplittingLanes::same_force_as)), share a group; a member without a lanes force, or
//! whose lanes run fails (a state that is not finite), runs alone by `run_member`, so its
//! error is its own run's. Plans with reductions, which read every step, run members alone.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use super::{in_member, run_member, MemberSource, Plan, Prepared, OBSERVE_EVERY};
use crate::classical::core::{Error, Result};
use crate::classical::integrators::lanes::Batch;
use crate::classical::integrators::Sampling;
use crate::classical::model::DynSystem;
use crate::classical::symbolic::native_lanes;

/// Members per parallel chunk of the lanes path: four batches of lanes (every member takes
/// the same steps, so a chunk has no tail to balance; 1000 members make 16 chunks with 16
/// lanes, enough for two threads). The split changes no result.
pub(super) fn chunk() -> usize {
    4 * native_lanes()
}

/// Whether `plan` runs its members in lanes: a splitting method keeping final states or
/// strided trajectories only (no reductions), over at least one step.
pub(super) fn in_lanes<S: MemberSource + ?Sized>(p: &Prepared<'_, S>, plan: &Plan) -> bool {
    p.method.needs_separable()
        && plan.reductions.is_empty()
        && p.early.is_none()
        && p.grid.n_steps() > 0
}

/// Members sharing one force: the first one's system runs them all.
struct Group {
    system: Box<dyn DynSystem>,
    /// Chunk positions of the members.
    members: Vec<usize>,
}

/// Runs the members `first..first + steps.len()` (rows of `width` in `rows`) as
/// [`run_member`] would, in lanes where they share a force; returns the error of the lowest
/// failing member, named by its index.
#[allow(clippy::too_many_arguments)]
pub(super) fn run_chunk<S: MemberSource + ?Sized>(
    p: &Prepared<'_, S>,
    plan: &Plan,
    first: usize,
    rows: &mut [f64],
    steps: &mut [usize],
    width: usize,
    stop: &AtomicBool,
    done: &AtomicUsize,
) -> Result<()> {
    let count = steps.len();
    let dim = p.dim;
    let t0 = p.grid.t0();
    let mut starts = vec![0.0; count * dim];
    let mut alone = vec![false; count];
    let mut groups: Vec<Group> = Vec::new();
    for j in 0..count {
        let index = first + j;
        let system = match p.source.build(index, t0) {
            Ok(s) if s.dynamical().state_dim() == dim => s,
            _ => {
                alone[j] = true;
                continue;
            }
        };
        starts[j * dim..(j + 1) * dim].copy_from_slice(system.dynamical().state());
        let Some(lanes) = system
            .dynamical()
            .splitting_lanes()
            .filter(|l| l.accepts(p.method))
        else {
            if j == 0 {
                // The first member has no lanes force (nor, as a rule, its kind): all run
                // alone, each built once more by its run, as without lanes.
                alone.fill(true);
                break;
            }
            alone[j] = true;
            continue;
        };
        let same = |g: &&mut Group| {
            p.source.same_system(first + g.members[0], index)
                || g.system
                    .dynamical()
                    .splitting_lanes()
                    .is_some_and(|o| o.same_force_as(lanes))
        };
        match groups.iter_mut().find(same) {
            Some(g) => g.members.push(j),
            None => groups.push(Group {
                system,
                members: vec![j],
            }),
        }
    }
    let n = p.grid.n_steps();
    let kept = |step: usize| -> Option<usize> {
        let k = plan.stride?;
        if step.is_multiple_of(k) {
            Some(step / k)
        } else if step == n {
            Some(Sampling::Stride(k).count(n) - 1)
        } else {
            None
        }
    };
    let width_lanes = native_lanes();
    let should_stop = || stop.load(Ordering::Relaxed);
    for g in &groups {
        let Some(force) = g.system.dynamical().splitting_lanes() else {
            continue;
        };
        for batch in g.members.chunks(width_lanes) {
            let batch_starts: Vec<f64> = batch
                .iter()
                .flat_map(|&j| starts[j * dim..(j + 1) * dim].iter().copied())
                .collect();
            // The trajectory's first row is the initial state, as `integrate` stores it.
            if plan.stride.is_some() {
                for &j in batch {
                    let at = j * width + p.final_width;
                    rows[at..at + dim].copy_from_slice(&starts[j * dim..(j + 1) * dim]);
                }
            }
            let mut record = |m: usize, step: usize, y: &[f64]| {
                let row = &mut rows[batch[m] * width..][..width];
                if step == n {
                    row[..p.final_width].copy_from_slice(&y[..p.final_width]);
                }
                if let Some(r) = kept(step) {
                    let at = p.final_width + r * dim;
                    row[at..at + dim].copy_from_slice(y);
                }
            };
            let failed = force.run_lanes(
                width_lanes,
                p.method,
                Batch {
                    starts: &batch_starts,
                    grid: &p.grid,
                    every: plan.stride,
                    check_every: OBSERVE_EVERY,
                    record: &mut record,
                    stop: &should_stop,
                },
            );
            let failed = match failed {
                Ok(failed) => failed,
                Err(e @ Error::Interrupted { .. }) => return Err(e),
                // Not run in lanes after all: each member's own run says why.
                Err(_) => vec![true; batch.len()],
            };
            for (&j, failed) in batch.iter().zip(failed) {
                if failed {
                    alone[j] = true;
                } else {
                    steps[j] = n;
                    done.fetch_add(1, Ordering::Relaxed);
                }
            }
        }
    }
    for j in (0..count).filter(|&j| alone[j]) {
        let index = first + j;
        if stop.load(Ordering::Relaxed) {
            return Err(Error::Interrupted { t: f64::NAN });
        }
        let row = &mut rows[j * width..(j + 1) * width];
        steps[j] = run_member(p, plan, index, row, stop).map_err(|e| match e {
            Error::Interrupted { .. } => e,
            e => in_member(index, e),
        })?;
        done.fetch_add(1, Ordering::Relaxed);
    }
    Ok(())
}
