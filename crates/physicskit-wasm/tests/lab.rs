//! The lab natively: a frame allocates nothing (counted by a global allocator that counts the
//! allocations of the test's own thread), for every catalogue system, and with a Poincaré
//! section on Hénon–Heiles.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use physicskit::classical::catalog::SYSTEMS;
use physicskit_wasm::Lab;

/// The system allocator, counting the calls of each thread (the tests run in parallel).
struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

// SAFETY: every call is forwarded unchanged to `System`; the count is a thread-local `Cell`
// with a const initializer, which does not allocate.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        // SAFETY: the caller's contract is `System`'s.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        // SAFETY: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static COUNTING: Counting = Counting;

fn allocations() -> u64 {
    ALLOCATIONS.with(Cell::get)
}

/// A frame as the page runs it: steps, then the readouts it draws.
fn frame(lab: &mut Lab) -> f64 {
    lab.step(16, 1e-3).unwrap();
    let p = lab.positions();
    lab.energy_error() + lab.time() + lab.state()[0] + p.first().copied().unwrap_or(0.0)
}

#[test]
fn a_frame_allocates_nothing_for_any_system_or_method() {
    for entry in SYSTEMS {
        for method in entry.methods() {
            let mut lab = Lab::new(entry.name, "{}").unwrap();
            if lab.set_method(method.name()).is_err() {
                // A method the built system refuses (a projectile with drag and a splitting
                // method): nothing runs, nothing to count.
                continue;
            }
            // The first frame may size the position buffer.
            frame(&mut lab);
            let before = allocations();
            let mut sink = 0.0;
            for _ in 0..3 {
                sink += frame(&mut lab);
            }
            assert_eq!(
                allocations() - before,
                0,
                "{} {} (sink {sink})",
                entry.name,
                method.name()
            );
        }
    }
}

#[test]
fn a_frame_with_a_section_allocates_nothing() {
    let mut lab = Lab::new("henon-heiles", "{}").unwrap();
    lab.set_method("yoshida4").unwrap();
    lab.set_section(0, 0.0, 1).unwrap();
    frame(&mut lab);
    let before = allocations();
    let crossings0 = lab.crossings().len();
    // About a period at dt = 1e-3 with 1000 steps a frame: crossings are recorded.
    for _ in 0..20 {
        lab.step(1000, 1e-3).unwrap();
    }
    assert!(lab.crossings().len() > crossings0, "no crossing recorded");
    assert_eq!(allocations() - before, 0);
}
