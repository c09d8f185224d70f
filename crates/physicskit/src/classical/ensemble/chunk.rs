//! The chunk runner of the lanes paths: one skeleton for the splitting methods' members
//! (`lanes.rs`) and the `taylor` method's (`taylor.rs`), which differ only in how a member
//! joins a group and how a group runs ([`Kind`]).
//!
//! Each member of the chunk is built once (by the checks before the run, which keep it for
//! the chunk, or here). Members whose systems are the same apart from their
//! initial states ([`MemberSource::same_system`]), or whose kind says they share a form (an
//! equal force, equal Taylor recurrences: [`Kind::shares`]), form a group, and each group runs
//! in lanes ([`Kind::run`]); the states the lanes report are written into the members' rows as
//! `run_member` lays them out. The reductions that read the member's steps (energy error,
//! first events) are computed from the states the lanes report at every step
//! ([`Stepwise`]), with the bits of the member's own run; the chaos reductions (max Lyapunov
//! exponent, SALI), which integrate deviation vectors on a flow of their own, then run member
//! by member, as `run_member` runs them. A member that cannot run in lanes (no lanes form, a state of
//! another length) or whose lanes run fails is marked alone and then run by `run_member`, so
//! its error is its own run's, named by its index.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use super::reduction::Stepwise;
use super::{in_member, run_member, MemberSource, Plan, Prepared, StopFlag, OBSERVE_EVERY};
use crate::classical::core::{Error, Result, TimeGrid};
use crate::classical::integrators::lanes::Record;
use crate::classical::integrators::{Method, Sampling, Tolerances};
use crate::classical::model::DynSystem;

/// One kind of lanes path: what the members of a group share and how a group runs.
pub(super) trait Kind {
    /// What a group's members share beyond their system (the Taylor form; nothing for a
    /// splitting method, whose lanes force is the system itself).
    type Form;

    /// The form of a member that leads a new group; `None`: the member runs alone.
    fn form(&self, system: &dyn DynSystem) -> Option<Self::Form>;

    /// Whether the member `(system, form)` runs in the group led by `(lead, lead_form)`.
    fn shares(&self, lead: Member<'_, Self::Form>, member: Member<'_, Self::Form>) -> bool;

    /// Runs the members of `run.starts` in lanes on the group led by `lead`.
    ///
    /// # Errors
    /// [`Error::Interrupted`] when `run.stop` is set; an error of the whole group (not of one
    /// member: those go to `run.failed`).
    fn run(&self, lead: Member<'_, Self::Form>, run: Lanes<'_>) -> Result<()>;
}

/// A member as a [`Kind`] sees it: its system and its form.
pub(super) type Member<'a, F> = (&'a dyn DynSystem, &'a F);

/// One group's run in lanes.
pub(super) struct Lanes<'a> {
    /// The members' initial states, one row of the state's length each.
    pub starts: &'a [f64],
    /// The output grid.
    pub grid: &'a TimeGrid,
    /// The method.
    pub method: Method,
    /// An adaptive method's tolerances (`None`: the defaults).
    pub tolerances: Option<Tolerances>,
    /// The steps to report besides the last: every `k`-th (`None`: only the last). A kind
    /// may report more steps; the runner keeps those it needs.
    pub every: Option<usize>,
    /// Whether the reductions read each step's energy (a kind that computes it alongside
    /// the states gives it to `record`).
    pub energy: bool,
    /// `record(member, step, state, energy)`: member `member`'s state at step `step` of the
    /// grid (`1..=n_steps`), in the order of the steps, with its energy where the kind
    /// computed it (bit for bit the member's own `energy`), else `None`.
    pub record: &'a mut Record<'a>,
    /// Where the maximum energy error is the only reduction that reads the steps:
    /// `largest_error(member, error)`, for a kind that folds it over every step itself and
    /// then need not report them (NaN where an energy was not finite). A kind that does not
    /// fold it reports every step.
    pub largest_error: Option<&'a mut dyn FnMut(usize, f64)>,
    /// `failed(member)`: the member's run failed; it reports no more states.
    pub failed: &'a mut dyn FnMut(usize),
    /// Stops the run with [`Error::Interrupted`].
    pub stop: &'a AtomicBool,
}

/// A group: the members (chunk positions; the first leads) and the lead's form.
struct Group<F> {
    form: F,
    members: Vec<usize>,
}

/// One chunk of members: the members `first..first + steps.len()`, their output rows of
/// `width` in `rows` and the steps each took, with the run's stop flag and count of members
/// done.
pub(super) struct Chunk<'a> {
    pub first: usize,
    pub rows: &'a mut [f64],
    pub steps: &'a mut [usize],
    pub width: usize,
    pub stop: &'a AtomicBool,
    pub done: &'a AtomicUsize,
}

/// Runs the members of chunk `c` at the positions `members`, one after another, each by
/// [`run_member`]; returns the error of the first that fails, named by its index.
pub(super) fn run_alone<S: MemberSource + ?Sized>(
    p: &Prepared<'_, S>,
    plan: &Plan,
    c: &mut Chunk<'_>,
    members: impl IntoIterator<Item = usize>,
) -> Result<()> {
    for j in members {
        let index = c.first + j;
        if c.stop.load(Ordering::Relaxed) {
            return Err(Error::Interrupted { t: f64::NAN });
        }
        let row = &mut c.rows[j * c.width..(j + 1) * c.width];
        c.steps[j] = run_member(p, plan, index, row, c.stop).map_err(|e| match e {
            Error::Interrupted { .. } => e,
            e => in_member(index, e),
        })?;
        c.done.fetch_add(1, Ordering::Relaxed);
    }
    Ok(())
}

/// Runs the members of chunk `c` as [`run_member`] would, in lanes where `kind` groups them;
/// returns the error of the lowest failing member, named by its index.
pub(super) fn run_chunk<K: Kind, S: MemberSource + ?Sized>(
    kind: &K,
    p: &Prepared<'_, S>,
    plan: &Plan,
    mut c: Chunk<'_>,
) -> Result<()> {
    let (first, width, stop) = (c.first, c.width, c.stop);
    let count = c.steps.len();
    let dim = p.dim;
    // Chunk position -> its system and initial state; members left to run alone.
    let mut systems: Vec<Option<Box<dyn DynSystem>>> = Vec::with_capacity(count);
    let mut starts = vec![0.0; count * dim];
    let mut alone = vec![false; count];
    let mut groups: Vec<Group<K::Form>> = Vec::new();
    for j in 0..count {
        let index = first + j;
        let system = match p.member(index) {
            Ok(s) if s.dynamical().state_dim() == dim => s,
            _ => {
                alone[j] = true;
                systems.push(None);
                continue;
            }
        };
        starts[j * dim..(j + 1) * dim].copy_from_slice(system.dynamical().state());
        let same = groups
            .iter_mut()
            .find(|g| p.source.same_system(first + g.members[0], index));
        if let Some(g) = same {
            g.members.push(j);
            systems.push(Some(system));
            continue;
        }
        let Some(form) = kind.form(&*system) else {
            if j == 0 {
                // The first member has no lanes form (nor, as a rule, its kind): all run
                // alone, each built once more by its run, as without lanes.
                alone.fill(true);
                break;
            }
            alone[j] = true;
            systems.push(None);
            continue;
        };
        let shares = |g: &&mut Group<K::Form>| {
            let lead = systems[g.members[0]].as_deref();
            lead.is_some_and(|lead| kind.shares((lead, &g.form), (&*system, &form)))
        };
        match groups.iter_mut().find(shares) {
            Some(g) => g.members.push(j),
            None => groups.push(Group {
                form,
                members: vec![j],
            }),
        }
        systems.push(Some(system));
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
    let mut stepwise = Stepwise::new(&plan.reductions, count, dim);
    // Every step when a reduction reads them, else the kept trajectory's (a kind that folds
    // the energy error itself needs no more, and reports every step where it cannot).
    let folds = stepwise.reads_only_energy();
    let every = if stepwise.reads_steps() && !folds {
        Some(1)
    } else {
        plan.stride
    };
    let reduced_at = p.final_width + p.kept_rows * dim;
    let reads_energy = stepwise.reads_energy();
    for g in &groups {
        let Some(lead) = systems[g.members[0]].as_deref() else {
            continue;
        };
        let group_starts: Vec<f64> = g
            .members
            .iter()
            .flat_map(|&j| starts[j * dim..(j + 1) * dim].iter().copied())
            .collect();
        for &j in &g.members {
            let start = &starts[j * dim..(j + 1) * dim];
            // The trajectory's first row is the initial state, as `integrate` stores it.
            if plan.stride.is_some() {
                let at = j * width + p.final_width;
                c.rows[at..at + dim].copy_from_slice(start);
            }
            if let Some(system) = systems[j].as_deref() {
                stepwise.start(j, system, p.grid.t0(), start);
            }
        }
        let mut record = |m: usize, step: usize, y: &[f64], energy: Option<f64>| {
            let j = g.members[m];
            let row = &mut c.rows[j * width..][..width];
            if step == n {
                row[..p.final_width].copy_from_slice(&y[..p.final_width]);
            }
            if let Some(r) = kept(step) {
                let at = p.final_width + r * dim;
                row[at..at + dim].copy_from_slice(y);
            }
            if let Some(system) = systems[j].as_deref() {
                stepwise.step(j, system, &p.grid, step, y, energy);
            }
        };
        let mut failed = |m: usize| alone[g.members[m]] = true;
        let mut largest: Vec<Option<f64>> = vec![None; g.members.len()];
        let mut fold = |m: usize, error: f64| largest[m] = Some(error);
        kind.run(
            (lead, &g.form),
            Lanes {
                starts: &group_starts,
                grid: &p.grid,
                method: p.method,
                tolerances: plan.tolerances,
                every,
                energy: reads_energy,
                record: &mut record,
                largest_error: folds.then_some(&mut fold as &mut dyn FnMut(usize, f64)),
                failed: &mut failed,
                stop,
            },
        )?;
        for (&j, error) in g.members.iter().zip(largest) {
            if let Some(error) = error {
                stepwise.largest_energy_error(j, error);
            }
        }
        for &j in &g.members {
            alone[j] |= stepwise.spoilt(j);
            if alone[j] {
                continue;
            }
            let Some(system) = systems[j].as_deref() else {
                continue;
            };
            // The chaos reductions, member by member on their own flows.
            let start = &starts[j * dim..(j + 1) * dim];
            let row = &mut c.rows[j * width..(j + 1) * width];
            let reduced = plan.reductions.iter().zip(stepwise.values(j));
            for (k, (r, &value)) in reduced.enumerate() {
                row[reduced_at + k] = if r.is_stepwise() {
                    value
                } else {
                    let mut flag = StopFlag(stop);
                    let own = r.on_own_flow(
                        system,
                        p.method,
                        start,
                        &p.grid,
                        Some(&mut flag),
                        OBSERVE_EVERY,
                    );
                    match own {
                        Ok(v) => v,
                        Err(e @ Error::Interrupted { .. }) => return Err(e),
                        // Its own run reports it, named by its index.
                        Err(_) => {
                            alone[j] = true;
                            break;
                        }
                    }
                };
            }
            if !alone[j] {
                c.steps[j] = n;
                c.done.fetch_add(1, Ordering::Relaxed);
            }
        }
    }
    run_alone(p, plan, &mut c, (0..count).filter(|&j| alone[j]))
}
