//! The macro that turns the one list of methods in [`integrators`](super) into the [`Method`]
//! enum, [`Method::ALL`], [`Method::info`], [`Method::dispatch`] and [`methods`](super::methods).
//!
//! A line of the list is `Variant = module` for a splitting method and
//! `Variant = module(Stepper)` for a method on a vector field, `module` being the method's file
//! (its name is the method's spec name) and `Stepper` the [`FieldStepper`](super::FieldStepper)
//! it declares, or `Variant = module(adaptive: Stepper)` for an adaptive method (a [`Scheme::Adaptive`] or
//! [`Scheme::Taylor`] one) and its [`AdaptiveStepper`](super::AdaptiveStepper). Everything else comes from the file's `INFO`: the kind of the method is
//! `INFO.scheme`, read at compile time. A splitting line takes its kick and drift weights (and
//! the number of drifts, the const parameter of [`SplittingStepper`](super::SplittingStepper)) from the
//! scheme; a vector-field line is sent to [`Dispatch::explicit_rk`](super::Dispatch) or
//! [`Dispatch::implicit_rk`](super::Dispatch) by the scheme; an adaptive line to
//! [`Dispatch::adaptive`](super::Dispatch). A line that contradicts its
//! `INFO` (a splitting line whose scheme is not [`Scheme::Splitting`], or a stepper given for a
//! splitting scheme) is a compile-time error, and every match on the scheme is exhaustive.
//!
//! [`Method`]: super::Method
//! [`Method::ALL`]: super::Method::ALL
//! [`Method::info`]: super::Method::info
//! [`Method::dispatch`]: super::Method::dispatch

use super::splitting::Coefficients;
use crate::classical::core::method::{MethodInfo, Scheme};

/// Number of substeps of a splitting method. Evaluated at compile time for each splitting line
/// of the registry, where a scheme of another kind fails the build.
pub(crate) const fn splitting_len(info: &MethodInfo) -> usize {
    match info.scheme {
        Scheme::Splitting { drifts, .. } => drifts.len(),
        Scheme::ExplicitRk | Scheme::ImplicitRk | Scheme::Adaptive | Scheme::Taylor => {
            panic!("a registry line without a stepper must be a splitting method")
        }
    }
}

/// The weights of a splitting method with `N` drifts ([`splitting_len`]), evaluated at compile
/// time, where kicks of the wrong length fail the build.
pub(crate) const fn splitting_coefficients<const N: usize>(info: &MethodInfo) -> Coefficients<N> {
    match info.scheme {
        Scheme::Splitting { kicks, drifts } => Coefficients::partitioned(kicks, drifts),
        Scheme::ExplicitRk | Scheme::ImplicitRk | Scheme::Adaptive | Scheme::Taylor => {
            panic!("a registry line without a stepper must be a splitting method")
        }
    }
}

/// The kinds of method that run on a vector field.
pub(crate) enum FieldKind {
    Explicit,
    Implicit,
}

/// The vector-field kind of a method, evaluated at compile time for each registry line that
/// names a stepper, where a splitting scheme fails the build.
pub(crate) const fn field_kind(info: &MethodInfo) -> FieldKind {
    match info.scheme {
        Scheme::ExplicitRk => FieldKind::Explicit,
        Scheme::ImplicitRk => FieldKind::Implicit,
        Scheme::Splitting { .. } => {
            panic!(
                "a splitting method takes no stepper in the registry: it runs on SplittingStepper"
            )
        }
        Scheme::Adaptive | Scheme::Taylor => {
            panic!("an adaptive method's registry line is `Name = file(adaptive: Stepper)`")
        }
    }
}

/// Evaluated at compile time for each `(adaptive: Stepper)` line of the registry, where a
/// method whose scheme is not [`Scheme::Adaptive`] or [`Scheme::Taylor`] fails the build. A
/// Taylor method is an adaptive stepper whose
/// [`AdaptiveStepper::for_system`](super::AdaptiveStepper::for_system) takes the system's
/// Taylor form, so both kinds share [`Dispatch::adaptive`](super::Dispatch::adaptive).
pub(crate) const fn check_adaptive(info: &MethodInfo) {
    if !matches!(info.scheme, Scheme::Adaptive | Scheme::Taylor) {
        panic!(
            "a registry line `(adaptive: Stepper)` must declare Scheme::Adaptive or Scheme::Taylor"
        );
    }
}

/// Generates the method modules, [`Method`](super::Method) and its table from the registry
/// list (see the module docs).
macro_rules! registry {
    ($($variant:ident = $module:ident $(($($stepper:tt)+))?),+ $(,)?) => {
        $(pub mod $module;)+

        /// A fixed-step integrator, named as in the spec. Generated from the registry list in
        /// [`integrators`](crate::classical::integrators); each variant's facts are the
        /// `INFO` of its file ([`Method::info`]).
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum Method {
            $(
                #[doc = concat!("`\"", stringify!($module), "\"`: see [`", stringify!($module),
                    "`](crate::classical::integrators::", stringify!($module), ").")]
                $variant,
            )+
        }

        impl Method {
            /// Every method, in the order they are listed to users (the registry's).
            pub const ALL: [Method; [$(stringify!($variant)),+].len()] = [$(Method::$variant),+];

            /// The facts the method's file declares.
            pub const fn info(self) -> &'static $crate::classical::core::method::MethodInfo {
                match self {
                    $(Method::$variant => &$module::INFO,)+
                }
            }

            /// Calls the one method of `dispatch` that handles this method's kind, with its
            /// drift weights or its stepper type.
            #[inline]
            pub fn dispatch<D: Dispatch>(self, dispatch: D) -> D::Output {
                match self {
                    $(Method::$variant => registry::registry!(@arm dispatch, $variant, $module $(, $($stepper)+)?),)+
                }
            }
        }

        /// The facts about every method, in [`Method::ALL`]'s order: the table that
        /// `physicskit list` and Python's `physicskit.classical.methods()` show.
        pub fn methods() -> &'static [$crate::classical::core::method::MethodInfo] {
            const TABLE: &[$crate::classical::core::method::MethodInfo] = &[$($module::INFO),+];
            TABLE
        }
    };
    (@arm $dispatch:ident, $variant:ident, $module:ident) => {{
        const N: usize = registry::splitting_len(&$module::INFO);
        const COEFFICIENTS: splitting::Coefficients<N> =
            registry::splitting_coefficients(&$module::INFO);
        $dispatch.splitting(Method::$variant, COEFFICIENTS)
    }};
    (@arm $dispatch:ident, $variant:ident, $module:ident, adaptive: $stepper:ident) => {{
        const _: () = registry::check_adaptive(&$module::INFO);
        $dispatch.adaptive::<$module::$stepper>(Method::$variant)
    }};
    (@arm $dispatch:ident, $variant:ident, $module:ident, $stepper:ident) => {{
        const KIND: registry::FieldKind = registry::field_kind(&$module::INFO);
        match KIND {
            registry::FieldKind::Explicit => {
                $dispatch.explicit_rk::<$module::$stepper>(Method::$variant)
            }
            registry::FieldKind::Implicit => {
                $dispatch.implicit_rk::<$module::$stepper>(Method::$variant)
            }
        }
    }};
}

pub(crate) use registry;
