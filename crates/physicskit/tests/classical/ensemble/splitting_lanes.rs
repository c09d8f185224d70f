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
//! that silently ran alone. A system written here, quartic wells with a mass per coordinate,
//! takes the slice path's energies with and without a potential over lanes.

use physicskit::classical::catalog;
use physicskit::classical::ensemble::{self, FromCatalogue, MemberSource, Members, Plan, Sweep};
use physicskit::classical::integrators::lanes::{Batch, LanesForce, Real, SplittingLanes};
use physicskit::classical::integrators::{HamiltonianSystem, MassInv};
use physicskit::classical::model::Value;
use physicskit::classical::symbolic::native_lanes;
use physicskit::classical::{
    DynamicalSystem, Error, IntegrateOptions, Method, Phase, Sampling, SimulationResult, TimeGrid,
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

/// A lanes run's recorded rows and energies, per member of the batch.
type Recorded = (Vec<Vec<Vec<f64>>>, Vec<Vec<Option<f64>>>);

/// `run_lanes` of the `count` members in `starts` on `lanes`, every `STRIDE`-th step recorded
/// with its energy where the lanes give it: which members failed, and each one's rows and
/// energies.
fn strided_rows(
    lanes: &dyn SplittingLanes,
    method: Method,
    starts: &[f64],
    grid: &TimeGrid,
    count: usize,
) -> physicskit::classical::Result<(Vec<bool>, Recorded)> {
    let mut rows: Vec<Vec<Vec<f64>>> = vec![Vec::new(); count];
    let mut energies: Vec<Vec<Option<f64>>> = vec![Vec::new(); count];
    let failed = lanes.run_lanes(
        native_lanes(),
        method,
        Batch {
            starts,
            grid,
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
    )?;
    Ok((failed, (rows, energies)))
}

/// `run_lanes` of the `count` members in `starts` on `lanes`, asked for each member's largest
/// energy error and no rows but the last: whether any member failed, and per member the
/// number of records and the error, where the lanes gave it.
fn folded_errors(
    lanes: &dyn SplittingLanes,
    method: Method,
    starts: &[f64],
    grid: &TimeGrid,
    count: usize,
) -> (Vec<bool>, Vec<usize>, Vec<Option<f64>>) {
    let mut records = vec![0_usize; count];
    let mut errors = vec![None; count];
    let failed = lanes
        .run_lanes(
            native_lanes(),
            method,
            Batch {
                starts,
                grid,
                every: None,
                check_every: 16,
                energy: false,
                record: &mut |m: usize, _: usize, _: &[f64], _: Option<f64>| records[m] += 1,
                largest_error: Some(&mut |m: usize, e: f64| errors[m] = Some(e)),
                stop: &|| false,
            },
        )
        .unwrap();
    (failed, records, errors)
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
            let (failed, (rows, energies)) =
                strided_rows(lanes, method, &starts, &grid, same.len())
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
        let (failed, records, errors) = folded_errors(lanes, method, &starts, &grid, same.len());
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

/// Uncoupled quartic wells `H = Σ p_i² / (2 m_i) + (k/4) Σ q_i⁴`, one mass per coordinate:
/// written here, not in the catalogue, to reach the lanes' slice path with per-coordinate
/// masses, with its potential over lanes (`potential: true`) or without one.
struct QuarticWells {
    phase: Phase,
    m_inv: Vec<f64>,
    k: f64,
    potential: bool,
}

impl QuarticWells {
    fn new(state: Vec<f64>, potential: bool) -> Self {
        let n = state.len() / 2;
        Self {
            phase: Phase::new(state, 0.0).unwrap(),
            m_inv: (0..n).map(|i| 1.0 / (1.0 + 0.75 * i as f64)).collect(),
            k: 1.3,
            potential,
        }
    }

    /// `(k/4) Σ q_i⁴`, over `f64` and over lanes.
    fn v<R: Real>(&self, q: &[R]) -> R {
        let mut sum = R::splat(0.0);
        for &x in q {
            sum += x * x * (x * x);
        }
        sum * (0.25 * self.k)
    }
}

impl HamiltonianSystem for QuarticWells {
    fn ndof(&self) -> usize {
        self.m_inv.len()
    }
    fn potential_energy(&self, q: &[f64]) -> f64 {
        self.v(q)
    }
    fn mass_inv(&self) -> MassInv<'_> {
        MassInv::PerCoordinate(&self.m_inv)
    }
    fn force(&self, q: &[f64], _t: f64, out: &mut [f64]) -> physicskit::classical::Result<()> {
        self.force_of(q, out);
        Ok(())
    }
}

impl LanesForce for QuarticWells {
    fn force_of<R: Real>(&self, q: &[R], out: &mut [R]) {
        for (f, &x) in out.iter_mut().zip(q) {
            *f = x * x * x * -self.k;
        }
    }
    fn same_force(&self, other: &Self) -> bool {
        (self.k, &self.m_inv) == (other.k, &other.m_inv)
    }
    fn potential_of<R: Real>(&self, q: &[R]) -> Option<R> {
        self.potential.then(|| self.v(q))
    }
}

physicskit::impl_separable_dynamics!(QuarticWells, {
    fn splitting_lanes(&self) -> Option<&dyn SplittingLanes> {
        Some(self)
    }
});

/// The slice path with a mass per coordinate (six wells, so the kinetic sum runs past the
/// four written-out terms): with a potential over lanes, every recorded energy is the
/// member's own `energy` of the row, bit for bit, and the largest energy error is folded in
/// the lanes (one record per member, the member's own run's error); without one, the lanes
/// give no energies and record every step for the caller to fold.
#[test]
fn slice_lanes_with_a_mass_per_coordinate_give_energies_exactly_where_they_can() {
    let l = native_lanes();
    let (dim, count) = (12, l.min(5));
    let start = |m: usize| -> Vec<f64> {
        (0..dim)
            .map(|i| 0.3 + 0.1 * (m as f64) - 0.07 * (i as f64))
            .collect()
    };
    let starts: Vec<f64> = (0..count).flat_map(start).collect();
    let (t1, dt) = (5.0, 0.01);
    let grid = TimeGrid::new((0.0, t1), dt).unwrap();
    let method = Method::Yoshida4;
    for potential in [true, false] {
        let lead = QuarticWells::new(start(0), potential);
        let (failed, (rows, energies)) =
            strided_rows(&lead, method, &starts, &grid, count).unwrap();
        assert_eq!(failed, vec![false; count]);
        let (failed, records, errors) = folded_errors(&lead, method, &starts, &grid, count);
        assert_eq!(failed, vec![false; count]);
        for m in 0..count {
            let run = |sampling: Sampling| {
                QuarticWells::new(start(m), potential)
                    .integrate_with(
                        (0.0, t1),
                        dt,
                        method,
                        IntegrateOptions {
                            sampling,
                            ..IntegrateOptions::default()
                        },
                    )
                    .unwrap()
            };
            let alone = QuarticWells::new(start(m), potential);
            // Row 0, the initial state, is not recorded by the lanes.
            let stored: Vec<Vec<f64>> = run(Sampling::Stride(STRIDE))
                .y
                .rows()
                .into_iter()
                .skip(1)
                .map(|r| r.to_vec())
                .collect();
            let bits = |rows: &[Vec<f64>]| -> Vec<u64> {
                rows.iter().flatten().map(|v| v.to_bits()).collect()
            };
            assert_eq!(
                bits(&rows[m]),
                bits(&stored),
                "potential {potential}, member {m}"
            );
            let got: Vec<Option<u64>> = energies[m].iter().map(|e| e.map(f64::to_bits)).collect();
            let want: Vec<Option<u64>> = rows[m]
                .iter()
                .map(|row| potential.then(|| alone.energy(row).to_bits()))
                .collect();
            assert_eq!(got, want, "potential {potential}, member {m}: energies");
            if potential {
                let error = run(Sampling::All).max_relative_energy_error().unwrap();
                assert_eq!(records[m], 1, "member {m}");
                assert_eq!(
                    errors[m].map(f64::to_bits),
                    Some(error.to_bits()),
                    "member {m}"
                );
            } else {
                assert_eq!(
                    (records[m], errors[m]),
                    (grid.n_steps(), None),
                    "member {m}"
                );
            }
        }
    }
}
