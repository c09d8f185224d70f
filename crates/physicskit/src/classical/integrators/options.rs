//! [`IntegrateOptions`]: what to store and whom to tell while integrating, and the
//! [`Tolerances`] of the adaptive methods.

use std::ops::ControlFlow;

use super::Method;
use crate::classical::core::error::{Error, Result};

/// Which steps of the grid are stored in the [`SimulationResult`](crate::classical::core::SimulationResult).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Sampling {
    /// Every step: `n_steps + 1` samples, as the spec documents.
    #[default]
    All,
    /// Every `k`-th step, plus the final step when `n_steps` is not a multiple of `k`.
    Stride(usize),
    /// Only the initial and the final state (two samples; one if `n_steps = 0`). For large
    /// ensembles whose full trajectory would not fit in memory.
    FinalOnly,
}

impl Sampling {
    /// The first stored step after step `step`, for a grid of `n_steps` steps (the final step
    /// is always stored). Step 0 is always stored too.
    #[inline]
    pub(crate) fn next_stored(self, step: usize, n_steps: usize) -> usize {
        match self {
            Sampling::All => step + 1,
            Sampling::Stride(k) => ((step / k + 1) * k).min(n_steps),
            Sampling::FinalOnly => n_steps,
        }
    }

    /// Number of stored samples for a grid of `n_steps` steps.
    pub(crate) fn count(self, n_steps: usize) -> usize {
        match self {
            Sampling::All => n_steps + 1,
            Sampling::Stride(k) => n_steps / k + 1 + usize::from(!n_steps.is_multiple_of(k)),
            Sampling::FinalOnly => 1 + usize::from(n_steps > 0),
        }
    }

    pub(crate) fn validate(self) -> Result<()> {
        match self {
            Sampling::Stride(0) => Err(Error::invalid("stride", 0.0, "must be >= 1")),
            _ => Ok(()),
        }
    }
}

/// Told of progress every [`IntegrateOptions::observe_every`] steps; may stop the run.
///
/// Used by the command line for its progress bar and by the Python bindings to stop on Ctrl-C.
/// It is called outside the per-step work, so a `dyn` call here costs nothing measurable.
pub trait Observer {
    /// `step` of `n_steps` is done and the clock reads `t`. Return `Break` to stop; the
    /// integration then returns [`Error::Interrupted`].
    fn observe(&mut self, step: usize, n_steps: usize, t: f64) -> ControlFlow<()>;
}

/// Error tolerances of an adaptive method (`dop853`), and its guard against runs that would not
/// end.
///
/// A step is accepted when its weighted error estimate `err` satisfies
/// `sqrt(mean_i (e_i / (atol + rtol max(|y_i|, |y_new,i|)))^2) <= 1` (Hairer, Nørsett & Wanner,
/// *Solving ODEs I*, 2nd ed., II.4 and II.10), so each accepted step's local error is about
/// `atol + rtol |y|` per component; the global error over a run is typically a modest
/// multiple of that, growing with the span.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerances {
    /// Relative tolerance (default `1e-10`).
    pub rtol: f64,
    /// Absolute tolerance (default `1e-12`), in the units of each state component.
    pub atol: f64,
    /// Most steps (accepted and rejected) one `integrate` call may attempt before it stops with
    /// [`Error::StepSizeTooSmall`] (default `10_000_000`): a guard against runs that would
    /// not end (tolerances far below what the problem allows, a near-singular field).
    pub max_steps: u64,
}

impl Default for Tolerances {
    fn default() -> Self {
        Self {
            rtol: 1e-10,
            atol: 1e-12,
            max_steps: 10_000_000,
        }
    }
}

impl Tolerances {
    /// Tolerances `rtol` and `atol` with the default step budget.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `rtol` or `atol` when it is not finite and `> 0`.
    ///
    /// # Example
    /// ```
    /// use physicskit::classical::Tolerances;
    /// let tol = Tolerances::new(1e-8, 1e-10).unwrap();
    /// assert_eq!(tol.rtol, 1e-8);
    /// assert!(Tolerances::new(0.0, 1e-10).is_err());
    /// ```
    pub fn new(rtol: f64, atol: f64) -> Result<Self> {
        let tol = Self {
            rtol,
            atol,
            ..Self::default()
        };
        tol.validate()?;
        Ok(tol)
    }

    /// The tolerances of a front end's optional `rtol`, `atol` and `max_steps` arguments for
    /// `method`: `None` when none is given, otherwise the given ones with the defaults for the
    /// others, validated.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the first given of `rtol`, `atol` and `max_steps` for a
    /// fixed-step method, which takes no tolerances and no step budget (its steps are set by
    /// `dt`); [`Error::InvalidParameter`] naming an invalid one.
    ///
    /// # Example
    /// ```
    /// use physicskit::classical::{Method, Tolerances};
    /// let tol = Tolerances::for_method(None, None, Some(500), Method::Dop853).unwrap().unwrap();
    /// assert_eq!((tol.rtol, tol.max_steps), (1e-10, 500));
    /// assert!(Tolerances::for_method(None, None, None, Method::Dop853).unwrap().is_none());
    /// assert!(Tolerances::for_method(None, None, Some(500), Method::Rk4).is_err());
    /// ```
    pub fn for_method(
        rtol: Option<f64>,
        atol: Option<f64>,
        max_steps: Option<u64>,
        method: Method,
    ) -> Result<Option<Self>> {
        let given = [
            ("rtol", rtol.is_some()),
            ("atol", atol.is_some()),
            ("max_steps", max_steps.is_some()),
        ];
        let Some(&(name, _)) = given.iter().find(|(_, is_given)| *is_given) else {
            return Ok(None);
        };
        check_adaptive(name, method)?;
        let default = Self::default();
        let tol = Self {
            rtol: rtol.unwrap_or(default.rtol),
            atol: atol.unwrap_or(default.atol),
            max_steps: max_steps.unwrap_or(default.max_steps),
        };
        tol.validate()?;
        Ok(Some(tol))
    }

    /// Checks both tolerances (finite, `> 0`) and the step budget (`>= 1`).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the offending field.
    pub fn validate(&self) -> Result<()> {
        crate::classical::core::error::check_positive("rtol", self.rtol)?;
        crate::classical::core::error::check_positive("atol", self.atol)?;
        if self.max_steps == 0 {
            return Err(Error::invalid("max_steps", 0.0, "must be >= 1"));
        }
        Ok(())
    }
}

/// `Ok` for an adaptive method; for a fixed-step one, [`Error::InvalidArgument`] naming `name`
/// (the argument that carried tolerances) and listing the adaptive methods.
pub(crate) fn check_adaptive(name: &str, method: Method) -> Result<()> {
    if method.is_adaptive() {
        return Ok(());
    }
    let adaptive: Vec<&str> = Method::ALL
        .into_iter()
        .filter(|m| m.is_adaptive())
        .map(Method::name)
        .collect();
    Err(Error::InvalidArgument {
        name: name.into(),
        reason: format!(
            "`{method}` is a fixed-step method (dt is its step) and takes no tolerances or step \
             budget; only the adaptive methods do: {}",
            adaptive.join(", ")
        ),
    })
}

/// Options of `integrate_with`. `IntegrateOptions::default()` is what `integrate` uses: every
/// sample and the energy stored, no observer.
#[derive(Default)]
pub struct IntegrateOptions<'a> {
    /// Which samples to keep.
    pub sampling: Sampling,
    /// Skip the energy diagnostic (saves one energy evaluation per stored sample).
    pub skip_energy: bool,
    /// Progress observer, called every `observe_every` steps.
    pub observer: Option<&'a mut dyn Observer>,
    /// Steps between observer calls; 0 means the default of 4096.
    pub observe_every: usize,
    /// Tolerances of an adaptive method; `None` means [`Tolerances::default`]. Refused with
    /// [`Error::InvalidArgument`] (naming `tolerances`) for a fixed-step method, which has
    /// none: a tolerance silently ignored would mislead.
    pub tolerances: Option<Tolerances>,
}

impl IntegrateOptions<'_> {
    /// Options storing every `k`-th sample.
    pub fn stride(k: usize) -> Self {
        Self {
            sampling: Sampling::Stride(k),
            ..Self::default()
        }
    }

    /// Options storing only the initial and final samples.
    pub fn final_only() -> Self {
        Self {
            sampling: Sampling::FinalOnly,
            ..Self::default()
        }
    }

    pub(crate) fn observe_interval(&self) -> usize {
        if self.observe_every == 0 {
            4096
        } else {
            self.observe_every
        }
    }
}
