//! [`FromParameters`]: members of any system that a closure builds from a vector of named real
//! parameters and an initial state, such as the SymPy engines' expression systems
//! (`ExprHamiltonian`, `ExprOde`, `LagrangianModel<ExprLagrangian>`), which are not catalogue
//! entries.
//!
//! Member `i` has the given parameter values, with [`Members::common`] values and its swept
//! values ([`Sweep`](super::Sweep), targets named as the parameters are) in place, and the
//! given initial state unless [`Members::states`] has a row for it. The closure builds it from
//! those numbers (so it checks them as its constructor does) and the member's clock is reset
//! to `t0`, as a single run does before integrating: a member is the system a caller builds
//! alone from the same numbers, bit for bit.

use super::members::{check_counts, same_sweeps, state_row, MemberSource, Members};
use crate::classical::core::{Error, Result};
use crate::classical::model::{DynSystem, Value};

/// Members built by `build(params, state)` from named real parameters (see the module
/// documentation).
pub struct FromParameters<'a, F> {
    names: Vec<String>,
    /// The parameter values of a member before its sweeps: the given ones, with the common
    /// values in place.
    base: Vec<f64>,
    state0: Vec<f64>,
    members: &'a Members,
    /// For each sweep, the index of its parameter.
    slots: Vec<usize>,
    build: F,
}

impl<'a, F> FromParameters<'a, F>
where
    F: Fn(&[f64], &[f64]) -> Result<Box<dyn DynSystem>> + Sync,
{
    /// The members of the system `build(params, state)` makes, from the parameters `params`
    /// (`name -> value`, in the order `build` takes them) and the initial state `state0`, as
    /// `members` varies them.
    ///
    /// # Errors
    /// No members; a sweep of the wrong length; a common value or sweep naming no parameter
    /// (the message lists the parameters), one named twice in `params`, or a common value
    /// that is not a real number; per-member `states` not of `n x state0.len()` values.
    /// Members themselves are checked when built.
    ///
    /// # Example
    /// ```
    /// use physicskit::classical::catalog;
    /// use physicskit::classical::model::Value;
    /// use physicskit::classical::ensemble::{self, FromParameters, Members, Plan, Sweep};
    ///
    /// // Harmonic oscillators of three stiffnesses, built from the catalogue by a closure.
    /// let members = Members {
    ///     sweeps: vec![Sweep::new("k", vec![1.0, 4.0, 9.0])],
    ///     n: 3,
    ///     ..Members::default()
    /// };
    /// let source = FromParameters::new(
    ///     vec![("k".into(), 1.0)],
    ///     vec![1.0, 0.0],
    ///     &members,
    ///     |params: &[f64], state: &[f64]| {
    ///         catalog::build(
    ///             "harmonic-oscillator",
    ///             [
    ///                 ("k".to_string(), Value::Scalar(params[0])),
    ///                 ("q0".to_string(), Value::Scalar(state[0])),
    ///                 ("p0".to_string(), Value::Scalar(state[1])),
    ///             ],
    ///         )
    ///     },
    /// )?;
    /// let plan = Plan {
    ///     t_span: (0.0, 1.0),
    ///     dt: 0.01,
    ///     method: None,
    ///     stride: None,
    ///     reductions: vec![],
    ///     final_state: true,
    ///     threads: None,
    ///     tolerances: None,
    /// };
    /// let out = ensemble::run_source(&source, &plan, None)?;
    /// assert_eq!(out.final_state.dim(), (3, 2));
    /// # Ok::<(), physicskit::classical::Error>(())
    /// ```
    pub fn new(
        params: Vec<(String, f64)>,
        state0: Vec<f64>,
        members: &'a Members,
        build: F,
    ) -> Result<Self> {
        check_counts(members)?;
        let (names, mut base): (Vec<String>, Vec<f64>) = params.into_iter().unzip();
        let index_of = |target: &str| -> Result<usize> {
            let mut found = names.iter().enumerate().filter(|(_, n)| *n == target);
            match (found.next(), found.next()) {
                (Some((i, _)), None) => Ok(i),
                (Some(_), Some(_)) => Err(Error::InvalidArgument {
                    name: target.into(),
                    reason: "two parameters have this name: give them distinct names".into(),
                }),
                (None, _) => Err(Error::InvalidArgument {
                    name: target.into(),
                    reason: if names.is_empty() {
                        "the system has no parameters; vary the initial states instead".into()
                    } else {
                        format!(
                            "no such parameter; the system's parameters are: {}",
                            names.join(", ")
                        )
                    },
                }),
            }
        };
        for (name, value) in &members.common {
            let i = index_of(name)?;
            base[i] = match value {
                Value::Scalar(x) => *x,
                other => {
                    return Err(Error::InvalidArgument {
                        name: name.clone(),
                        reason: format!("expected a real number, got {}", other.kind_name()),
                    })
                }
            };
        }
        let slots = members
            .sweeps
            .iter()
            .map(|s| index_of(&s.target))
            .collect::<Result<Vec<_>>>()?;
        // The shape of the states, checked once here rather than per member.
        state_row(members, 0, state0.len())?;
        Ok(Self {
            names,
            base,
            state0,
            members,
            slots,
            build,
        })
    }
}

impl<F> MemberSource for FromParameters<'_, F>
where
    F: Fn(&[f64], &[f64]) -> Result<Box<dyn DynSystem>> + Sync,
{
    fn count(&self) -> usize {
        self.members.n
    }

    /// Builds member `index` with its parameters and initial state, clock at `t0`.
    ///
    /// # Errors
    /// A swept value that is not finite (named by its parameter), and whatever `build` or the
    /// system's `reset` refuses.
    fn build(&self, index: usize, t0: f64) -> Result<Box<dyn DynSystem>> {
        let mut params = self.base.clone();
        for (sweep, &slot) in self.members.sweeps.iter().zip(&self.slots) {
            let x = sweep.values[index];
            if !x.is_finite() {
                return Err(Error::invalid(
                    self.names[slot].clone(),
                    x,
                    "must be finite",
                ));
            }
            params[slot] = x;
        }
        let state = state_row(self.members, index, self.state0.len())?.unwrap_or(&self.state0);
        let mut system = (self.build)(&params, state)?;
        system.reset(Some(state), t0)?;
        Ok(system)
    }

    /// Equal swept values: equal parameters, with which `build` makes the same system.
    fn same_system(&self, a: usize, b: usize) -> bool {
        same_sweeps(self.members, a, b)
    }
}
