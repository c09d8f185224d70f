//! What the ensemble binaries (`splitting_lanes`, `ensemble_reductions`) share: their number
//! of members, their Hénon–Heiles members and their best-of timing.

use std::time::Instant;

use physicskit::classical::ensemble::Members;

/// Members in each ensemble workload.
pub const MEMBERS: usize = 1000;

/// [`MEMBERS`] Hénon–Heiles states at `E = 1/8` on `x = 0`: 50 heights `y` in `[-0.2, 0.2]`
/// by 20 momenta `p_x` in `(-0.3, 0.3)`, `p_y > 0` from the energy.
pub fn henon_heiles() -> Members {
    let states = (0..MEMBERS)
        .flat_map(|m| {
            let y = -0.2 + 0.4 * (m / 20) as f64 / 49.0;
            let px = -0.3 + 0.6 * ((m % 20) as f64 + 0.5) / 20.0;
            let v = 0.5 * y * y - y * y * y / 3.0;
            [0.0, y, px, (2.0 * (0.125 - v) - px * px).sqrt()]
        })
        .collect();
    Members {
        states: Some(states),
        n: MEMBERS,
        ..Members::default()
    }
}

/// The best wall time of `n` runs of `f`, in milliseconds, after one untimed run whose output
/// is returned beside it.
pub fn best_of(n: usize, mut f: impl FnMut() -> Vec<f64>) -> (f64, Vec<f64>) {
    let out = f();
    let mut best = f64::INFINITY;
    for _ in 0..n {
        let start = Instant::now();
        std::hint::black_box(f());
        best = best.min(start.elapsed().as_secs_f64());
    }
    (best * 1e3, out)
}
