//! `physicskit._core`: the native half of the Python package `physicskit`.
//!
//! The pure-Python package (`python/physicskit/`) holds the spec's class hierarchy, names,
//! signatures and docstrings; every numeric operation lands here:
//!
//! * [`native`]: `NativeSystem`, the wrapper of every built-in Rust system (integrates with the
//!   GIL released, stops on Ctrl-C);
//! * [`builtin`]: one constructor per built-in system;
//! * [`callback`]: Rust integrators running systems written in Python;
//! * [`errors`]: the mapping of core errors onto Python exceptions;
//! * [`convert`]: zero-copy hand-over of result arrays to numpy;
//! * [`memory`]: the allocator (mimalloc) and its hook into the core's memory check.

pub mod builtin;
pub mod callback;
pub mod convert;
pub mod errors;
pub mod interrupt;
pub mod memory;
pub mod native;

use pyo3::prelude::*;

/// The extension module `physicskit._core`.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<native::NativeSystem>()?;
    m.add(
        "ConvergenceError",
        m.py().get_type::<errors::ConvergenceError>(),
    )?;
    memory::register();
    builtin::register(m)?;
    callback::register(m)?;
    Ok(())
}
