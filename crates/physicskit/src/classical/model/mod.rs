//! A system as front ends see it, whatever its concrete type: [`DynSystem`] (one object-safe
//! system per family wrapper, with optional [`Capabilities`]), the [`Session`] that steps one
//! frame by frame, and the catalogue's vocabulary ([`SystemEntry`], [`ParamSpec`],
//! [`Value`]): how a front end names, builds, checks and runs any system.
//!
//! It sits on the integrators (a `DynSystem` runs them; a `Session` holds their steppers) and
//! under every system, which describes itself with a [`SystemEntry`].

pub mod entry;
pub mod erased;
pub mod session;

pub use entry::{
    Attribute, Drawing, Ends, Family, Pace, ParamSpec, Presentation, Shape, SystemEntry, Value,
    Values, PACE_CHECK_FRAMES,
};
pub use erased::{Capabilities, DynSystem};
pub use session::{Refused, Session};
