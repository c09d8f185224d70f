//! Chaos maps (`analysis/chaos_map.rs`): bit-identical for any number of threads, and each
//! point's indicator equals the one computed on its own.

use crate::analysis::lyapunov::chaotic_orbit;
use physicskit::classical::analysis::chaos_map::{chaos_map, Indicator, MapRun};
use physicskit::classical::analysis::lyapunov::max_lyapunov;
use physicskit::classical::analysis::poincare::Direction;
use physicskit::classical::analysis::section::SurfaceOfSection;
use physicskit::classical::model::erased::DynSystem;

/// A line of initial states across the Hénon–Heiles section at E = 1/8 (x = 0, y from -0.3
/// to 0.3, p_x = 0, p_y from the energy).
fn states(n: usize) -> Vec<f64> {
    let e = 1.0 / 8.0;
    (0..n)
        .flat_map(|i| {
            let y = -0.3 + 0.6 * i as f64 / (n - 1) as f64;
            let v = 0.5 * y * y - y * y * y / 3.0;
            [0.0, y, 0.0, (2.0 * (e - v)).sqrt()]
        })
        .collect()
}

fn on_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

/// One and two threads give the same bits for each indicator (fixed chunks, independent
/// points), and a point's value is that of its orbit run alone.
#[test]
fn maps_are_bit_identical_on_any_number_of_threads() {
    let system = chaotic_orbit();
    let states = states(9);
    let plane = SurfaceOfSection::coordinate(1, 0.0, Direction::Increasing).unwrap();
    for indicator in [
        Indicator::MaxLyapunov {
            renormalize_every: 10,
        },
        Indicator::Sali {
            renormalize_every: 10,
        },
        Indicator::Crossings(plane),
    ] {
        let run = MapRun {
            t_span: (0.0, 50.0),
            dt: 0.01,
            method: None,
            indicator,
        };
        let one = on_pool(1, || chaos_map(&system, &states, &run).unwrap());
        let two = on_pool(2, || chaos_map(&system, &states, &run).unwrap());
        assert_eq!(
            one.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
            two.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
        );
        assert!(one.iter().all(|v| v.is_finite()));
        if let Indicator::MaxLyapunov { .. } = run.indicator {
            let mut alone = chaotic_orbit();
            alone.reset(Some(&states[4 * 4..5 * 4]), 0.0).unwrap();
            let s = max_lyapunov(&mut alone, (0.0, 50.0), 0.01, None, 10).unwrap();
            assert_eq!(s.exponents[0].to_bits(), one[4].to_bits());
        }
    }
    // The system itself is not moved.
    assert_eq!(system.dynamical().t().to_bits(), 0.0f64.to_bits());
}
