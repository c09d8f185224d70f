//! The `extern "C"` surface the page calls (`web/lab.js` wraps it).
//!
//! Conventions:
//! - A lab is a handle (`>= 1`; `0` means the call failed) into a slab of [`Lab`]s.
//! - Text and arrays go in through buffers this module owns: the page asks for
//!   [`pk_input_bytes`] / [`pk_input_f64`] of a length, writes into the returned address of
//!   the linear memory, then calls the function that reads them.
//! - Results come out as addresses and lengths of buffers the lab owns (read as typed-array
//!   views, valid until the next call into the module) or as numbers.
//! - Status: `0` success, `-1` failure, with the message at [`pk_error_ptr`] /
//!   [`pk_error_len`] (UTF-8). No path panics: `panic = abort` in wasm would kill the page's
//!   module.
//!
//! `#[no_mangle]` is the one reason this module allows `unsafe_code` (the lint flags the
//! attribute, since two exports of one name would clash at link time); it has no `unsafe`
//! block.
#![allow(unsafe_code)]

use std::cell::RefCell;

use crate::{method_order, Lab};

#[derive(Default)]
struct Registry {
    labs: Vec<Option<Lab>>,
    input: Vec<u8>,
    input_f64: Vec<f64>,
    text: String,
    error: String,
}

thread_local! {
    static REGISTRY: RefCell<Registry> = RefCell::new(Registry::default());
}

fn with<T>(f: impl FnOnce(&mut Registry) -> T) -> T {
    REGISTRY.with(|r| f(&mut r.borrow_mut()))
}

/// Runs `f` on lab `h`, turning a missing handle or an error into status `-1`.
fn on_lab(h: u32, f: impl FnOnce(&mut Lab, &Registry) -> Result<(), String>) -> i32 {
    with(|r| {
        let mut registry = std::mem::take(&mut r.labs);
        let outcome = match slot(&mut registry, h) {
            Some(lab) => f(lab, r),
            None => Err(format!("no lab with handle {h}")),
        };
        r.labs = registry;
        match outcome {
            Ok(()) => 0,
            Err(message) => {
                r.error = message;
                -1
            }
        }
    })
}

fn slot(labs: &mut [Option<Lab>], h: u32) -> Option<&mut Lab> {
    let i = usize::try_from(h).ok()?.checked_sub(1)?;
    labs.get_mut(i)?.as_mut()
}

/// Reads lab `h` with `f`, or `default` if there is none.
fn read<T>(h: u32, default: T, f: impl FnOnce(&Lab) -> T) -> T {
    with(|r| slot(&mut r.labs, h).map_or(default, |lab| f(lab)))
}

fn address(values: &[f64]) -> usize {
    values.as_ptr() as usize
}

fn input_text(r: &Registry, start: usize, len: usize) -> Result<String, String> {
    let bytes = r
        .input
        .get(start..start.saturating_add(len))
        .ok_or("text past the input buffer")?;
    String::from_utf8(bytes.to_vec()).map_err(|_| "text is not UTF-8".into())
}

/// A setup from the input bytes: the system's name (`name_len` bytes), its parameters as a
/// JSON object (`params_len` bytes; none: `{}`) and a method's name (`method_len` bytes),
/// one after another.
fn setup(
    r: &Registry,
    name_len: usize,
    params_len: usize,
    method_len: usize,
) -> Result<(String, String, String), String> {
    let name = input_text(r, 0, name_len)?;
    let params = input_text(r, name_len, params_len)?;
    let method = input_text(r, name_len.saturating_add(params_len), method_len)?;
    let params = if params.is_empty() {
        "{}".into()
    } else {
        params
    };
    Ok((name, params, method))
}

/// Makes the byte input buffer `len` long; returns its address.
#[no_mangle]
pub extern "C" fn pk_input_bytes(len: usize) -> usize {
    with(|r| {
        r.input.clear();
        r.input.resize(len, 0);
        r.input.as_ptr() as usize
    })
}

/// Makes the number input buffer `len` long; returns its address.
#[no_mangle]
pub extern "C" fn pk_input_f64(len: usize) -> usize {
    with(|r| {
        r.input_f64.clear();
        r.input_f64.resize(len, 0.0);
        address(&r.input_f64)
    })
}

/// Writes the catalogue JSON (as `physicskit list --json`) into the text buffer; returns
/// its length ([`pk_text_ptr`] is its address).
#[no_mangle]
pub extern "C" fn pk_catalogue() -> usize {
    with(|r| {
        r.text = physicskit_listing::catalogue_json();
        r.text.len()
    })
}

/// The order the method steps at on a system with the tolerance `tol` (`rtol = atol`; see
/// [`method_order`]): the input bytes hold the system's name (`name_len` bytes), its
/// parameters as a JSON object (`params_len` bytes) and the method's name (`method_len`
/// bytes), one after another, as for [`pk_build`]. Returns 0 on failure (the error says why).
#[no_mangle]
pub extern "C" fn pk_method_order(
    name_len: usize,
    params_len: usize,
    method_len: usize,
    tol: f64,
) -> u32 {
    with(|r| {
        let order = setup(r, name_len, params_len, method_len)
            .and_then(|(system, params, method)| method_order(&system, &params, &method, tol));
        match order {
            Ok(order) => order,
            Err(message) => {
                r.error = message;
                0
            }
        }
    })
}

/// Address of the text buffer.
#[no_mangle]
pub extern "C" fn pk_text_ptr() -> usize {
    with(|r| r.text.as_ptr() as usize)
}

/// Address of the last error message.
#[no_mangle]
pub extern "C" fn pk_error_ptr() -> usize {
    with(|r| r.error.as_ptr() as usize)
}

/// Length in bytes of the last error message.
#[no_mangle]
pub extern "C" fn pk_error_len() -> usize {
    with(|r| r.error.len())
}

/// Builds a lab: the input bytes hold the system's name (`name_len` bytes), its parameters as
/// a JSON object (`params_len` bytes) and the method's name (`method_len` bytes; none: the
/// default), one after another. Returns the handle, or 0 on failure.
#[no_mangle]
pub extern "C" fn pk_build(name_len: usize, params_len: usize, method_len: usize) -> u32 {
    build(
        name_len,
        params_len,
        method_len,
        crate::lab::DEFAULT_TOLERANCE,
    )
}

/// [`pk_build`] at the tolerance `tol`.
fn build(name_len: usize, params_len: usize, method_len: usize, tol: f64) -> u32 {
    with(|r| {
        let built =
            setup(r, name_len, params_len, method_len).and_then(|(name, params, method)| {
                Lab::with_tolerance(
                    &name,
                    &params,
                    (!method.is_empty()).then_some(method.as_str()),
                    tol,
                )
            });
        match built {
            Ok(lab) => {
                let free = r.labs.iter().position(Option::is_none);
                let i = free.unwrap_or(r.labs.len());
                if i == r.labs.len() {
                    r.labs.push(None);
                }
                r.labs[i] = Some(lab);
                u32::try_from(i + 1).unwrap_or(0)
            }
            Err(message) => {
                r.error = message;
                0
            }
        }
    })
}

/// [`pk_build`] with the tolerance `tol` (`rtol = atol`) of an adaptive method (kept, and
/// unused, by a fixed-step one). Returns the handle, or 0 on failure (a `tol` that is not
/// finite and positive, or one the method refuses, among the reasons).
#[no_mangle]
pub extern "C" fn pk_build_tol(
    name_len: usize,
    params_len: usize,
    method_len: usize,
    tol: f64,
) -> u32 {
    build(name_len, params_len, method_len, tol)
}

/// Frees lab `h` (nothing if there is none).
#[no_mangle]
pub extern "C" fn pk_free(h: u32) {
    with(|r| {
        if let Some(i) = usize::try_from(h).ok().and_then(|h| h.checked_sub(1)) {
            if let Some(s) = r.labs.get_mut(i) {
                *s = None;
            }
        }
    });
}

/// Sets the method of lab `h` to the name in the first `len` input bytes.
#[no_mangle]
pub extern "C" fn pk_set_method(h: u32, len: usize) -> i32 {
    on_lab(h, |lab, r| lab.set_method(&input_text(r, 0, len)?))
}

/// Sets the tolerance (`rtol = atol`) of lab `h`'s adaptive method to `tol` (see
/// [`Lab::set_tolerance`]).
#[no_mangle]
pub extern "C" fn pk_set_tolerance(h: u32, tol: f64) -> i32 {
    on_lab(h, |lab, _| lab.set_tolerance(tol))
}

/// Lab `h`'s tolerance (NaN if there is no such lab).
#[no_mangle]
pub extern "C" fn pk_tolerance(h: u32) -> f64 {
    read(h, f64::NAN, Lab::tolerance)
}

/// Advances lab `h` by `n` steps of `dt`.
#[no_mangle]
pub extern "C" fn pk_step(h: u32, n: u32, dt: f64) -> i32 {
    on_lab(h, |lab, _| lab.step(n, dt))
}

/// Starts a new run of lab `h` from the first `len` numbers of the input buffer.
#[no_mangle]
pub extern "C" fn pk_set_state(h: u32, len: usize) -> i32 {
    on_lab(h, |lab, r| {
        let state = r
            .input_f64
            .get(..len)
            .ok_or("state past the input buffer")?;
        lab.set_state(state)
    })
}

/// Returns lab `h` to its run's initial state at `t = 0`.
#[no_mangle]
pub extern "C" fn pk_reset(h: u32) -> i32 {
    on_lab(h, |lab, _| lab.reset())
}

/// Sets lab `h`'s Poincaré section `state[k] = value`, crossed in `direction` (+1, -1, 0).
#[no_mangle]
pub extern "C" fn pk_set_section(h: u32, k: usize, value: f64, direction: i32) -> i32 {
    on_lab(h, |lab, _| lab.set_section(k, value, direction))
}

/// Forgets lab `h`'s crossings.
#[no_mangle]
pub extern "C" fn pk_clear_crossings(h: u32) -> i32 {
    on_lab(h, |lab, _| {
        lab.clear_crossings();
        Ok(())
    })
}

/// Launches a run of lab `h` at its energy: the input buffer holds `pairs` pairs `(index,
/// value)` to assign; entry `solve` is the momentum solved for (see
/// [`Lab::launch_at_energy`]).
#[no_mangle]
pub extern "C" fn pk_launch(h: u32, pairs: usize, solve: usize) -> i32 {
    on_lab(h, |lab, r| {
        let flat = r
            .input_f64
            .get(..pairs.saturating_mul(2))
            .ok_or("pairs past the input buffer")?;
        let mut assign = Vec::with_capacity(pairs);
        for pair in flat.chunks_exact(2) {
            if !(pair[0] >= 0.0 && pair[0].fract() == 0.0 && pair[0] < 1e9) {
                return Err(format!("{} is not an index", pair[0]));
            }
            assign.push((pair[0] as usize, pair[1]));
        }
        lab.launch_at_energy(&assign, solve)
    })
}

/// Address of lab `h`'s state.
#[no_mangle]
pub extern "C" fn pk_state_ptr(h: u32) -> usize {
    read(h, 0, |lab| address(lab.state()))
}

/// Length of lab `h`'s state.
#[no_mangle]
pub extern "C" fn pk_state_len(h: u32) -> usize {
    read(h, 0, |lab| lab.state().len())
}

/// Address of lab `h`'s initial state.
#[no_mangle]
pub extern "C" fn pk_initial_ptr(h: u32) -> usize {
    read(h, 0, |lab| address(lab.initial_state()))
}

/// Address of lab `h`'s drawing positions.
#[no_mangle]
pub extern "C" fn pk_positions_ptr(h: u32) -> usize {
    read(h, 0, |lab| address(lab.positions()))
}

/// Number of lab `h`'s drawing coordinates.
#[no_mangle]
pub extern "C" fn pk_positions_len(h: u32) -> usize {
    read(h, 0, |lab| lab.positions().len())
}

/// Address of lab `h`'s crossings.
#[no_mangle]
pub extern "C" fn pk_crossings_ptr(h: u32) -> usize {
    read(h, 0, |lab| address(lab.crossings()))
}

/// Number of values in lab `h`'s crossings (states one after another).
#[no_mangle]
pub extern "C" fn pk_crossings_len(h: u32) -> usize {
    read(h, 0, |lab| lab.crossings().len())
}

/// Address of the orbit numbers of lab `h`'s crossings (`u32`, one per crossing).
#[no_mangle]
pub extern "C" fn pk_crossing_orbits_ptr(h: u32) -> usize {
    read(h, 0, |lab| lab.crossing_orbits().as_ptr() as usize)
}

/// Number of lab `h`'s crossings.
#[no_mangle]
pub extern "C" fn pk_crossing_orbits_len(h: u32) -> usize {
    read(h, 0, |lab| lab.crossing_orbits().len())
}

/// The energy of the state in the first `len` numbers of the input buffer, for lab `h`'s
/// system (NaN on failure, with the message at [`pk_error_ptr`]).
#[no_mangle]
pub extern "C" fn pk_energy_of(h: u32, len: usize) -> f64 {
    let mut energy = f64::NAN;
    on_lab(h, |lab, r| {
        let state = r
            .input_f64
            .get(..len)
            .ok_or("state past the input buffer")?;
        energy = lab.energy_of(state)?;
        Ok(())
    });
    energy
}

/// Lab `h`'s clock (NaN if there is no such lab).
#[no_mangle]
pub extern "C" fn pk_time(h: u32) -> f64 {
    read(h, f64::NAN, Lab::time)
}

/// Lab `h`'s energy.
#[no_mangle]
pub extern "C" fn pk_energy(h: u32) -> f64 {
    read(h, f64::NAN, Lab::energy)
}

/// Lab `h`'s initial energy.
#[no_mangle]
pub extern "C" fn pk_energy0(h: u32) -> f64 {
    read(h, f64::NAN, Lab::energy0)
}

/// Lab `h`'s relative energy error.
#[no_mangle]
pub extern "C" fn pk_energy_error(h: u32) -> f64 {
    read(h, f64::NAN, Lab::energy_error)
}

/// Computes lab `h`'s drawing positions of the configuration in the first `len` input
/// numbers; returns their count (read them at [`pk_probe_ptr`]), or -1 on failure.
#[no_mangle]
pub extern "C" fn pk_positions_of(h: u32, len: usize) -> i32 {
    let mut count = 0;
    let status = on_lab(h, |lab, r| {
        let q = r
            .input_f64
            .get(..len)
            .ok_or("configuration past the input buffer")?;
        count = lab.positions_of(q)?.len();
        Ok(())
    });
    if status == 0 {
        i32::try_from(count).unwrap_or(-1)
    } else {
        -1
    }
}

/// Address of the positions [`pk_positions_of`] computed last.
#[no_mangle]
pub extern "C" fn pk_probe_ptr(h: u32) -> usize {
    read(h, 0, |lab| address(lab.probe()))
}
