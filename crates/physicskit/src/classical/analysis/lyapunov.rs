//! Lyapunov exponents by the method of Benettin, Galgani, Giorgilli & Strelcyn (Meccanica 15,
//! 9–20 and 21–30, 1980).
//!
//! `k` deviation vectors `w_1..w_k` follow the tangent dynamics of the orbit
//! ([`Flow::step_tangent`]: the exact tangent map of a splitting method, or the variational
//! equations integrated by the method). Every `m` steps (`renormalize_every`) they are
//! re-orthonormalized by a QR factorization `W = Q R` (modified Gram–Schmidt, vectors in their
//! order), `W ← Q`, and
//!
//! ```text
//! λ_i(t) = (1 / (t - t0)) Σ ln R_ii
//! ```
//!
//! over all renormalizations so far. `λ_1 ≥ λ_2 ≥ ...` emerge in the vectors' order as `t`
//! grows (the `i`-th running sum measures the growth of `i`-dimensional volumes).
//!
//! Guarantees that follow from the tangent dynamics:
//! - a splitting method's tangent map has determinant one exactly, so with `k = dim` the
//!   estimates sum to zero up to rounding at every renormalization;
//! - for a Hamiltonian flow the exponents come in pairs `λ_i = -λ_{dim+1-i}`: QR's finite-time
//!   estimates pair only as `t → ∞`;
//! - for an ODE, `Σ λ_i` over the full spectrum is the time average of the divergence `tr Df`
//!   (Liouville).
//!
//! Cost: one tangent step per step (about `1 + k` times the orbit's work for a method on a
//! field, plus a Jacobian; `benchmarks/README.md` has the measured figures).
//!
//! The initial vectors are a fixed pseudo-random orthonormal set (splitmix64, then
//! Gram–Schmidt), so a run is reproducible and no vector starts in a special direction (along
//! the flow, or inside an invariant subspace).

use super::section::Continuation;
use super::watch::AnalysisOptions;
use crate::classical::core::error::check_finite;
use crate::classical::core::{Error, Result, TimeGrid};
use crate::classical::integrators::Flow;
use crate::classical::integrators::Method;
use crate::classical::model::erased::DynSystem;

/// Steps between re-orthonormalizations (Lyapunov) or evaluations of the index (SALI, GALI)
/// when the caller names none: the default of every front end (Python's `renormalize_every`,
/// the CLI's `--renormalize-every`, the gallery). Short enough that the deviation vectors grow
/// by at most `exp(10 h lambda)` between renormalizations, long enough that the QR step costs
/// little beside the tangent integration.
pub const DEFAULT_RENORMALIZE_EVERY: usize = 10;

/// The result of [`lyapunov_spectrum`].
#[derive(Debug, Clone, PartialEq)]
pub struct LyapunovSpectrum {
    /// The final estimates, sorted in descending order.
    pub exponents: Vec<f64>,
    /// The times of the renormalizations.
    pub t: Vec<f64>,
    /// The running estimates at each time of `t`, row-major `(len(t), k)`, in the vectors'
    /// (Gram–Schmidt) order.
    pub history: Vec<f64>,
    /// Number of exponents `k`.
    pub k: usize,
}

/// Checks `renormalize_every >= 1` and `1 <= k <= dim`: the counts every front end must
/// pass for `k` deviation vectors of a `dim`-dimensional state (`name` is the caller's name of
/// `k` in the message). Front ends call it before building a flow for `k` vectors.
///
/// # Errors
/// [`Error::InvalidParameter`].
pub fn check_vectors(k: usize, dim: usize, every: usize, name: &str) -> Result<()> {
    if every == 0 {
        return Err(Error::invalid("renormalize_every", 0.0, "must be >= 1"));
    }
    if k == 0 || k > dim {
        return Err(Error::invalid(
            name,
            k as f64,
            format!("must be between 1 and the state dimension {dim}"),
        ));
    }
    Ok(())
}

/// `k` orthonormal pseudo-random vectors of length `dim` (row-major), the same on every run.
pub(crate) fn initial_vectors(k: usize, dim: usize) -> Result<Vec<f64>> {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut w: Vec<f64> = (0..k * dim)
        .map(|_| {
            // splitmix64
            state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^= z >> 31;
            (z >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect();
    let mut r = vec![0.0; k];
    gram_schmidt(&mut w, dim, &mut r, 0.0)?;
    Ok(w)
}

/// Modified Gram–Schmidt on the rows of `w` (`k x dim`): `w ← Q`, `r[i] = R_ii`. Each row's
/// projections are removed twice ("twice is enough", Giraud et al. 2005), so `Q` stays
/// orthonormal to rounding even for nearly aligned vectors.
///
/// # Errors
/// [`Error::NonFinite`] at `t` if a vector is zero or not finite.
pub(crate) fn gram_schmidt(w: &mut [f64], dim: usize, r: &mut [f64], t: f64) -> Result<()> {
    let k = w.len() / dim;
    for (i, ri) in r.iter_mut().enumerate().take(k) {
        let (done, rest) = w.split_at_mut(i * dim);
        let v = &mut rest[..dim];
        for _ in 0..2 {
            for u in done.chunks_exact(dim) {
                let d: f64 = u.iter().zip(v.iter()).map(|(a, b)| a * b).sum();
                v.iter_mut().zip(u).for_each(|(x, a)| *x -= d * a);
            }
        }
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(norm.is_finite() && norm > 0.0) {
            return Err(Error::NonFinite {
                name: "deviation vector".into(),
                t,
            });
        }
        let inv = 1.0 / norm;
        v.iter_mut().for_each(|x| *x *= inv);
        *ri = norm;
    }
    Ok(())
}

/// The Lyapunov spectrum's first `k` exponents of the orbit from `state0` over `grid` on
/// `flow` (built for at least `k` vectors), renormalizing every `renormalize_every` steps and
/// at the end; and where the run ended. `options` has the observer and which rows of the
/// history to keep ([`AnalysisOptions`]; the exponents do not depend on it).
///
/// # Errors
/// [`Error::InvalidParameter`] for `k` outside `1..=dim` or `renormalize_every = 0`;
/// [`Error::NonFinite`] for a diverging orbit or deviation; [`Error::TrajectoryTooLarge`] for
/// a history that would not fit in memory; [`Error::Interrupted`] when the observer stops the
/// run; whatever the system reports.
pub fn lyapunov_on_flow(
    flow: &mut dyn Flow,
    state0: &[f64],
    grid: &TimeGrid,
    k: usize,
    renormalize_every: usize,
    mut options: AnalysisOptions<'_>,
) -> Result<(LyapunovSpectrum, Continuation)> {
    let n = flow.dim();
    check_vectors(k, n, renormalize_every, "n_exponents")?;
    check_finite("state", state0, grid.t0())?;
    let mut y = vec![0.0; n];
    flow.enter(grid.t0(), state0, &mut y)?;
    let mut w = initial_vectors(k, n)?;
    let mut r = vec![0.0; k];
    let mut sums = vec![0.0; k];
    let steps = grid.n_steps();
    let thinning = options.thinning(steps.div_ceil(renormalize_every), k + 1)?;
    let mut out = LyapunovSpectrum {
        exponents: Vec::new(),
        t: Vec::with_capacity(thinning.kept()),
        history: Vec::with_capacity(thinning.kept() * k),
        k,
    };
    let dt = grid.dt();
    let mut watch = options.watch(steps);
    let mut row = 0;
    for i in 0..steps {
        flow.step_tangent(grid.time(i), &mut y, &mut w, dt)?;
        let done = i + 1;
        if done % renormalize_every == 0 || done == steps {
            let t = grid.time(done);
            check_finite("state", &y, t)?;
            gram_schmidt(&mut w, n, &mut r, t)?;
            for (s, ri) in sums.iter_mut().zip(&r) {
                *s += ri.ln();
            }
            if thinning.keeps(row) {
                let elapsed = t - grid.t0();
                out.t.push(t);
                out.history.extend(sums.iter().map(|s| s / elapsed));
            }
            row += 1;
        }
        watch.tick(done, grid.time(done))?;
    }
    let elapsed = grid.t_end() - grid.t0();
    out.exponents = sums
        .iter()
        .map(|s| if elapsed > 0.0 { s / elapsed } else { 0.0 })
        .collect();
    out.exponents.sort_by(|a, b| b.total_cmp(a));
    let mut state = state0.to_vec();
    flow.leave(grid.t_end(), &y, &mut state)?;
    Ok((
        out,
        Continuation {
            state,
            t: grid.t_end(),
        },
    ))
}

/// The largest Lyapunov exponent at the end of the run from `state0` over `grid` on `flow`
/// (one deviation vector, no history kept): [`lyapunov_on_flow`] with `k = 1`, so the same
/// bits as [`max_lyapunov`]'s `exponents[0]` for the same system, method and grid. The chaos
/// maps and the ensembles' per-member reduction run it.
///
/// # Errors
/// As [`lyapunov_on_flow`].
pub(crate) fn max_exponent_on_flow(
    flow: &mut dyn Flow,
    state0: &[f64],
    grid: &TimeGrid,
    renormalize_every: usize,
    options: AnalysisOptions<'_>,
) -> Result<f64> {
    let options = options.with_history_stride(usize::MAX);
    let (spectrum, _) = lyapunov_on_flow(flow, state0, grid, 1, renormalize_every, options)?;
    Ok(spectrum.exponents[0])
}

/// The first `n_exponents` Lyapunov exponents (all for `None`) of `system`'s orbit over
/// `t_span` with step `dt` and `method` (the system's default for `None`), re-orthonormalizing
/// every `renormalize_every` steps. The system is left at the end of the run, as `integrate`
/// leaves it.
///
/// # Errors
/// As [`lyapunov_on_flow`]; [`Error::InvalidTimeSpan`]; [`Error::UnsupportedMethod`].
///
/// # Example
/// The pendulum's libration is regular: its largest exponent tends to zero.
///
/// ```
/// use physicskit::classical::analysis::lyapunov::lyapunov_spectrum;
/// use physicskit::classical::model::erased::Hamiltonian;
/// use physicskit::classical::examples::Pendulum;
///
/// let mut pendulum = Hamiltonian(Pendulum::new(1.0, 0.0, 1.0).unwrap());
/// let spectrum = lyapunov_spectrum(&mut pendulum, (0.0, 1000.0), 0.01, None, None, 10).unwrap();
/// assert!(spectrum.exponents[0] < 0.02);
/// assert!(spectrum.exponents.iter().sum::<f64>().abs() < 1e-12);
/// ```
pub fn lyapunov_spectrum<S: DynSystem + ?Sized>(
    system: &mut S,
    t_span: (f64, f64),
    dt: f64,
    method: Option<Method>,
    n_exponents: Option<usize>,
    renormalize_every: usize,
) -> Result<LyapunovSpectrum> {
    let grid = TimeGrid::new(t_span, dt)?;
    let method = method.unwrap_or_else(|| system.default_method());
    let state0 = system.dynamical().state().to_vec();
    let (spectrum, end) = {
        let mut flow = system.flow(method, n_exponents.unwrap_or(state0.len()))?;
        let k = n_exponents.unwrap_or(flow.dim());
        lyapunov_on_flow(
            flow.as_mut(),
            &state0,
            &grid,
            k,
            renormalize_every,
            AnalysisOptions::default(),
        )?
    };
    system.reset(Some(&end.state), end.t)?;
    Ok(spectrum)
}

/// The largest Lyapunov exponent: [`lyapunov_spectrum`] with one vector.
///
/// # Errors
/// As [`lyapunov_spectrum`].
pub fn max_lyapunov<S: DynSystem + ?Sized>(
    system: &mut S,
    t_span: (f64, f64),
    dt: f64,
    method: Option<Method>,
    renormalize_every: usize,
) -> Result<LyapunovSpectrum> {
    lyapunov_spectrum(system, t_span, dt, method, Some(1), renormalize_every)
}
