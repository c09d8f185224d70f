//! The plain-loop references compute the same physics as the library: written independently
//! (forces, potentials and the yoshida4 loop by hand in `src/plain.rs`), both must give the
//! same trajectory and energies up to rounding. Otherwise the speed comparison would compare
//! different work.

use crate::{plain, workloads};

#[test]
fn plain_loops_match_the_library() {
    let steps = 2000;
    let mut compared = 0;
    for w in workloads::all() {
        let Some(reference) = plain::case(&w.name) else {
            continue;
        };
        let lib = w.run(steps).expect("runs");
        let (q0, p0) = w
            .start()
            .expect("builds")
            .expect("separable workloads have q and p");
        let plain = reference(&q0, &p0, steps, w.dt);
        let ndof = lib.ndof.expect("separable workloads have q and p");
        let e = lib.energy.as_ref().expect("energy stored");
        assert_eq!(plain.t.len(), lib.n_samples(), "{}", w.name);
        // Same scheme, same operations up to their order: the difference is rounding. The
        // states stay O(1) (|q| <= 2 pi for the kink, orbits of radius ~1); measured over
        // these 2000 steps at most 3.2e-14 (sine-Gordon). 1e-10 leaves room for other
        // compilers' rounding, while a wrong force or weight would differ at O(dt^2) ~ 1e-6
        // after one step.
        let last = lib.y.row(steps).to_vec();
        let (q, p) = last.split_at(ndof);
        let plain_q = &plain.q[steps * ndof..];
        let plain_p = &plain.p[steps * ndof..];
        let dy = q
            .iter()
            .zip(plain_q)
            .chain(p.iter().zip(plain_p))
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        println!("{}: max |dy| {dy:e}", w.name);
        assert!(dy < 1e-10, "{}: states differ by {dy:e}", w.name);
        // Energies: the same terms summed in another order (and from states that differ by
        // rounding), relative to the largest |E|: measured at most 2.9e-15; 1e-12 is ~350x
        // that, far below a wrong potential term (O(1)).
        let scale = e.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
        let de = e
            .iter()
            .zip(&plain.energy)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        println!("{}: max |dE| / scale {:e}", w.name, de / scale);
        assert!(de < 1e-12 * scale, "{}: energies differ by {de:e}", w.name);
        compared += 1;
    }
    assert_eq!(compared, 8, "every separable workload has a plain loop");
}
