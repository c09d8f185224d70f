//! The stand-in for `jit.rs` where no JIT is built (feature `jit` off, or WebAssembly):
//! every tape is interpreted.

use super::Tape;

/// No native code, ever.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct Jit(());

/// Native code, which this build cannot have.
pub(super) enum Native {}

impl Jit {
    #[inline(always)]
    pub(super) fn code(&self, _: &Tape) -> Option<&Native> {
        None
    }

    pub(super) fn compile(&self, _: &Tape) -> Option<&Native> {
        None
    }

    pub(super) fn compile_for_foreign_target(&self, _: &Tape) -> Option<&Native> {
        None
    }

    pub(super) fn is_native(&self) -> bool {
        false
    }
}

impl Native {
    pub(super) fn call(&self, _: &[f64], _: &[f64], _: f64, _: &mut [f64]) -> f64 {
        match *self {}
    }
}
