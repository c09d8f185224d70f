//! Alignment indices: SALI (Skokos, J. Phys. A 34, 10029–10043, 2001) and GALI_k (Skokos,
//! Bountis & Antonopoulos, Physica D 231, 30–54, 2007).
//!
//! `k` deviation vectors follow the tangent dynamics of the orbit ([`Flow::step_tangent`]).
//! Every `renormalize_every` steps each is rescaled to unit length, `u_i = w_i / |w_i|`
//! (never orthogonalized: their alignment is what is measured), and
//!
//! ```text
//! SALI   = min(|u_1 + u_2|, |u_1 - u_2|)
//! GALI_k = |u_1 ∧ ... ∧ u_k| = Π R_ii   (QR factorization of [u_1 .. u_k])
//! ```
//!
//! On a chaotic orbit every vector turns towards the most unstable direction: SALI and GALI_2
//! fall as `exp(-(λ_1 - λ_2) t)`, GALI_k as `exp(-Σ_{j≥2} (λ_1 - λ_j) t)`. On a regular orbit
//! of an `N`-degree-of-freedom Hamiltonian system the vectors fall onto the torus's tangent
//! space, where SALI stays near a positive value and GALI_k (`k ≤ N`) too. The crossing of
//! [`CHAOS_THRESHOLD`] = 1e-8 classifies an orbit as chaotic (Skokos 2001 uses this value:
//! below it the two unit vectors agree to eight digits, far beyond what a regular orbit's
//! slowly rotating tangent vectors reach, yet above the 1e-16 where rounding makes the index
//! meaningless).

use super::lyapunov::{check_vectors, gram_schmidt, initial_vectors};
use super::section::Continuation;
use super::watch::AnalysisOptions;
use crate::classical::core::error::check_finite;
use crate::classical::core::{Result, TimeGrid};
use crate::classical::integrators::Flow;
use crate::classical::integrators::Method;
use crate::classical::model::erased::DynSystem;

/// The index below which an orbit is called chaotic (see the module docs).
pub const CHAOS_THRESHOLD: f64 = 1e-8;

/// What an alignment index says of an orbit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// The index fell below [`CHAOS_THRESHOLD`].
    Chaotic,
    /// It did not, over the time computed (a regular orbit, or a weakly chaotic one that
    /// needs a longer run).
    Regular,
}

impl Verdict {
    /// The verdict on an index history: chaotic once any value is below [`CHAOS_THRESHOLD`].
    pub fn of(index: &[f64]) -> Self {
        if index.iter().any(|&v| v < CHAOS_THRESHOLD) {
            Verdict::Chaotic
        } else {
            Verdict::Regular
        }
    }

    /// `"chaotic"` or `"regular"`.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Chaotic => "chaotic",
            Verdict::Regular => "regular",
        }
    }
}

/// Which index to compute.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Alignment {
    /// SALI (two vectors).
    Sali,
    /// GALI_k with `k` vectors.
    Gali(usize),
}

impl Alignment {
    fn vectors(self) -> usize {
        match self {
            Alignment::Sali => 2,
            Alignment::Gali(k) => k,
        }
    }
}

/// An alignment index against time.
#[derive(Debug, Clone, PartialEq)]
pub struct AlignmentIndex {
    /// Times, from `t0` (index 1 for GALI, √2 for SALI: the vectors start orthonormal).
    pub t: Vec<f64>,
    /// The index at each time.
    pub index: Vec<f64>,
    /// The smallest index of the run, over every evaluation, kept or not
    /// ([`AnalysisOptions::history_stride`]).
    pub minimum: f64,
}

impl AlignmentIndex {
    /// The verdict on every evaluation of the run, kept or not: [`Verdict::of`] its minimum.
    pub fn verdict(&self) -> Verdict {
        Verdict::of(&[self.minimum])
    }
}

/// The unit vectors' index; `w` is normalized in place, `q` and `r` are scratch.
fn index_of(
    which: Alignment,
    w: &mut [f64],
    dim: usize,
    q: &mut [f64],
    r: &mut [f64],
    t: f64,
) -> Result<f64> {
    for v in w.chunks_exact_mut(dim) {
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(norm.is_finite() && norm > 0.0) {
            return Err(crate::classical::core::Error::NonFinite {
                name: "deviation vector".into(),
                t,
            });
        }
        let inv = 1.0 / norm;
        v.iter_mut().for_each(|x| *x *= inv);
    }
    Ok(match which {
        Alignment::Sali => {
            let (u1, u2) = w.split_at(dim);
            let (mut plus, mut minus) = (0.0, 0.0);
            for (a, b) in u1.iter().zip(u2) {
                plus += (a + b) * (a + b);
                minus += (a - b) * (a - b);
            }
            plus.sqrt().min(minus.sqrt())
        }
        Alignment::Gali(_) => {
            q.copy_from_slice(w);
            match gram_schmidt(q, dim, r, t) {
                Ok(()) => r.iter().product(),
                // Vectors aligned to rounding: a zero volume.
                Err(_) => 0.0,
            }
        }
    })
}

/// The alignment index `which` of the orbit from `state0` over `grid` on `flow` (built for at
/// least its number of vectors), evaluated every `renormalize_every` steps and at the end. The
/// run stops early once the index is below `stop_below` (0 never stops), which saves the rest
/// of a chaotic orbit when only the verdict matters. `options` has the observer and which
/// evaluations to keep ([`AnalysisOptions`]: the start, every `history_stride`-th and the last
/// are kept; the minimum is taken over all).
///
/// # Errors
/// [`Error::InvalidParameter`](crate::classical::Error::InvalidParameter) for a number of
/// vectors outside `2..=dim` (SALI needs a state of 2 or more), or `renormalize_every = 0`;
/// [`Error::NonFinite`](crate::classical::Error::NonFinite) for a diverging orbit;
/// [`Error::TrajectoryTooLarge`](crate::classical::Error::TrajectoryTooLarge) for a history
/// that would not fit in memory; [`Error::Interrupted`](crate::classical::Error::Interrupted)
/// when the observer stops the run; whatever the system reports.
pub fn alignment_on_flow(
    flow: &mut dyn Flow,
    state0: &[f64],
    grid: &TimeGrid,
    which: Alignment,
    renormalize_every: usize,
    stop_below: f64,
    mut options: AnalysisOptions<'_>,
) -> Result<(AlignmentIndex, Continuation)> {
    let n = flow.dim();
    let k = which.vectors();
    check_vectors(k, n, renormalize_every, "k")?;
    if k < 2 {
        return Err(crate::classical::core::Error::invalid(
            "k",
            k as f64,
            "an alignment index needs at least 2 vectors",
        ));
    }
    check_finite("state", state0, grid.t0())?;
    let mut y = vec![0.0; n];
    flow.enter(grid.t0(), state0, &mut y)?;
    let mut w = initial_vectors(k, n)?;
    let mut q = vec![0.0; k * n];
    let mut r = vec![0.0; k];
    let steps = grid.n_steps();
    // The start, then the evaluations, thinned: evaluation `e` (1-based) is row `e - 1`.
    let thinning = options.thinning(steps.div_ceil(renormalize_every), 2)?;
    let mut out = AlignmentIndex {
        t: Vec::with_capacity(thinning.kept() + 1),
        index: Vec::with_capacity(thinning.kept() + 1),
        minimum: index_of(which, &mut w, n, &mut q, &mut r, grid.t0())?,
    };
    out.t.push(grid.t0());
    out.index.push(out.minimum);
    let dt = grid.dt();
    let mut t_end = grid.t0();
    let mut watch = options.watch(steps);
    let mut row = 0;
    for i in 0..steps {
        flow.step_tangent(grid.time(i), &mut y, &mut w, dt)?;
        let done = i + 1;
        if done % renormalize_every == 0 || done == steps {
            t_end = grid.time(done);
            check_finite("state", &y, t_end)?;
            let v = index_of(which, &mut w, n, &mut q, &mut r, t_end)?;
            out.minimum = out.minimum.min(v);
            // The row that ends a run early is kept too.
            if thinning.keeps(row) || v < stop_below {
                out.t.push(t_end);
                out.index.push(v);
            }
            row += 1;
            if v < stop_below {
                break;
            }
        }
        watch.tick(done, grid.time(done))?;
    }
    let mut state = state0.to_vec();
    flow.leave(t_end, &y, &mut state)?;
    Ok((out, Continuation { state, t: t_end }))
}

/// SALI at the end of the run from `state0` over `grid` on `flow`, or where it fell below
/// `stop_below` (0: the end of the run; no history kept): the last value of
/// [`alignment_on_flow`]'s index, so with `stop_below = 0` the same bits as the last value of
/// [`alignment_index`] with [`Alignment::Sali`] for the same system, method and grid. The
/// chaos maps and the ensembles' per-member reduction run it.
///
/// # Errors
/// As [`alignment_on_flow`].
pub(crate) fn sali_on_flow(
    flow: &mut dyn Flow,
    state0: &[f64],
    grid: &TimeGrid,
    renormalize_every: usize,
    stop_below: f64,
    options: AnalysisOptions<'_>,
) -> Result<f64> {
    let options = options.with_history_stride(usize::MAX);
    let (index, _) = alignment_on_flow(
        flow,
        state0,
        grid,
        Alignment::Sali,
        renormalize_every,
        stop_below,
        options,
    )?;
    Ok(index.index.last().copied().unwrap_or(f64::NAN))
}

/// SALI (`which = Alignment::Sali`) or GALI_k of `system`'s orbit over `t_span` with step `dt`
/// and `method` (the system's default for `None`), every `renormalize_every` steps. The system
/// is left at the end of the run.
///
/// # Errors
/// As [`alignment_on_flow`]; [`Error::InvalidTimeSpan`](crate::classical::Error); an
/// unsupported method.
pub fn alignment_index<S: DynSystem + ?Sized>(
    system: &mut S,
    t_span: (f64, f64),
    dt: f64,
    method: Option<Method>,
    which: Alignment,
    renormalize_every: usize,
) -> Result<AlignmentIndex> {
    let grid = TimeGrid::new(t_span, dt)?;
    let method = method.unwrap_or_else(|| system.default_method());
    let state0 = system.dynamical().state().to_vec();
    let (index, end) = {
        let mut flow = system.flow(method, which.vectors())?;
        alignment_on_flow(
            flow.as_mut(),
            &state0,
            &grid,
            which,
            renormalize_every,
            0.0,
            AnalysisOptions::default(),
        )?
    };
    system.reset(Some(&end.state), end.t)?;
    Ok(index)
}
