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

/// Launches on a Hénon–Heiles section add orbits: the crossings of earlier orbits stay, each
/// crossing carries its orbit's number, every crossing lies on the section (`y = 0`, `py >
/// 0`) at the launch energy, and a new state of another energy forgets them.
#[test]
fn section_crossings_accumulate_over_launched_orbits() {
    let mut lab = Lab::new("henon-heiles", "{}").unwrap();
    lab.set_method("yoshida4").unwrap();
    lab.set_section(1, 0.0, 1).unwrap();
    let e0 = lab.energy0();
    let mut orbits = Vec::new();
    for x in [0.0, 0.1, -0.15] {
        lab.launch_at_energy(&[(0, x), (2, 0.0), (1, 0.0)], 3)
            .unwrap();
        // 40 time units: about six periods of the x oscillation (2 pi), so several upward
        // crossings of y = 0 per orbit.
        for _ in 0..40 {
            lab.step(1000, 1e-3).unwrap();
        }
        orbits.push(*lab.crossing_orbits().last().unwrap());
    }
    let numbers = lab.crossing_orbits();
    assert_eq!(numbers.len() * 4, lab.crossings().len());
    for o in &orbits {
        let count = numbers.iter().filter(|&n| n == o).count();
        assert!(count >= 3, "orbit {o}: {count} crossings");
    }
    assert!(orbits[0] != orbits[1] && orbits[1] != orbits[2]);
    for s in lab.crossings().chunks_exact(4) {
        // Hénon's step lands on y = 0 to rounding. The energy: yoshida4 at dt = 1e-3 errs by
        // O(dt^4) ~ 1e-12 relative at these amplitudes (E0 = 0.081, the default start), and
        // the crossing's two RK4 substeps by less; 1e-9 leaves three decades of margin.
        assert!(s[1].abs() < 1e-12, "crossing off the section: {s:?}");
        assert!(s[3] > 0.0);
        let e = lab.energy_of(s).unwrap();
        assert!(
            (e - e0).abs() < 1e-9 * e0.abs(),
            "crossing at energy {e}, E0 {e0}"
        );
    }
    // A reset forgets only the current orbit's crossings.
    let before = numbers.len();
    lab.reset().unwrap();
    let kept = lab.crossing_orbits().len();
    assert!(kept < before && kept > 0);
    assert!(lab.crossing_orbits().iter().all(|&n| n != orbits[2]));
    // A state of another energy: the section starts empty.
    lab.set_state(&[0.05, 0.0, 0.0, 0.2]).unwrap();
    assert!(lab.crossings().is_empty() && lab.crossing_orbits().is_empty());
    assert!(lab.energy_of(&[0.0; 3]).is_err());
}

/// A count from a hostile link is refused before anything is allocated, with a message
/// naming it; a count the lab runs is accepted.
#[test]
fn a_huge_count_is_refused_by_name() {
    let error = Lab::new("pendulum-swarm", r#"{"n": 1e12}"#).err().unwrap();
    assert!(error.contains("`n`"), "{error}");
    let limit = physicskit_wasm::MAX_LAB_COUNT;
    assert!(Lab::new("pendulum-swarm", &format!(r#"{{"n": {}}}"#, limit + 1)).is_err());
    assert!(Lab::new("pendulum-swarm", r#"{"n": 2000}"#).is_ok());
}

/// A setup some methods refuse builds with a method that takes it: a projectile with drag is
/// not separable, so its default splitting method refuses it, and rk4 runs it (the gallery's
/// link names rk4 with drag). An unknown method is refused by name.
#[test]
fn a_setup_builds_with_its_own_method() {
    let drag = r#"{"drag_coeff": 0.02}"#;
    let error = Lab::new("projectile", drag).err().unwrap();
    let mut lab = Lab::with_method("projectile", drag, Some("rk4")).unwrap();
    assert_eq!(lab.method().name(), "rk4", "default refused with {error}");
    lab.step(10, 1e-3).unwrap();
    let error = Lab::with_method("projectile", "{}", Some("warp-drive"))
        .err()
        .unwrap();
    assert!(error.contains("warp-drive"), "{error}");
    assert!(Lab::with_method("projectile", "{}", None).is_ok());
}

/// Calls `pk_build` as the page does: the name, parameters and method's bytes written one
/// after another into the module's input buffer. Returns the handle, or the error message.
fn build_through_exports(name: &[u8], params: &[u8], method: &[u8]) -> Result<u32, String> {
    use physicskit_wasm::exports::{pk_build, pk_error_len, pk_error_ptr, pk_input_bytes};
    let bytes = [name, params, method].concat();
    let at = pk_input_bytes(bytes.len());
    // SAFETY: `pk_input_bytes` has just made its buffer `bytes.len()` long at `at`, and
    // nothing touches it until `pk_build` reads it (the page writes the same way into the
    // module's linear memory).
    #[allow(unsafe_code)]
    unsafe {
        std::ptr::copy_nonoverlapping(bytes.as_ptr(), at as *mut u8, bytes.len());
    }
    let h = pk_build(name.len(), params.len(), method.len());
    if h != 0 {
        return Ok(h);
    }
    // SAFETY: the error message is a `String` the module owns, unchanged until its next call.
    #[allow(unsafe_code)]
    let message =
        unsafe { std::slice::from_raw_parts(pk_error_ptr() as *const u8, pk_error_len()) };
    Err(String::from_utf8(message.to_vec()).expect("the module's messages are UTF-8"))
}

/// A method name from a share link or a script call is untrusted: `pk_build` given every
/// method name with every system, an unknown name, bytes that are not UTF-8 and lengths past
/// the input refuses with a message naming what it refused (a panic would abort the page's
/// module), and the module builds and runs a lab afterwards.
#[test]
fn build_refuses_a_bad_method_by_name_and_keeps_running() {
    use physicskit::classical::Method;
    use physicskit_wasm::exports::{pk_build, pk_free, pk_input_bytes, pk_step};
    for entry in SYSTEMS {
        let name = entry.name.as_bytes();
        for method in Method::ALL {
            // The lab runs the methods the entry lists, adaptive ones among them.
            let listed = entry.methods().any(|m| m == method);
            match build_through_exports(name, b"{}", method.name().as_bytes()) {
                Ok(h) => {
                    assert!(listed, "{} built with {method}", entry.name);
                    // A method it builds with, it runs with (dt of the page's default).
                    assert_eq!(pk_step(h, 2, 1e-3), 0, "{} {method}", entry.name);
                    pk_free(h);
                }
                Err(message) => {
                    // Every refusal offers only methods the entry lists.
                    let offered = message.rsplit_once(" with ").map_or("", |(_, list)| list);
                    for name in offered.split(", ") {
                        assert!(
                            entry.methods().any(|m| m.name() == name),
                            "{} with {method}: {message:?} offers {name:?}",
                            entry.name
                        );
                    }
                    assert!(
                        message.contains(method.name()) || message.contains(entry.name),
                        "{} with {method}: the message {message:?} names neither",
                        entry.name
                    );
                }
            }
        }
    }
    let hostile: [(&[u8], &str); 5] = [
        (b"warp-drive", "warp-drive"),
        (b"<img src=x onerror=alert(1)>", "<img src=x"),
        (b"RK4", "RK4"),
        (b" rk4", " rk4"),
        (b"\xff\xfe", "UTF-8"),
    ];
    for (method, named) in hostile {
        let message = build_through_exports(b"double-pendulum", b"{}", method).unwrap_err();
        assert!(
            message.contains(named),
            "{message:?} does not name {named:?}"
        );
    }
    // Lengths past what was written: refused, not read past the buffer.
    pk_input_bytes(4);
    assert_eq!(pk_build(4, usize::MAX, 1), 0);
    assert_eq!(pk_build(usize::MAX, 1, 1), 0);
    // The module is whole: a lab builds and runs.
    let h = build_through_exports(b"double-pendulum", b"{}", b"rk4").unwrap();
    assert_eq!(pk_step(h, 10, 1e-3), 0);
    pk_free(h);
}

/// The tolerance of an adaptive method is untrusted (a share link, a script call): values
/// that are not finite and positive, or that `taylor` cannot take, are refused naming `rtol`,
/// and the lab runs on at the tolerance it had. A tolerance the lab takes is the one its run
/// has: the same bits as a lab built at it.
#[test]
fn a_hostile_tolerance_is_refused_and_the_run_goes_on() {
    for method in ["taylor", "dop853"] {
        let mut lab = Lab::with_tolerance("kepler", "{}", Some(method), 1e-8).unwrap();
        // 1e300 asks taylor for no correct digit; dop853 takes it (a valid, useless value
        // the page's menu and link check never give).
        let taylor_only = [1e300, 1e-300];
        for bad in [f64::NAN, f64::INFINITY, -f64::INFINITY, 0.0, -1.0]
            .into_iter()
            .chain(taylor_only.into_iter().filter(|_| method == "taylor"))
        {
            let error = lab.set_tolerance(bad).unwrap_err();
            assert!(error.contains("rtol"), "{method} {bad}: {error}");
            // The tolerance kept is the one set, exactly.
            assert_eq!(lab.tolerance().to_bits(), 1e-8_f64.to_bits());
            let error = Lab::with_tolerance("kepler", "{}", Some(method), bad)
                .err()
                .unwrap();
            assert!(error.contains("rtol"), "{method} {bad}: {error}");
        }
        lab.step(50, 1e-2).unwrap();
        lab.set_tolerance(1e-12).unwrap();
        lab.reset().unwrap();
        lab.step(50, 1e-2).unwrap();
        let mut fresh = Lab::with_tolerance("kepler", "{}", Some(method), 1e-12).unwrap();
        fresh.step(50, 1e-2).unwrap();
        assert_eq!(lab.state(), fresh.state(), "{method}");
        let mut loose = Lab::with_tolerance("kepler", "{}", Some(method), 1e-6).unwrap();
        loose.step(50, 1e-2).unwrap();
        assert_ne!(
            loose.state(),
            fresh.state(),
            "{method}: the tolerance is not used"
        );
    }
    // A fixed-step method keeps a tolerance for the next adaptive one.
    let mut lab = Lab::with_method("kepler", "{}", Some("rk4")).unwrap();
    lab.set_tolerance(1e-7).unwrap();
    assert!(lab.set_tolerance(-1.0).is_err());
    lab.set_method("taylor").unwrap();
    assert_eq!(lab.tolerance().to_bits(), 1e-7_f64.to_bits());
}

/// The facts line's order comes from untrusted input (a share link's system, parameters,
/// method and tolerance): an unknown name, a tolerance that is not finite and positive, one
/// the Taylor stepper refuses (relative tolerance below 2^-54 or at least 1), an unknown
/// system and refused parameters are refused with a message naming them; every tolerance
/// Taylor accepts gives an order within its range, the order a run of that system at that
/// tolerance reports; a fixed-step method has its catalogue order whatever the tolerance.
#[test]
fn method_order_refuses_hostile_input_by_name() {
    use physicskit::classical::catalog;
    use physicskit::classical::integrators::IntegrateOptions;
    use physicskit::classical::{Method, Tolerances};
    use physicskit_wasm::method_order;
    let unknown = method_order("kepler", "{}", "<script>", 1e-10).unwrap_err();
    assert!(unknown.contains("<script>"), "{unknown}");
    for tol in [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        0.0,
        -1e-10,
        1e-300,
        1.0,
        1e300,
    ] {
        let refused = method_order("kepler", "{}", "taylor", tol).unwrap_err();
        assert!(refused.contains("rtol"), "{tol}: {refused}");
    }
    let system = method_order("<img>", "{}", "taylor", 1e-10).unwrap_err();
    assert!(system.contains("<img>"), "{system}");
    let params = method_order("kepler", r#"{"nope": 1}"#, "taylor", 1e-10).unwrap_err();
    assert!(params.contains("nope"), "{params}");
    let max = Method::Taylor.order();
    for name in ["kepler", "double-pendulum", "henon-heiles"] {
        let entry = catalog::find(name).unwrap();
        for tol in [1e-16, 1e-10, 1e-6, 0.5] {
            let order = method_order(name, "{}", "taylor", tol).unwrap();
            assert!((2..=max).contains(&order), "{name} at {tol}: order {order}");
            let run = entry
                .build_from(vec![])
                .unwrap()
                .integrate(
                    (0.0, 0.01),
                    0.01,
                    Method::Taylor,
                    IntegrateOptions {
                        tolerances: Some(Tolerances::new(tol, tol).unwrap()),
                        ..IntegrateOptions::default()
                    },
                )
                .unwrap();
            assert_eq!(
                run.extra_scalar("order"),
                Some(f64::from(order)),
                "{name} at {tol}"
            );
        }
    }
    assert_eq!(
        method_order("kepler", "{}", "verlet", 1e300).unwrap(),
        Method::Verlet.order()
    );
}
