//! Poincaré sections: the points where a trajectory pierces a hyperplane `y_k = c`.
//!
//! A trajectory is integrated with a fixed step. When one step carries the section coordinate
//! `s = y_k - c` across zero in the requested direction, the crossing is located with
//! **Hénon's trick** (M. Hénon, "On the numerical computation of Poincaré maps", Physica D 5,
//! 412–414, 1982): from the state before the crossing, the equations of motion are rewritten
//! with `y_k` as the independent variable,
//!
//! ```text
//! dy_i/dy_k = f_i(y) / f_k(y),        dt/dy_k = 1 / f_k(y),
//! ```
//!
//! and integrated with RK4 from `y_k` to exactly `c`. The crossing state is then accurate to the
//! order of that RK4 step (error `O(|Δy_k|^5)`), not to the step of the sampling: no nearest
//! sample, no interpolation. The trick needs a transversal crossing (`f_k != 0`), which holds
//! for every crossing in the chosen direction except at tangencies; a step whose rewritten
//! equations produce non-finite values is counted in [`PoincareSection::skipped`] rather than
//! stored.
//!
//! The spec's Hénon–Heiles section is `y = 0` with `p_y > 0`: coordinate 1 of the state
//! `[x, y, px, py]`, value 0, direction [`Direction::Increasing`] (since `dy/dt = p_y`).

use crate::classical::core::error::{check_finite, check_finite_scalar};
use crate::classical::core::{Error, Result};
use crate::classical::integrators::{
    splitting, splitting::Coefficients, AdaptiveStepper, Dispatch, FieldStepper, FirstOrder, Rk4,
    SplittingStepper, VectorField,
};
use crate::classical::integrators::{HamiltonianSystem, Method};

/// Which way through the section a crossing must go to count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// `y_k` increases through the section value (`dy_k/dt > 0`).
    Increasing,
    /// `y_k` decreases through the section value.
    Decreasing,
    /// Either way.
    Both,
}

impl Direction {
    /// Whether a step from `before` to `after` (values of `g(y) - c` on either side of the
    /// section) crosses in this direction. A start exactly on the section does not count, so a
    /// crossing landing exactly on a step end is counted once, by the step that arrives there.
    pub fn crossed(self, before: f64, after: f64) -> bool {
        let up = before < 0.0 && after >= 0.0;
        let down = before > 0.0 && after <= 0.0;
        match self {
            Direction::Increasing => up,
            Direction::Decreasing => down,
            Direction::Both => up || down,
        }
    }
}

/// The hyperplane `y[coordinate] = value`, crossed in `direction`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    coordinate: usize,
    value: f64,
    direction: Direction,
}

impl Section {
    /// The plane `y[coordinate] = value` of the full state vector.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-finite `value`.
    pub fn new(coordinate: usize, value: f64, direction: Direction) -> Result<Self> {
        Ok(Self {
            coordinate,
            value: check_finite_scalar("value", value)?,
            direction,
        })
    }

    /// Index of the section coordinate in the state vector.
    pub fn coordinate(&self) -> usize {
        self.coordinate
    }

    /// Section value `c`.
    pub fn value(&self) -> f64 {
        self.value
    }

    /// Required crossing direction.
    pub fn direction(&self) -> Direction {
        self.direction
    }

    /// Whether a step from `before` to `after` (values of `y_k - c`) crosses in the requested
    /// direction. A start exactly on the plane does not count, so a crossing landing exactly
    /// on a step end is counted once, by the step that arrives there.
    fn crossed(&self, before: f64, after: f64) -> bool {
        self.direction.crossed(before, after)
    }
}

/// The crossings of one trajectory, in time order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PoincareSection {
    /// Crossing times.
    pub t: Vec<f64>,
    /// Crossing states, row-major `(n_crossings, state_dim)`; the section coordinate equals
    /// the section value up to rounding.
    pub states: Vec<f64>,
    /// State dimension (row length of `states`).
    pub dim: usize,
    /// Crossings detected but dropped because the rewritten equations were singular there
    /// (a tangency, `f_k = 0`).
    pub skipped: usize,
}

impl PoincareSection {
    /// Number of stored crossings.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether no crossing was stored.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// State at crossing `i`; `None` past the end.
    pub fn state(&self, i: usize) -> Option<&[f64]> {
        self.states.get(i * self.dim..(i + 1) * self.dim)
    }

    /// Component `j` of every crossing state (for example `x` and `px` for a plot).
    pub fn component(&self, j: usize) -> Vec<f64> {
        if j >= self.dim {
            return Vec::new();
        }
        self.states.chunks_exact(self.dim).map(|s| s[j]).collect()
    }
}

/// The field with `y_k` as the independent variable: extended state `[y, t]`,
/// `d[y, t]/dy_k = [f(y), 1] / f_k(y)`.
struct SectionTime<'a, F: ?Sized> {
    field: &'a F,
    k: usize,
}

impl<F: VectorField + ?Sized> VectorField for SectionTime<'_, F> {
    fn dim(&self) -> usize {
        self.field.dim() + 1
    }

    fn eval(&self, _s: f64, z: &[f64], dz: &mut [f64]) -> Result<()> {
        let n = self.field.dim();
        self.field.eval(z[n], &z[..n], &mut dz[..n])?;
        let inv = 1.0 / dz[self.k];
        dz[..n].iter_mut().for_each(|d| *d *= inv);
        dz[n] = inv;
        Ok(())
    }
}

/// Hénon's step: from `(t, y)` on one side of the section, integrates along the trajectory
/// until `y_k` equals the section value, using `y_k` as the independent variable
/// (`substeps` RK4 steps). Returns the crossing time and writes the crossing state into `out`.
///
/// Accurate when the crossing is transversal and `(t, y)` is within about one integration step
/// of the section.
///
/// # Errors
/// [`Error::DimensionMismatch`] if `y` or `out` do not match the field, `section` names a
/// coordinate past the state, or `substeps == 0`; [`Error::NonFinite`] at a tangency, where
/// `dy_k/dt = 0` makes the rewritten equations singular; whatever the field reports.
pub fn henon_step<F: VectorField + ?Sized>(
    field: &F,
    t: f64,
    y: &[f64],
    section: &Section,
    substeps: usize,
    out: &mut [f64],
) -> Result<f64> {
    HenonWork::new(field.dim()).step(field, t, y, section, substeps, out)
}

/// The buffers of [`henon_step`] (the extended state `[y, t]` and its RK4 stepper), kept by a
/// caller that locates crossings as it steps (the lab) so that a crossing allocates nothing.
#[derive(Debug, Clone)]
pub struct HenonWork {
    dim: usize,
    z: Vec<f64>,
    rk: Rk4,
}

impl HenonWork {
    /// Buffers for fields of dimension `dim`.
    pub fn new(dim: usize) -> Self {
        Self {
            dim,
            z: Vec::with_capacity(dim + 1),
            rk: Rk4::new(dim + 1),
        }
    }

    /// [`henon_step`] in these buffers (allocating nothing when `field.dim()` is the `dim`
    /// they were made for).
    ///
    /// # Errors
    /// As [`henon_step`].
    pub fn step<F: VectorField + ?Sized>(
        &mut self,
        field: &F,
        t: f64,
        y: &[f64],
        section: &Section,
        substeps: usize,
        out: &mut [f64],
    ) -> Result<f64> {
        let n = field.dim();
        check_dims(n, y.len(), section)?;
        if out.len() != n {
            return Err(Error::DimensionMismatch {
                name: "out".into(),
                expected: n,
                found: out.len(),
            });
        }
        if substeps == 0 {
            return Err(Error::invalid("substeps", 0.0, "must be >= 1"));
        }
        if self.dim != n {
            *self = Self::new(n);
        }
        self.z.clear();
        self.z.extend_from_slice(y);
        self.z.push(t);
        henon_into(field, section, substeps, &mut self.rk, &mut self.z)?;
        out.copy_from_slice(&self.z[..n]);
        Ok(self.z[n])
    }
}

/// Runs the Hénon step on the extended state `z = [y, t]` in place.
fn henon_into<F: VectorField + ?Sized>(
    field: &F,
    section: &Section,
    substeps: usize,
    rk: &mut Rk4,
    z: &mut [f64],
) -> Result<()> {
    let k = section.coordinate;
    let n = field.dim();
    let rewritten = SectionTime { field, k };
    let s0 = z[k];
    let h = (section.value - s0) / substeps as f64;
    for i in 0..substeps {
        rk.step(&rewritten, s0 + i as f64 * h, z, h)?;
    }
    z[k] = section.value;
    check_finite("section state", z, z[n])
}

fn check_dims(n: usize, found: usize, section: &Section) -> Result<()> {
    if found != n {
        return Err(Error::DimensionMismatch {
            name: "y0".into(),
            expected: n,
            found,
        });
    }
    if section.coordinate >= n {
        return Err(Error::DimensionMismatch {
            name: "section coordinate (must index the state)".into(),
            expected: n,
            found: section.coordinate,
        });
    }
    Ok(())
}

/// The options of a section run: step, end time and how many crossings to keep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionRun {
    /// Fixed integration step (positive).
    pub dt: f64,
    /// Integrate from `t0` until `t_end` ...
    pub t_end: f64,
    /// ... or until this many crossings are stored, whichever comes first.
    pub max_crossings: usize,
    /// RK4 substeps of each Hénon step (2 keeps its error well below that of the main steps).
    pub henon_substeps: usize,
}

impl SectionRun {
    /// A run with step `dt` to `t_end`, stopping early after `max_crossings`; two Hénon
    /// substeps.
    pub fn new(dt: f64, t_end: f64, max_crossings: usize) -> Self {
        Self {
            dt,
            t_end,
            max_crossings,
            henon_substeps: 2,
        }
    }

    fn validate(&self, t0: f64) -> Result<()> {
        if !(self.dt.is_finite() && self.dt > 0.0 && t0.is_finite() && self.t_end.is_finite())
            || self.t_end < t0
        {
            return Err(Error::InvalidTimeSpan {
                t0,
                t1: self.t_end,
                dt: self.dt,
                reason: "need a finite dt > 0 and t_end >= t0".into(),
            });
        }
        if self.henon_substeps == 0 {
            return Err(Error::invalid("henon_substeps", 0.0, "must be >= 1"));
        }
        Ok(())
    }
}

/// The shared stepping loop: `advance(t, y, h)` moves `y` by one step of the main integrator.
fn run_section<F, A>(
    field: &F,
    t0: f64,
    y0: &[f64],
    section: &Section,
    run: &SectionRun,
    mut advance: A,
) -> Result<PoincareSection>
where
    F: VectorField + ?Sized,
    A: FnMut(f64, &mut [f64], f64) -> Result<()>,
{
    let n = field.dim();
    check_dims(n, y0.len(), section)?;
    check_finite("y0", y0, t0)?;
    run.validate(t0)?;
    let k = section.coordinate;
    let mut y = y0.to_vec();
    let mut before = vec![0.0; n];
    let mut z = vec![0.0; n + 1];
    let mut rk = Rk4::new(n + 1);
    let mut out = PoincareSection {
        dim: n,
        ..PoincareSection::default()
    };
    let n_steps = ((run.t_end - t0) / run.dt).round() as usize;
    for i in 0..n_steps {
        if out.len() >= run.max_crossings {
            break;
        }
        let t = t0 + i as f64 * run.dt;
        before.copy_from_slice(&y);
        advance(t, &mut y, run.dt)?;
        check_finite("state", &y, t + run.dt)?;
        if section.crossed(before[k] - section.value, y[k] - section.value) {
            z[..n].copy_from_slice(&before);
            z[n] = t;
            match henon_into(field, section, run.henon_substeps, &mut rk, &mut z) {
                Ok(()) => {
                    out.t.push(z[n]);
                    out.states.extend_from_slice(&z[..n]);
                }
                Err(Error::NonFinite { .. }) => out.skipped += 1,
                Err(e) => return Err(e),
            }
        }
    }
    Ok(out)
}

/// The Poincaré section of the trajectory of `field` from `(t0, y0)`, integrated with RK4.
///
/// # Errors
/// [`Error::DimensionMismatch`] for a `y0` or section coordinate that does not fit the field,
/// [`Error::NonFinite`] for a non-finite `y0` or a diverging trajectory,
/// [`Error::InvalidTimeSpan`] for a bad `dt` or `t_end`; whatever the field reports.
///
/// # Example
/// The harmonic oscillator `x'' = -x` from `(1, 0)` crosses `x = 0` upwards at
/// `t = 3π/2 + 2πj` with velocity `+1`:
///
/// ```
/// use physicskit::classical::analysis::poincare::{poincare_section, Direction, Section, SectionRun};
/// use physicskit::classical::integrators::FirstOrder;
/// use physicskit::classical::examples::HarmonicOscillator;
///
/// let osc = HarmonicOscillator::new(1.0, 0.0, 1.0, 1.0).unwrap();
/// let section = Section::new(0, 0.0, Direction::Increasing).unwrap();
/// let run = SectionRun::new(0.01, 20.0, 10);
/// let cut = poincare_section(&FirstOrder(&osc), 0.0, &[1.0, 0.0], &section, &run).unwrap();
/// assert_eq!(cut.len(), 3);
/// assert!((cut.t[0] - 1.5 * std::f64::consts::PI).abs() < 1e-6);
/// assert!((cut.state(0).unwrap()[1] - 1.0).abs() < 1e-6);
/// ```
pub fn poincare_section<F: VectorField + ?Sized>(
    field: &F,
    t0: f64,
    y0: &[f64],
    section: &Section,
    run: &SectionRun,
) -> Result<PoincareSection> {
    let mut rk = Rk4::new(field.dim());
    run_section(field, t0, y0, section, run, |t, y, h| {
        rk.step(field, t, y, h)
    })
}

/// The Poincaré section of a separable Hamiltonian system from the state `y0 = [q, p]` at
/// `t0`, integrated with a symplectic splitting method such as `verlet` or `yoshida4` (so long
/// runs keep the energy surface); the crossings are located with the system's own vector field.
///
/// # Errors
/// [`Error::UnsupportedMethod`] for a method that is not a splitting method or a system it
/// cannot integrate; otherwise as [`poincare_section`].
pub fn poincare_section_separable<S: HamiltonianSystem>(
    system: &S,
    t0: f64,
    y0: &[f64],
    section: &Section,
    run: &SectionRun,
    method: Method,
) -> Result<PoincareSection> {
    method.dispatch(SeparableSection {
        system,
        t0,
        y0,
        section,
        run,
    })
}

/// The inputs of [`poincare_section_separable`], waiting for the method's kind.
struct SeparableSection<'a, S> {
    system: &'a S,
    t0: f64,
    y0: &'a [f64],
    section: &'a Section,
    run: &'a SectionRun,
}

impl<S: HamiltonianSystem> SeparableSection<'_, S> {
    fn not_splitting(method: Method) -> Result<PoincareSection> {
        Err(Error::UnsupportedMethod {
            method: method.name().into(),
            reason: "a separable section run uses a splitting method; use poincare_section \
                     (rk4) for other methods"
                .into(),
        })
    }
}

impl<S: HamiltonianSystem> Dispatch for SeparableSection<'_, S> {
    type Output = Result<PoincareSection>;

    fn splitting<const N: usize>(self, method: Method, weights: Coefficients<N>) -> Self::Output {
        let system = self.system;
        splitting::check_system(method, system)?;
        let ndof = system.ndof();
        let mut stepper = SplittingStepper::new(weights, ndof);
        run_section(
            &FirstOrder(system),
            self.t0,
            self.y0,
            self.section,
            self.run,
            |t, y, h| {
                let (q, p) = y.split_at_mut(ndof);
                stepper.step(system, t, q, p, h)
            },
        )
    }

    fn explicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        Self::not_splitting(method)
    }

    fn implicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        Self::not_splitting(method)
    }

    fn adaptive<St: AdaptiveStepper>(self, method: Method) -> Self::Output {
        Self::not_splitting(method)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::classical::examples::{HarmonicOscillator, Pendulum};

    /// For the oscillator `x(t) = cos t`, `x = 0` is crossed upwards at `t = 3π/2 + 2πj`
    /// with `v = +1`. RK4's phase error on the oscillator grows as t dt^4 / 120, which for
    /// dt = 0.02 is below 1e-7 by t = 60; the Hénon step adds O(dt^5) per crossing, so 1e-6
    /// tests accuracy far beyond a nearest-sample guess (off by up to dt/2 = 0.01).
    #[test]
    fn oscillator_crossings_match_the_analytic_times() {
        let osc = HarmonicOscillator::new(1.0, 0.0, 1.0, 1.0).unwrap();
        let section = Section::new(0, 0.0, Direction::Increasing).unwrap();
        let run = SectionRun::new(0.02, 60.0, usize::MAX);
        let cut = poincare_section(&FirstOrder(&osc), 0.0, &[1.0, 0.0], &section, &run).unwrap();
        assert_eq!(cut.len(), 9);
        for (j, &t) in cut.t.iter().enumerate() {
            let exact = 1.5 * std::f64::consts::PI + 2.0 * std::f64::consts::PI * j as f64;
            assert!((t - exact).abs() < 1e-6, "crossing {j}: {t} vs {exact}");
            let s = cut.state(j).unwrap();
            assert!(s[0].abs() < 1e-14);
            assert!((s[1] - 1.0).abs() < 1e-6);
        }
    }

    /// A pendulum libration from rest at q0 crosses q = 0 upwards with
    /// p = sqrt(2 (1 - cos q0)) (energy conservation), at quarter-period times. Yoshida-4 with
    /// dt = 0.01 keeps the energy to ~1e-10, so p at the crossing matches to 1e-8.
    #[test]
    fn separable_section_lands_on_the_energy_surface() {
        let q0 = 2.0_f64;
        let pend = Pendulum::new(q0, 0.0, 1.0).unwrap();
        let section = Section::new(0, 0.0, Direction::Increasing).unwrap();
        let run = SectionRun::new(0.01, 50.0, usize::MAX);
        let cut =
            poincare_section_separable(&pend, 0.0, &[q0, 0.0], &section, &run, Method::Yoshida4)
                .unwrap();
        assert!(cut.len() >= 3);
        let expected = (2.0 * (1.0 - q0.cos())).sqrt();
        for p in cut.component(1) {
            assert!((p - expected).abs() < 1e-8, "{p} vs {expected}");
        }
        // Successive crossings are one period apart.
        let period = cut.t[1] - cut.t[0];
        assert!((cut.t[2] - cut.t[1] - period).abs() < 1e-7);
    }

    /// The Hénon step alone: from x = cos t0 (t0 just before 3π/2) to x = 0, the returned time
    /// is 3π/2 to RK4 accuracy for one 0.1-long step (~1e-8).
    #[test]
    fn henon_step_hits_the_plane() {
        let osc = HarmonicOscillator::new(0.0, 0.0, 1.0, 1.0).unwrap();
        let section = Section::new(0, 0.0, Direction::Increasing).unwrap();
        let t0 = 1.5 * std::f64::consts::PI - 0.1;
        let y = [t0.cos(), -t0.sin()];
        let mut out = [0.0; 2];
        let t = henon_step(&FirstOrder(&osc), t0, &y, &section, 2, &mut out).unwrap();
        assert!((t - 1.5 * std::f64::consts::PI).abs() < 1e-8);
        assert!(out[0].abs() < 1e-15);
    }

    #[test]
    fn bad_inputs_are_errors() {
        let osc = HarmonicOscillator::new(1.0, 0.0, 1.0, 1.0).unwrap();
        let f = FirstOrder(&osc);
        let ok = Section::new(0, 0.0, Direction::Both).unwrap();
        let run = SectionRun::new(0.1, 1.0, 10);
        assert!(Section::new(0, f64::NAN, Direction::Both).is_err());
        let far = Section::new(5, 0.0, Direction::Both).unwrap();
        assert!(matches!(
            poincare_section(&f, 0.0, &[1.0, 0.0], &far, &run),
            Err(Error::DimensionMismatch { .. })
        ));
        assert!(matches!(
            poincare_section(&f, 0.0, &[1.0], &ok, &run),
            Err(Error::DimensionMismatch { .. })
        ));
        assert!(matches!(
            poincare_section(&f, 0.0, &[1.0, 0.0], &ok, &SectionRun::new(-0.1, 1.0, 10)),
            Err(Error::InvalidTimeSpan { .. })
        ));
        assert!(matches!(
            poincare_section(&f, 0.0, &[f64::NAN, 0.0], &ok, &run),
            Err(Error::NonFinite { .. })
        ));
        assert!(matches!(
            poincare_section_separable(&osc, 0.0, &[1.0, 0.0], &ok, &run, Method::Rk4),
            Err(Error::UnsupportedMethod { .. })
        ));
    }
}
