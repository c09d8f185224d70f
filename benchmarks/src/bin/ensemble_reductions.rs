//! Ensembles with a reduction: 1000 Hénon–Heiles orbits (`E = 1/8`, launched on `x = 0`, the
//! members of `splitting_lanes`) to `t = 100`, keeping each member's final state and its
//! maximum relative energy error (`Reduction::MaxEnergyError`), by `yoshida4` (`dt = 0.01`)
//! and by `taylor` (default tolerances, outputs every 0.1).
//!
//! Per workload: `ensemble1_ms`, `ensemble2_ms`, the best of `N` (first argument, default 5)
//! after one untimed run of `ensemble::run` on one and on two threads; `same_bits`, whether
//! both runs' energy errors and final states equal, bit for bit, those of each member's own
//! `integrate` (`SimulationResult::max_relative_energy_error`, every step stored).

use physicskit::classical::catalog;
use physicskit::classical::ensemble::{self, FromCatalogue, MemberSource, Plan, Reduction};
use physicskit::classical::{IntegrateOptions, Method, Sampling};
use physicskit_benchmarks::ensembles::{best_of, henon_heiles, MEMBERS};

const T_END: f64 = 100.0;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(5);
    let entry = catalog::find("henon-heiles").expect("catalogue entry");
    let members = henon_heiles();
    let source = FromCatalogue::new(entry, &members).expect("members");
    for (method, dt) in [(Method::Yoshida4, 0.01), (Method::Taylor, 0.1)] {
        // Each member's own run: its energy error, then its final state.
        let reference: Vec<f64> = (0..MEMBERS)
            .flat_map(|i| {
                let result = source
                    .build(i, 0.0)
                    .expect("member")
                    .integrate(
                        (0.0, T_END),
                        dt,
                        method,
                        IntegrateOptions {
                            sampling: Sampling::All,
                            ..IntegrateOptions::default()
                        },
                    )
                    .expect("run");
                let error = result.max_relative_energy_error().expect("energies");
                std::iter::once(error).chain(result.final_state().to_vec())
            })
            .collect();
        let run = |threads: usize| {
            let plan = Plan {
                t_span: (0.0, T_END),
                dt,
                method: Some(method),
                stride: None,
                reductions: vec![Reduction::MaxEnergyError],
                final_state: true,
                threads: Some(threads),
                tolerances: None,
            };
            best_of(n, || {
                let out = ensemble::run(entry, &members, &plan, None).expect("ensemble");
                let errors = &out.reductions[0].1;
                (0..MEMBERS)
                    .flat_map(|i| std::iter::once(errors[i]).chain(out.final_state.row(i).to_vec()))
                    .collect()
            })
        };
        let (one, out1) = run(1);
        let (two, out2) = run(2);
        let same = |a: &[f64]| {
            a.len() == reference.len()
                && a.iter()
                    .zip(&reference)
                    .all(|(x, y)| x.to_bits() == y.to_bits())
        };
        println!(
            "{{\"system\": \"henon-heiles\", \"method\": \"{}\", \"dt\": {dt}, \"members\": \
             {MEMBERS}, \"ensemble1_ms\": {one:.2}, \"ensemble2_ms\": {two:.2}, \"same_bits\": {}}}",
            method.name(),
            same(&out1) && same(&out2)
        );
    }
}
