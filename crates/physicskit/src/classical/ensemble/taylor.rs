//! The `taylor` method's members in SIMD lanes: members that share a Taylor form run `L` at
//! a time on one program ([`integrate_batch`]; [`native_lanes`]: 16 with AVX-512, 8 with
//! AVX2, else 4), each with exactly the outputs of its own `integrate`.
//!
//! Members whose systems are the same apart from their initial states
//! ([`MemberSource::same_system`](super::MemberSource::same_system)) take the Taylor form built for the first of them; others
//! build theirs, and members with equal recurrences ([`TaylorProgram::same_recurrences`])
//! share one (`chunk.rs`). A member without a Taylor form (the error its `integrate`
//! reports), or whose batch run fails, runs alone by `run_member`, so its error is its own
//! run's.

use std::sync::atomic::Ordering;

use super::chunk::{Kind, Lanes, Member};
use crate::classical::core::Result;
use crate::classical::integrators::taylor_batch::integrate_batch;
use crate::classical::integrators::{Method, TaylorField};
use crate::classical::model::DynSystem;
use crate::classical::symbolic::{native_lanes, TaylorProgram};

/// Members per parallel chunk of the lanes path, for `n` members on `threads` threads: about
/// a quarter of each thread's share (at least 64, at most 1024). A chunk's lanes run out of
/// members one by one at its end (members take different numbers of steps), and those
/// expansions still cost all lanes: long chunks make that tail a small part of the work, and
/// four per thread still balance the threads. The split changes no result.
pub(super) fn chunk(n: usize, threads: usize) -> usize {
    (n / (4 * threads.max(1))).clamp(64, 1024)
}

/// Whether a plan with `method` runs its members in lanes: the `taylor` method, whatever it
/// keeps (reductions are computed from the lanes' states, `chunk.rs`). The engine runs a plan
/// of events only, or of no steps, member by member whatever the method.
pub(super) fn in_lanes(method: Method) -> bool {
    method == Method::Taylor
}

/// The `taylor` method's [`Kind`]: a group is the members of one Taylor form (its program),
/// run by [`integrate_batch`] in `L` lanes.
pub(super) struct Taylor;

impl Kind for Taylor {
    type Form = Box<dyn TaylorField>;

    fn form(&self, system: &dyn DynSystem) -> Option<Self::Form> {
        let field = system.dynamical().taylor_field()?.ok()?;
        let fits = field.dim() == system.dynamical().state_dim();
        (fits && TaylorProgram::from_field(&*field).is_some()).then_some(field)
    }

    fn shares(&self, (_, lead): Member<'_, Self::Form>, (_, form): Member<'_, Self::Form>) -> bool {
        match (
            TaylorProgram::from_field(&**lead),
            TaylorProgram::from_field(&**form),
        ) {
            (Some(a), Some(b)) => a.same_recurrences(b),
            _ => false,
        }
    }

    fn run(&self, (_, field): Member<'_, Self::Form>, run: Lanes<'_>) -> Result<()> {
        let Some(program) = TaylorProgram::from_field(&**field) else {
            // Not a lead `form` accepted: each member's own run says why.
            (0..run.starts.len() / field.dim()).for_each(run.failed);
            return Ok(());
        };
        match native_lanes() {
            16 => run_lanes::<16>(program, run),
            8 => run_lanes::<8>(program, run),
            _ => run_lanes::<4>(program, run),
        }
    }
}

/// The members of `run` in `L` lanes on `program`.
fn run_lanes<const L: usize>(program: &TaylorProgram, run: Lanes<'_>) -> Result<()> {
    let Lanes {
        starts,
        grid,
        tolerances,
        record,
        failed,
        stop,
        ..
    } = run;
    integrate_batch(
        &mut program.lanes::<L>(),
        starts,
        grid,
        tolerances.unwrap_or_default(),
        |m, step, y| record(m, step, y, None),
        |m, _| failed(m),
        || stop.load(Ordering::Relaxed),
    )
}
