//! Splitting-method members run in SIMD lanes (Kepler, Hénon–Heiles, the pendulum, the
//! harmonic oscillator, the projectile, the Toda lattice): each
//! member's final state and strided trajectory are its own `integrate`'s bit for bit, for
//! every splitting method, on one thread and on two, for member counts 1, 3, a lane width,
//! twice it plus one (so batches that do not fill their lanes), and members of different
//! forces in one ensemble (a parameter swept between two values, interleaved: two groups, the
//! masses among them for the oscillator and the projectile); a member that escapes fails with
//! its own run's error, named by index, beside members that do not, and a batch of lanes flags
//! exactly its escaping members (Hénon–Heiles above the saddles' energy). The lanes runner itself is checked directly too (`run_lanes` accepts every
//! such system and reproduces each member), so the equalities above cannot come from members
//! that silently ran alone.

use physicskit::classical::catalog;
use physicskit::classical::ensemble::{self, FromCatalogue, MemberSource, Members, Plan, Sweep};
use physicskit::classical::integrators::lanes::Batch;
use physicskit::classical::model::Value;
use physicskit::classical::symbolic::native_lanes;
use physicskit::classical::{
    Error, IntegrateOptions, Method, Sampling, SimulationResult, TimeGrid,
};
use std::f64::consts::TAU;

const STRIDE: usize = 7;

fn plan(t1: f64, dt: f64, method: Method, threads: usize) -> Plan {
    Plan {
        t_span: (0.0, t1),
        dt,
        method: Some(method),
        stride: Some(STRIDE),
        reductions: vec![],
        final_state: true,
        threads: Some(threads),
        tolerances: None,
    }
}

/// Hénon–Heiles states at `E = 1/8` on `x = 0`, `n` of them, with `escaping` members at
/// `E = 0.565` (above the saddles' 1/6: they leave and their states overflow).
fn henon_heiles_states(n: usize, escaping: &[usize]) -> Vec<f64> {
    (0..n)
        .flat_map(|m| {
            if escaping.contains(&m) {
                return [0.0, 0.0, 0.8, 0.7];
            }
            let y = -0.25 + 0.45 * m as f64 / n as f64;
            let px = 0.2 - 0.3 * m as f64 / n as f64;
            let v = 0.5 * y * y - y * y * y / 3.0;
            [0.0, y, px, (2.0 * (0.125 - v) - px * px).sqrt()]
        })
        .collect()
}

/// The ensembles of `n` members: catalogue name, members, span and step.
fn ensembles(n: usize) -> Vec<(&'static str, Members, f64, f64)> {
    let kepler = Members {
        sweeps: vec![Sweep::new(
            "e",
            (0..n).map(|i| 0.05 + 0.6 * i as f64 / n as f64).collect(),
        )],
        n,
        ..Members::default()
    };
    // Two forces (c_pn = 0 and -0.01) interleaved, and a perturbation through `powf`.
    let precessing = Members {
        common: vec![
            ("eps".into(), Value::Scalar(0.3)),
            ("c_eps".into(), Value::Scalar(0.002)),
        ],
        sweeps: vec![
            Sweep::new(
                "e",
                (0..n).map(|i| 0.1 + 0.5 * i as f64 / n as f64).collect(),
            ),
            Sweep::new("c_pn", (0..n).map(|i| -0.01 * (i % 2) as f64).collect()),
        ],
        n,
        ..Members::default()
    };
    let henon_heiles = Members {
        states: Some(henon_heiles_states(n, &[])),
        n,
        ..Members::default()
    };
    let mut all = vec![
        ("kepler", kepler, 2.0 * TAU, TAU / 500.0),
        ("kepler", precessing, 2.0 * TAU, TAU / 500.0),
        ("henon-heiles", henon_heiles, 20.0, 0.02),
    ];
    all.extend(more_ensembles(n));
    all
}

/// `n` values from `a` towards `b`.
fn spread(n: usize, a: f64, b: f64) -> Vec<f64> {
    (0..n).map(|i| a + (b - a) * i as f64 / n as f64).collect()
}

/// `x` and `y` interleaved over `n` members (two force groups).
fn alternating(n: usize, x: f64, y: f64) -> Vec<f64> {
    (0..n).map(|i| if i % 2 == 0 { x } else { y }).collect()
}

/// `n` states of an `ndof`-site lattice, each a different smooth displacement and momentum.
fn lattice_states(n: usize, ndof: usize) -> Vec<f64> {
    (0..n)
        .flat_map(|m| {
            let phase = 0.37 * m as f64;
            let q = (0..ndof).map(move |j| 0.3 * (phase + 0.9 * j as f64).sin());
            let p = (0..ndof).map(move |j| 0.2 * (phase - 0.5 * j as f64).cos());
            q.chain(p).collect::<Vec<_>>()
        })
        .collect()
}

/// The systems whose forces took lanes after Kepler and Hénon–Heiles, each with one
/// parameter of the force (or mass) alternating between two values.
fn more_ensembles(n: usize) -> Vec<(&'static str, Members, f64, f64)> {
    let members = |sweeps: Vec<Sweep>, states: Option<Vec<f64>>| Members {
        sweeps,
        states,
        n,
        ..Members::default()
    };
    vec![
        (
            "pendulum",
            members(
                vec![
                    Sweep::new("q0", spread(n, 0.2, 2.9)),
                    Sweep::new("g_over_l", alternating(n, 1.0, 2.0)),
                ],
                None,
            ),
            10.0,
            0.05,
        ),
        (
            "harmonic-oscillator",
            members(
                vec![
                    Sweep::new("q0", spread(n, -1.0, 1.0)),
                    Sweep::new("m", alternating(n, 1.0, 2.5)),
                ],
                None,
            ),
            10.0,
            0.05,
        ),
        (
            "projectile",
            members(
                vec![
                    Sweep::new("speed", spread(n, 5.0, 25.0)),
                    Sweep::new("angle_deg", spread(n, 20.0, 70.0)),
                    Sweep::new("m", alternating(n, 1.0, 0.5)),
                ],
                None,
            ),
            2.0,
            0.01,
        ),
        (
            "toda",
            members(
                vec![Sweep::new("a", alternating(n, 1.0, 2.0))],
                Some(lattice_states(n, 8)),
            ),
            10.0,
            0.05,
        ),
    ]
}

/// Member `i`'s own `integrate` over `(0, t1)` by `method`, every `STRIDE`-th step stored
/// as the plans keep them (so an error names the first stored non-finite row, as theirs).
fn own_run(
    source: &impl MemberSource,
    i: usize,
    (t1, dt): (f64, f64),
    method: Method,
) -> physicskit::classical::Result<SimulationResult> {
    source.build(i, 0.0)?.integrate(
        (0.0, t1),
        dt,
        method,
        IntegrateOptions {
            sampling: Sampling::Stride(STRIDE),
            ..IntegrateOptions::default()
        },
    )
}

/// `ensemble::run` of `members` fails by every splitting method, on one thread and on two,
/// with member `bad`'s own run's error (a state that is not finite), named by its index.
fn fails_with_the_members_own_error(name: &str, members: &Members, bad: usize, span: (f64, f64)) {
    let entry = catalog::find(name).unwrap();
    let source = FromCatalogue::new(entry, members).unwrap();
    for method in splitting_methods() {
        let alone = own_run(&source, bad, span, method).unwrap_err();
        let Error::NonFinite { name, t } = alone else {
            panic!("{method:?}: member {bad} ran: {alone}");
        };
        let want = Error::NonFinite {
            name: format!("member {bad}: {name}"),
            t,
        };
        for threads in [1, 2] {
            let got = ensemble::run(entry, members, &plan(span.0, span.1, method, threads), None)
                .unwrap_err();
            assert_eq!(got, want, "{method:?}, {threads} threads");
        }
    }
}

/// The splitting methods, read from the method table.
fn splitting_methods() -> Vec<Method> {
    Method::ALL
        .into_iter()
        .filter(|m| m.needs_separable())
        .collect()
}

#[test]
fn members_in_lanes_equal_their_own_integrate_on_one_and_two_threads() {
    let l = native_lanes();
    let methods = splitting_methods();
    assert!(methods.len() >= 7, "{methods:?}");
    for n in [1, 3, l, 2 * l + 1] {
        for (name, members, t1, dt) in ensembles(n) {
            let entry = catalog::find(name).unwrap();
            let source = FromCatalogue::new(entry, &members).unwrap();
            for &method in &methods {
                let one = ensemble::run(entry, &members, &plan(t1, dt, method, 1), None).unwrap();
                let two = ensemble::run(entry, &members, &plan(t1, dt, method, 2), None).unwrap();
                assert_eq!(one, two, "{name}, {method:?}, {n} members: 1 and 2 threads");
                let trajectory = one.trajectory.as_ref().unwrap();
                for i in 0..n {
                    let alone = own_run(&source, i, (t1, dt), method).unwrap();
                    let last = alone.y.nrows() - 1;
                    let bits = |v: Vec<f64>| v.into_iter().map(f64::to_bits).collect::<Vec<_>>();
                    assert_eq!(
                        bits(one.final_state.row(i).to_vec()),
                        bits(alone.y.row(last).to_vec()),
                        "{name}, {method:?}, {n} members, member {i}: final state"
                    );
                    let mine = trajectory.index_axis(ndarray::Axis(0), i);
                    assert_eq!(mine.dim(), alone.y.dim(), "{name}: trajectory shape");
                    assert_eq!(
                        bits(mine.iter().copied().collect()),
                        bits(alone.y.iter().copied().collect()),
                        "{name}, {method:?}, {n} members, member {i}: trajectory"
                    );
                    assert_eq!(one.steps[i], (t1 / dt).round() as usize, "{name}: steps");
                }
            }
        }
    }
}

/// Members 5 and 9 of 12 escape: the ensemble reports member 5's error, as its own run
/// reports it, prefixed with its index; on two threads too. The others' runs are unharmed:
/// without the escaping members' rows the same ensemble's final states are theirs.
#[test]
fn an_escaping_member_fails_with_its_own_error_beside_good_ones() {
    let members = Members {
        states: Some(henon_heiles_states(12, &[5, 9])),
        n: 12,
        ..Members::default()
    };
    fails_with_the_members_own_error("henon-heiles", &members, 5, (40.0, 0.05));
}

/// Among the first `l` members, those of the first member's force (every other one where a
/// parameter alternates), and their initial states one after another: a batch for `run_lanes`.
fn first_force_batch(source: &FromCatalogue<'_>, l: usize) -> (Vec<usize>, Vec<f64>) {
    let first = source.build(0, 0.0).unwrap();
    let lanes = first.dynamical().splitting_lanes().unwrap();
    let same: Vec<usize> = (0..l)
        .filter(|&i| {
            let b = source.build(i, 0.0).unwrap();
            lanes.same_force_as(b.dynamical().splitting_lanes().unwrap())
        })
        .collect();
    let starts = same
        .iter()
        .flat_map(|&i| source.build(i, 0.0).unwrap().dynamical().state().to_vec())
        .collect();
    (same, starts)
}

/// `run_lanes` of each system above, called directly on a batch of a lane width of members
/// sharing the first member's force: accepted for every splitting method, no member fails,
/// and every recorded row is the member's own strided trajectory's, bit for bit. Asked for
/// energies, the lanes give them for every one of these systems (each has a potential over
/// lanes; the Toda lattice's runs over slices), each bit for bit the member's own `energy` of
/// the row.
#[test]
fn run_lanes_accepts_every_lanes_system_and_reproduces_each_member() {
    let l = native_lanes();
    for (name, members, t1, dt) in ensembles(l) {
        let entry = catalog::find(name).unwrap();
        let source = FromCatalogue::new(entry, &members).unwrap();
        let (same, starts) = first_force_batch(&source, l);
        if !matches!(name, "kepler" | "henon-heiles") {
            // One of two alternating values of a parameter the force or the mass reads.
            assert_eq!(same, (0..l).step_by(2).collect::<Vec<_>>(), "{name}");
        }
        let first = source.build(0, 0.0).unwrap();
        let lanes = first.dynamical().splitting_lanes().unwrap();
        let grid = TimeGrid::new((0.0, t1), dt).unwrap();
        for method in splitting_methods() {
            assert!(lanes.accepts(method), "{name}, {method:?}");
            let mut rows: Vec<Vec<Vec<f64>>> = vec![Vec::new(); same.len()];
            let mut energies: Vec<Vec<Option<f64>>> = vec![Vec::new(); same.len()];
            let failed = lanes
                .run_lanes(
                    l,
                    method,
                    Batch {
                        starts: &starts,
                        grid: &grid,
                        every: Some(STRIDE),
                        check_every: 16,
                        energy: true,
                        record: &mut |m: usize, _: usize, y: &[f64], e: Option<f64>| {
                            rows[m].push(y.to_vec());
                            energies[m].push(e);
                        },
                        largest_error: None,
                        stop: &|| false,
                    },
                )
                .unwrap_or_else(|e| panic!("{name}, {method:?}: {e}"));
            assert_eq!(failed, vec![false; same.len()], "{name}, {method:?}");
            for (m, &i) in same.iter().enumerate() {
                let alone = own_run(&source, i, (t1, dt), method).unwrap();
                // Row 0 of the trajectory is the initial state, which the runner does not
                // record.
                let want: Vec<u64> = alone
                    .y
                    .iter()
                    .skip(alone.y.ncols())
                    .map(|v| v.to_bits())
                    .collect();
                let got: Vec<u64> = rows[m].iter().flatten().map(|v| v.to_bits()).collect();
                assert_eq!(got, want, "{name}, {method:?}, member {i}");
                let member = source.build(i, 0.0).unwrap();
                let own_energy = |row: &Vec<f64>| member.dynamical().energy(row).to_bits();
                let got: Vec<Option<u64>> =
                    energies[m].iter().map(|e| e.map(f64::to_bits)).collect();
                let want: Vec<Option<u64>> =
                    rows[m].iter().map(|row| Some(own_energy(row))).collect();
                assert_eq!(got, want, "{name}, {method:?}, member {i}: energies");
            }
        }
    }
}

/// In one batch of lanes (9 members, or a lane width if fewer), member 2 and the last
/// (Hénon–Heiles above the saddles' energy) leave and overflow: `run_lanes` flags exactly
/// those two, and the others, in the lanes of the same force, run to the end, each with its
/// own run's final state.
#[test]
fn run_lanes_flags_only_the_escaping_members_of_a_batch() {
    let entry = catalog::find("henon-heiles").unwrap();
    let count = native_lanes().min(9);
    let escaping = [2, count - 1];
    let members = Members {
        states: Some(henon_heiles_states(count, &escaping)),
        n: count,
        ..Members::default()
    };
    let (t1, dt) = (40.0, 0.05);
    let source = FromCatalogue::new(entry, &members).unwrap();
    let starts: Vec<f64> = (0..count)
        .flat_map(|i| source.build(i, 0.0).unwrap().dynamical().state().to_vec())
        .collect();
    let first = source.build(0, 0.0).unwrap();
    let lanes = first.dynamical().splitting_lanes().unwrap();
    let grid = TimeGrid::new((0.0, t1), dt).unwrap();
    for method in splitting_methods() {
        let mut finals = vec![Vec::new(); count];
        let n = grid.n_steps();
        let failed = lanes
            .run_lanes(
                native_lanes(),
                method,
                Batch {
                    starts: &starts,
                    grid: &grid,
                    every: None,
                    check_every: 16,
                    energy: false,
                    record: &mut |m: usize, step: usize, y: &[f64], _: Option<f64>| {
                        assert_eq!(step, n);
                        finals[m] = y.to_vec();
                    },
                    largest_error: None,
                    stop: &|| false,
                },
            )
            .unwrap();
        let flagged: Vec<usize> = (0..count).filter(|&i| failed[i]).collect();
        assert_eq!(flagged, escaping, "{method:?}");
        for i in (0..count).filter(|&i| !failed[i]) {
            let alone = own_run(&source, i, (t1, dt), method).unwrap();
            let last = alone.y.row(alone.y.nrows() - 1).to_vec();
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&finals[i]), bits(&last), "{method:?}, member {i}");
        }
    }
}

/// Asked for each member's largest energy error and no rows but the last, the lanes fold it
/// themselves (Hénon–Heiles, the pendulum on fixed-length arrays, the Toda lattice over
/// slices): one record per member, and the error, bit for bit that of the member's own run
/// with every step stored.
#[test]
fn run_lanes_folds_the_largest_energy_error_where_it_computes_energies() {
    let l = native_lanes();
    for (name, members, t1, dt) in ensembles(l) {
        if !matches!(name, "henon-heiles" | "pendulum" | "toda") {
            continue;
        }
        let entry = catalog::find(name).unwrap();
        let source = FromCatalogue::new(entry, &members).unwrap();
        let first = source.build(0, 0.0).unwrap();
        let lanes = first.dynamical().splitting_lanes().unwrap();
        let (same, starts) = first_force_batch(&source, l);
        let grid = TimeGrid::new((0.0, t1), dt).unwrap();
        let method = Method::Yoshida4;
        let mut records = vec![0_usize; same.len()];
        let mut errors = vec![None; same.len()];
        let failed = lanes
            .run_lanes(
                l,
                method,
                Batch {
                    starts: &starts,
                    grid: &grid,
                    every: None,
                    check_every: 16,
                    energy: false,
                    record: &mut |m: usize, _: usize, _: &[f64], _: Option<f64>| records[m] += 1,
                    largest_error: Some(&mut |m: usize, e: f64| errors[m] = Some(e)),
                    stop: &|| false,
                },
            )
            .unwrap();
        assert_eq!(failed, vec![false; same.len()], "{name}");
        for (m, &i) in same.iter().enumerate() {
            let own = source
                .build(i, 0.0)
                .unwrap()
                .integrate(
                    (0.0, t1),
                    dt,
                    method,
                    IntegrateOptions {
                        sampling: Sampling::All,
                        ..IntegrateOptions::default()
                    },
                )
                .unwrap()
                .max_relative_energy_error()
                .unwrap();
            assert_eq!(records[m], 1, "{name}, member {i}");
            assert_eq!(
                errors[m].map(f64::to_bits),
                Some(own.to_bits()),
                "{name}, member {i}"
            );
        }
    }
}
