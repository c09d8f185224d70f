//! The library against a hand-written loop of the same scheme, system and storage.
//!
//! `cargo bench -p physicskit-benchmarks --bench vs_plain`. The target: each separable
//! case within 1.25x of its plain loop. Both sides run 10^4 yoshida4 steps storing t, q, p and
//! the energy of every sample.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use physicskit::classical::Method;
use physicskit_benchmarks::{plain, workloads};
use std::hint::black_box;

const STEPS: usize = 10_000;

fn vs_plain(c: &mut Criterion) {
    for w in workloads::all() {
        let Some(reference) = plain::case(&w.name) else {
            continue;
        };
        let (q0, p0) = w
            .start()
            .expect("workload builds")
            .expect("separable workloads have q and p");
        if w.method != Method::Yoshida4 {
            continue;
        }
        let mut group = c.benchmark_group(&w.name);
        group.throughput(Throughput::Elements(STEPS as u64));
        group.bench_function(BenchmarkId::new("physicskit", STEPS), |b| {
            b.iter(|| black_box(w.run(STEPS).expect("workload runs")))
        });
        group.bench_function(BenchmarkId::new("plain", STEPS), |b| {
            b.iter(|| black_box(reference(&q0, &p0, STEPS, w.dt)))
        });
        group.finish();
    }
}

criterion_group!(benches, vs_plain);
criterion_main!(benches);
