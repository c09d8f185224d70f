//! ns per step of each integrator on small systems (criterion).
//!
//! `cargo bench -p physicskit --bench integrators`. Each benchmark integrates 10^4 steps and
//! reports the time per call; divide by 10^4 for ns/step. `final_only` measures the stepping
//! alone; `stored` adds writing every sample and its energy, as `integrate` does by default.
//! `sin`, `sum_cos` and `trig_systems` (ns per element, per 10^3 steps) time the slice trig
//! functions and the two systems bound by them.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use physicskit::classical::examples::{HarmonicOscillator, Pendulum};
use physicskit::classical::{HamiltonianSystem, IntegrateOptions, Method};
use std::hint::black_box;

const STEPS: u64 = 10_000;
const DT: f64 = 1e-3;

fn integrators(c: &mut Criterion) {
    let mut group = c.benchmark_group("pendulum");
    group.throughput(Throughput::Elements(STEPS));
    for method in Method::ALL {
        group.bench_with_input(
            BenchmarkId::new("stored", method.name()),
            &method,
            |b, &m| {
                b.iter(|| {
                    let mut p = Pendulum::new(1.0, 0.0, 1.0).unwrap();
                    black_box(p.integrate((0.0, STEPS as f64 * DT), DT, m).unwrap())
                })
            },
        );
        group.bench_with_input(
            BenchmarkId::new("final_only", method.name()),
            &method,
            |b, &m| {
                b.iter(|| {
                    let mut p = Pendulum::new(1.0, 0.0, 1.0).unwrap();
                    black_box(
                        p.integrate_with(
                            (0.0, STEPS as f64 * DT),
                            DT,
                            m,
                            IntegrateOptions::final_only(),
                        )
                        .unwrap(),
                    )
                })
            },
        );
    }
    group.finish();

    let mut group = c.benchmark_group("oscillator_implicit_midpoint");
    group.throughput(Throughput::Elements(STEPS));
    for dt in [1e-3, 1e-1] {
        group.bench_with_input(BenchmarkId::from_parameter(dt), &dt, |b, &dt| {
            b.iter(|| {
                let mut o = HarmonicOscillator::new(1.0, 0.0, 1.0, 1.0).unwrap();
                black_box(
                    o.integrate_with(
                        (0.0, STEPS as f64 * dt),
                        dt,
                        Method::ImplicitMidpoint,
                        IntegrateOptions::final_only(),
                    )
                    .unwrap(),
                )
            })
        });
    }
    group.finish();
}

/// Slice sine and cosine sum (vectorized, 1-ulp class) against libm, per element.
fn trig(c: &mut Criterion) {
    use physicskit::classical::core::trig::{sin_into, sum_cos};
    let mut group = c.benchmark_group("sin");
    for n in [100usize, 200, 100_000] {
        let x: Vec<f64> = (0..n).map(|i| i as f64 * 0.013 - 1.0).collect();
        let mut out = vec![0.0; n];
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::new("slice", n), &x, |b, x| {
            b.iter(|| sin_into(black_box(x), &mut out))
        });
        group.bench_with_input(BenchmarkId::new("libm", n), &x, |b, x| {
            b.iter(|| {
                for (o, v) in out.iter_mut().zip(black_box(x)) {
                    *o = v.sin();
                }
            })
        });
    }
    group.finish();

    // The energy of a stored sample of the swarm: 200 cosines added in index order.
    let mut group = c.benchmark_group("sum_cos");
    let x: Vec<f64> = (0..200).map(|i| f64::from(i) * 0.013 - 1.0).collect();
    group.throughput(Throughput::Elements(200));
    group.bench_function(BenchmarkId::new("slice", 200), |b| {
        b.iter(|| sum_cos(black_box(&x)))
    });
    group.bench_function(BenchmarkId::new("libm", 200), |b| {
        b.iter(|| black_box(&x).iter().map(|v| v.cos()).sum::<f64>())
    });
    group.finish();
}

/// The two trig-bound systems stepping alone (yoshida4, final state only): the pendulum swarm
/// (n = 200, 600 sines per step) and the sine-Gordon kink (n = 100, 300 sines per step).
fn trig_systems(c: &mut Criterion) {
    use physicskit::classical::systems::{PendulumSwarm, SineGordonChain};
    const SYSTEM_STEPS: u64 = 1_000;
    let mut group = c.benchmark_group("trig_systems");
    group.throughput(Throughput::Elements(SYSTEM_STEPS));
    let final_only = |dt: f64| {
        (
            (0.0, SYSTEM_STEPS as f64 * dt),
            dt,
            Method::Yoshida4,
            IntegrateOptions::final_only(),
        )
    };
    group.bench_function("swarm_200", |b| {
        b.iter(|| {
            let mut s = PendulumSwarm::from_box(1.0, 0.0, 0.05, 0.05, 200, 1.0, 0).unwrap();
            let (span, dt, m, o) = final_only(1e-3);
            black_box(s.integrate_with(span, dt, m, o).unwrap())
        })
    });
    group.bench_function("sine_gordon_100", |b| {
        let (q0, p0) = SineGordonChain::kink(100, 50.0, 1.0, 0.2, 1).unwrap();
        b.iter(|| {
            let mut s = SineGordonChain::new(100, 1.0, 1.0, Some(&q0), Some(&p0)).unwrap();
            let (span, dt, m, o) = final_only(1e-2);
            black_box(s.integrate_with(span, dt, m, o).unwrap())
        })
    });
    group.finish();
}

criterion_group!(benches, integrators, trig, trig_systems);
criterion_main!(benches);
