//! The stand-in for `taylor_jit.rs` where no JIT is built (feature `jit` off, or
//! WebAssembly): every program's recurrences are interpreted.

use super::{Node, Val};

/// No native code, ever.
#[derive(Debug, Clone, Default)]
pub(super) struct Jit(());

/// Native code, which this build cannot have.
pub(super) enum Native {}

impl Jit {
    pub(super) fn never() -> Self {
        Self(())
    }

    #[inline(always)]
    pub(super) fn code(&self, _: &[Node], _: &[Val], _: usize) -> Option<&Native> {
        None
    }

    pub(super) fn compile(&self, _: &[Node], _: &[Val], _: usize) -> Option<&Native> {
        None
    }

    pub(super) fn compile_compact(&self, _: &[Node], _: &[Val], _: usize) -> Option<&Native> {
        None
    }

    pub(super) fn compile_unrolled(&self, _: &[Node], _: &[Val], _: usize) -> Option<&Native> {
        None
    }

    pub(super) fn is_avx(&self, _: usize) -> bool {
        false
    }

    pub(super) fn is_native(&self, _: usize) -> bool {
        false
    }
}

impl Native {
    pub(super) fn call(&self, _: &mut [f64]) {
        match *self {}
    }

    pub(super) fn writes_blocks(&self) -> bool {
        match *self {}
    }
}
