//! What a method is, as data: [`MethodInfo`] (the facts each integrator's file declares about
//! itself) and [`Scheme`] (the kind of loop that runs it).
//!
//! The [`Method`](crate::classical::integrators::Method) enum that names them is generated
//! from the one registry list in [`integrators`](crate::classical::integrators), next to the
//! integrators' files.

/// The facts about one integrator, declared as `pub const INFO: MethodInfo` in the
/// integrator's own file and listed by [`methods`](crate::classical::integrators::methods) (what `physicskit list` and Python's
/// `physicskit.classical.methods()` show).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct MethodInfo {
    /// The spec's name (`"yoshida4"`), which [`Method`](crate::classical::integrators::Method)'s `FromStr` parses.
    pub name: &'static str,
    /// The method's name in words, for titles and legends (`"implicit midpoint"`,
    /// `"Gauss–Legendre 4"`).
    pub label: &'static str,
    /// One line for listings.
    pub summary: &'static str,
    /// Order of accuracy of the global error.
    pub order: u32,
    /// Symplectic on the systems the method accepts.
    pub symplectic: bool,
    /// Needs a separable Hamiltonian `H = T(p) + V(q)` with conservative forces (the splitting
    /// methods); such a method refuses every other system with
    /// [`Error::UnsupportedMethod`](super::error::Error::UnsupportedMethod).
    pub separable_only: bool,
    /// Evaluations of the force (splitting methods) or of the right-hand side `f(t, y)` (the
    /// others) per step. For explicit methods the exact count; for implicit methods, whose
    /// count depends on how fast the solve converges, the typical count at the small steps
    /// these methods are used with, as [`evaluations`](Self::evaluations) explains. What a run
    /// actually spent is in its `result.extra`.
    pub evaluations_per_step: u32,
    /// What [`evaluations_per_step`](Self::evaluations_per_step) counts, and whether it is
    /// exact or typical.
    pub evaluations: &'static str,
    /// Where the method comes from (author, year, journal).
    pub reference: &'static str,
    /// The kind of loop that runs the method; the drivers dispatch on it.
    pub scheme: Scheme,
}

impl MethodInfo {
    /// True for the kinds that adapt their step to tolerances, [`Scheme::Adaptive`] and
    /// [`Scheme::Taylor`] (see [`Method::is_adaptive`](crate::classical::integrators::Method::is_adaptive)).
    pub fn is_adaptive(&self) -> bool {
        matches!(self.scheme, Scheme::Adaptive | Scheme::Taylor)
    }

    /// True for the [`Scheme::Taylor`] kind, which runs only on systems that have a Taylor
    /// form (their field as expressions, from which the Taylor recurrences are generated).
    pub fn needs_taylor_form(&self) -> bool {
        matches!(self.scheme, Scheme::Taylor)
    }
}

/// The kind of a method, which decides the loop that runs it and the systems it accepts.
///
/// Adding a kind (an adaptive method with dense output, say) means adding a variant here and a
/// method to [`Dispatch`](crate::classical::integrators::Dispatch): every match on a kind is
/// exhaustive, so the compiler lists each place that must decide what the new kind does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scheme {
    /// A splitting method, `kick k_0, drift d_0, kick k_1, ..., drift d_{s-1}, kick k_s`, run
    /// by the one kick–drift–kick loop of
    /// [`splitting`](crate::classical::integrators::splitting) on separable Hamiltonians. A
    /// symmetric composition of Störmer–Verlet has the kicks
    /// [`composition_kicks`](crate::classical::integrators::splitting::composition_kicks) of
    /// its drifts.
    Splitting {
        /// The `s + 1` kick weights, as fractions of the step (summing to one).
        kicks: &'static [f64],
        /// The `s` drift weights, as fractions of the step (summing to one).
        drifts: &'static [f64],
    },
    /// An explicit one-step method on a vector field `dy/dt = f(t, y)`.
    ExplicitRk,
    /// An implicit Runge–Kutta method on a vector field, solved each step by the shared
    /// implicit solve ([`implicit_solve`](crate::classical::integrators::implicit_solve)).
    /// Lagrangian systems run it on their canonical form `[q, p]`, where it is symplectic.
    ImplicitRk,
    /// An adaptive explicit method with error control and dense output on a vector field
    /// ([`AdaptiveStepper`](crate::classical::integrators::AdaptiveStepper)): on the
    /// fixed-step API `dt` is the spacing of the output samples, which are interpolated from
    /// the adaptive steps; tolerances from
    /// [`IntegrateOptions::tolerances`](crate::classical::IntegrateOptions::tolerances).
    Adaptive,
    /// An adaptive Taylor method: as [`Scheme::Adaptive`] on the fixed-step API (tolerances,
    /// `dt` the output spacing), but stepping the system's *Taylor form*, its field compiled
    /// into Taylor-coefficient recurrences, instead of evaluating its vector field. Only
    /// systems defined by expressions have one (the symbolic engines); every other system
    /// refuses the method with [`Error::UnsupportedMethod`](super::error::Error::UnsupportedMethod).
    Taylor,
}
