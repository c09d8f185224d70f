//! The `taylor` method's members in SIMD lanes: members that share a Taylor form run `L` at
//! a time on one program ([`integrate_batch`]; [`native_lanes`]: 16 with AVX-512, 8 with
//! AVX2, else 4), each with exactly the outputs of its own `integrate`.
//!
//! Members whose systems are the same apart from their initial states
//! ([`MemberSource::same_system`]) take the Taylor form built for the first of them; others
//! build theirs, and members with equal recurrences ([`TaylorProgram::same_recurrences`])
//! share one. A member without a Taylor form (the error its `integrate` reports), or whose
//! batch run fails, runs alone by `run_member`, so its error is its own run's. Plans with
//! reductions, which read every step, run members alone.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use super::{in_member, run_member, MemberSource, Plan, Prepared};
use crate::classical::core::{Error, Result};
use crate::classical::integrators::taylor_batch::integrate_batch;
use crate::classical::integrators::{Method, Sampling, TaylorField};
use crate::classical::symbolic::{native_lanes, TaylorProgram};

/// Members per parallel chunk of the lanes path, for `n` members on `threads` threads: about
/// a quarter of each thread's share (at least 64, at most 1024). A chunk's lanes run out of
/// members one by one at its end (members take different numbers of steps), and those
/// expansions still cost all lanes: long chunks make that tail a small part of the work, and
/// four per thread still balance the threads. The split changes no result.
pub(super) fn chunk(n: usize, threads: usize) -> usize {
    (n / (4 * threads.max(1))).clamp(64, 1024)
}

/// Whether `plan` runs its members in lanes: the `taylor` method keeping final states or
/// strided trajectories only (no reductions), over at least one step.
pub(super) fn in_lanes<S: MemberSource + ?Sized>(p: &Prepared<'_, S>, plan: &Plan) -> bool {
    p.method == Method::Taylor
        && plan.reductions.is_empty()
        && p.early.is_none()
        && p.grid.n_steps() > 0
}

/// Members sharing one Taylor form.
struct Group {
    field: Box<dyn TaylorField>,
    /// Chunk positions of the members.
    members: Vec<usize>,
}

/// Runs the members `first..first + steps.len()` (rows of `width` in `rows`) as
/// [`run_member`] would, in lanes where they share a Taylor form; returns the error of the
/// lowest failing member, named by its index.
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
    // Chunk position -> its initial state; members left to run alone.
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
        if let Some(g) = groups
            .iter_mut()
            .find(|g| p.source.same_system(first + g.members[0], index))
        {
            g.members.push(j);
            continue;
        }
        let field = match system.dynamical().taylor_field() {
            Some(Ok(field)) if field.dim() == dim => field,
            _ => {
                alone[j] = true;
                continue;
            }
        };
        let Some(program) = TaylorProgram::from_field(&*field) else {
            alone[j] = true;
            continue;
        };
        let same = |g: &&mut Group| {
            TaylorProgram::from_field(&*g.field).is_some_and(|q| q.same_recurrences(program))
        };
        match groups.iter_mut().find(same) {
            Some(g) => g.members.push(j),
            None => groups.push(Group {
                field,
                members: vec![j],
            }),
        }
    }
    for g in &groups {
        let Some(program) = TaylorProgram::from_field(&*g.field) else {
            continue;
        };
        let run = match native_lanes() {
            16 => run_group::<16, S>,
            8 => run_group::<8, S>,
            _ => run_group::<4, S>,
        };
        run(p, plan, program, g, &starts, rows, width, &mut alone, stop)?;
        for &j in &g.members {
            if !alone[j] {
                steps[j] = p.grid.n_steps();
                done.fetch_add(1, Ordering::Relaxed);
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

/// The members of `group` in `L` lanes on `program`, their outputs into their rows (final
/// state, then the kept trajectory rows, as `run_member` lays them out); a member whose run
/// fails is marked `alone`.
#[allow(clippy::too_many_arguments)]
fn run_group<const L: usize, S: MemberSource + ?Sized>(
    p: &Prepared<'_, S>,
    plan: &Plan,
    program: &TaylorProgram,
    group: &Group,
    starts: &[f64],
    rows: &mut [f64],
    width: usize,
    alone: &mut [bool],
    stop: &AtomicBool,
) -> Result<()> {
    let dim = p.dim;
    let n = p.grid.n_steps();
    let group_starts: Vec<f64> = group
        .members
        .iter()
        .flat_map(|&j| starts[j * dim..(j + 1) * dim].iter().copied())
        .collect();
    // The trajectory's first row is the initial state, as `integrate` stores it.
    if plan.stride.is_some() {
        for &j in &group.members {
            let at = j * width + p.final_width;
            rows[at..at + dim].copy_from_slice(&starts[j * dim..(j + 1) * dim]);
        }
    }
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
    let mut failed = Vec::new();
    integrate_batch(
        &mut program.lanes::<L>(),
        &group_starts,
        &p.grid,
        plan.tolerances.unwrap_or_default(),
        |m, step, y| {
            let row = &mut rows[group.members[m] * width..][..width];
            if step == n {
                row[..p.final_width].copy_from_slice(&y[..p.final_width]);
            }
            if let Some(r) = kept(step) {
                let at = p.final_width + r * dim;
                row[at..at + dim].copy_from_slice(y);
            }
        },
        |m, _| failed.push(group.members[m]),
        || stop.load(Ordering::Relaxed),
    )?;
    for j in failed {
        alone[j] = true;
    }
    Ok(())
}
