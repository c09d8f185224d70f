//! The chaos loops' options (`analysis/watch.rs`): a thinned history keeps exactly the rows
//! of the full one (the numbers never depend on it), a history too large for memory is
//! refused before the run, and the observer stops a run as it stops `integrate`.

use std::ops::ControlFlow;

use crate::analysis::lyapunov::chaotic_orbit;
use physicskit::classical::analysis::lyapunov::lyapunov_on_flow;
use physicskit::classical::analysis::poincare::Direction;
use physicskit::classical::analysis::sali::{alignment_on_flow, Alignment};
use physicskit::classical::analysis::section::{section_on_flow, SurfaceOfSection};
use physicskit::classical::analysis::watch::AnalysisOptions;
use physicskit::classical::model::erased::DynSystem;
use physicskit::classical::{Error, Method, Observer, TimeGrid};

/// Stops after `stop_at` steps; counts its calls.
struct StopAfter {
    stop_at: usize,
    calls: Vec<usize>,
}

impl Observer for StopAfter {
    fn observe(&mut self, step: usize, _n_steps: usize, _t: f64) -> ControlFlow<()> {
        self.calls.push(step);
        if step >= self.stop_at {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}

fn lyapunov_with(
    grid: &TimeGrid,
    every: usize,
    options: AnalysisOptions<'_>,
) -> physicskit::classical::Result<physicskit::classical::analysis::lyapunov::LyapunovSpectrum> {
    let sys = chaotic_orbit();
    let state0 = sys.dynamical().state().to_vec();
    let mut flow = sys.flow(Method::Yoshida4, 4)?;
    lyapunov_on_flow(flow.as_mut(), &state0, grid, 4, every, options).map(|(s, _)| s)
}

/// 1003 steps renormalized every 10: 101 rows (the last after 3 steps). Stride 7 keeps rows
/// 6, 13, ..., 97 and the last, bit for bit; the exponents are the full run's, bit for bit.
#[test]
fn a_thinned_history_keeps_the_full_ones_rows() {
    let grid = TimeGrid::new((0.0, 10.03), 0.01).unwrap();
    assert_eq!(grid.n_steps(), 1003);
    let full = lyapunov_with(&grid, 10, AnalysisOptions::default()).unwrap();
    let thin = lyapunov_with(&grid, 10, AnalysisOptions::default().with_history_stride(7)).unwrap();
    assert_eq!(full.t.len(), 101);
    let rows: Vec<usize> = (6..101).step_by(7).chain([100]).collect();
    assert_eq!(thin.t.len(), rows.len());
    for (j, &i) in rows.iter().enumerate() {
        assert_eq!(thin.t[j].to_bits(), full.t[i].to_bits());
        for c in 0..4 {
            assert_eq!(
                thin.history[4 * j + c].to_bits(),
                full.history[4 * i + c].to_bits()
            );
        }
    }
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&thin.exponents), bits(&full.exponents));
}

/// SALI thinned: the start, every 5th evaluation and the last are kept, and the minimum (so
/// the verdict) is over all evaluations, kept or not.
#[test]
fn a_thinned_sali_keeps_its_minimum_and_verdict() {
    let grid = TimeGrid::new((0.0, 300.0), 0.01).unwrap();
    let run = |stride| {
        let sys = chaotic_orbit();
        let state0 = sys.dynamical().state().to_vec();
        let mut flow = sys.flow(Method::Yoshida4, 2).unwrap();
        let options = AnalysisOptions::default().with_history_stride(stride);
        alignment_on_flow(
            flow.as_mut(),
            &state0,
            &grid,
            Alignment::Sali,
            10,
            0.0,
            options,
        )
        .unwrap()
        .0
    };
    let full = run(1);
    let thin = run(5);
    let all_min = full.index.iter().copied().fold(f64::INFINITY, f64::min);
    assert_eq!(full.minimum.to_bits(), all_min.to_bits());
    assert_eq!(thin.minimum.to_bits(), full.minimum.to_bits());
    assert_eq!(thin.verdict(), full.verdict());
    // 3000 evaluations after the start: the start, rows 5, 10, ..., 3000.
    assert_eq!(full.t.len(), 3001);
    assert_eq!(thin.t.len(), 601);
    assert_eq!(thin.index[1].to_bits(), full.index[5].to_bits());
    assert_eq!(
        thin.t.last().unwrap().to_bits(),
        full.t.last().unwrap().to_bits()
    );
}

/// 1e15 steps renormalized at each: 1e15 rows of 5 numbers, 4e16 bytes, more than any
/// machine here has; refused at once, before a step is taken. Thinned to one row in 1e9, the
/// same run would fit (it is not run).
#[test]
fn a_history_too_large_is_refused_up_front() {
    let grid = TimeGrid::new((0.0, 1e13), 0.01).unwrap();
    let started = std::time::Instant::now();
    let err = lyapunov_with(&grid, 1, AnalysisOptions::default()).unwrap_err();
    assert!(matches!(err, Error::TrajectoryTooLarge { .. }), "{err}");
    // Generous: the refusal reads /proc/meminfo and allocates nothing.
    assert!(started.elapsed().as_secs_f64() < 1.0);
}

/// The observer is called every `observe_every` steps of a Lyapunov run, a SALI run and a
/// section, and its `Break` ends each with `Interrupted` at the time of its last step.
#[test]
fn the_observer_stops_every_chaos_loop() {
    let grid = TimeGrid::new((0.0, 100.0), 0.01).unwrap();
    let sys = chaotic_orbit();
    let state0 = sys.dynamical().state().to_vec();
    let expect_stop = |result: Error, observer: &StopAfter| {
        assert_eq!(observer.calls, vec![100, 200, 300]);
        match result {
            Error::Interrupted { t } => assert!((t - 3.0).abs() < 1e-12, "t = {t}"),
            other => panic!("{other}"),
        }
    };
    let mut observer = StopAfter {
        stop_at: 300,
        calls: Vec::new(),
    };
    let e = lyapunov_with(&grid, 10, AnalysisOptions::observed(&mut observer, 100)).unwrap_err();
    expect_stop(e, &observer);

    let mut observer = StopAfter {
        stop_at: 300,
        calls: Vec::new(),
    };
    let mut flow = sys.flow(Method::Yoshida4, 2).unwrap();
    let options = AnalysisOptions::observed(&mut observer, 100);
    let e = alignment_on_flow(
        flow.as_mut(),
        &state0,
        &grid,
        Alignment::Sali,
        10,
        0.0,
        options,
    )
    .unwrap_err();
    expect_stop(e, &observer);

    let mut observer = StopAfter {
        stop_at: 300,
        calls: Vec::new(),
    };
    let mut flow = sys.flow(Method::Yoshida4, 0).unwrap();
    let surface = SurfaceOfSection::coordinate(0, 0.0, Direction::Increasing).unwrap();
    let options = AnalysisOptions::observed(&mut observer, 100);
    let e =
        section_on_flow(flow.as_mut(), &state0, &grid, &surface, usize::MAX, options).unwrap_err();
    expect_stop(e, &observer);
}
