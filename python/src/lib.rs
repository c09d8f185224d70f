//! `physicskit._core`: the native half of the Python package `physicskit`.
//!
//! The pure-Python package (`python/physicskit/`) holds the spec's class hierarchy, names,
//! signatures and docstrings; every numeric operation lands here:
//!
//! * [`catalog`]: `build(name, params)`, the one constructor of every built-in system, and the
//!   `catalog()` / `methods()` listings, all read from the core's catalogue;
//! * [`params`]: the conversion of Python arguments into the catalogue's typed values;
//! * [`native`]: `NativeSystem`, the wrapper of the core's type-erased system (integrates with
//!   the GIL released, stops on Ctrl-C; capabilities such as `positions` as methods);
//! * [`functions`]: closed forms and analyses that take no system;
//! * [`expr`]: Lagrangians from the SymPy engine's expressions;
//! * [`callback`]: Rust integrators running systems written in Python;
//! * [`chaos`]: Poincaré sections, Lyapunov spectra, SALI/GALI and chaos maps;
//! * [`errors`]: the mapping of core errors onto Python exceptions;
//! * [`convert`]: zero-copy hand-over of result arrays to numpy;
//! * [`memory`]: the allocator (mimalloc) and its hook into the core's memory check.

pub mod callback;
pub mod catalog;
pub mod chaos;
pub mod convert;
pub mod ensemble;
pub mod errors;
pub mod expr;
pub mod functions;
pub mod interrupt;
pub mod memory;
pub mod native;
pub mod params;

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
    catalog::register(m)?;
    functions::register(m)?;
    expr::register(m)?;
    callback::register(m)?;
    chaos::register(m)?;
    ensemble::register(m)?;
    Ok(())
}
