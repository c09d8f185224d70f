//! The extension's allocator: mimalloc, for everything Rust allocates here, above all the
//! trajectories handed to numpy (pydantic-core does the same).
//!
//! mimalloc keeps freed memory for reuse and returns it to the OS only at its first call
//! after a delay (`purge_delay`, 1 s in mimalloc 3). A result's storage, freed when Python drops
//! the arrays, is therefore still faulted in when the next run within that second allocates
//! its storage; with the system allocator every large trajectory came from a fresh `mmap` and
//! the kernel zeroed each of its pages again: a third to a half of the time per step of the
//! swarm (320 MB per run) and the sine-Gordon chain (measurements: `benchmarks/README.md`).
//!
//! Memory so held counts as used for the OS, whose available-memory figure decides whether a
//! run fits; [`release_retained`] is registered with the core to hand it back before a run
//! would be refused.

/// The allocator of the extension module.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// Returns memory mimalloc holds for reuse to the OS (`mi_collect(true)`): the calling
/// thread's free pages and the freed blocks waiting in mimalloc's shared arenas, which is
/// where a dropped trajectory's storage goes (tested from Python: a refused run hands a
/// dropped 64 MB result back).
#[allow(unsafe_code)]
pub fn release_retained() {
    // SAFETY: `mi_collect` takes no pointers and may be called from any thread at any time;
    // it only frees memory no live allocation uses.
    unsafe { libmimalloc_sys::mi_collect(true) }
}

/// Registers [`release_retained`] with the core's memory check (once per process).
pub fn register() {
    physicskit::classical::core::set_memory_release_hook(release_retained);
}
