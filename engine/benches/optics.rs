//! Criterion benchmarks of the optics: the exact emission solve and
//! aberration of every vertex of one body, and of a 1 000-puck gas on one
//! thread (the workload of [`lightcone_engine::optics::solve_rate`]).
//! `cargo bench -p lightcone-engine --bench optics`.
//! (`lightcone bench optics` and the `optics_rate` example print the
//! solves-per-second table of BENCHMARKS.md, on 1 and 2 threads.)

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use lightcone_engine::optics::solve_rate::{BodyOutput, SolveRate};

fn emission_solves(c: &mut Criterion) {
    let mut group = c.benchmark_group("emission_solves");
    for segments in [48u32, 512] {
        let work = SolveRate::gas(1000, segments);
        let per_body = work.vertices_per_puck() as u64;
        let mut out = BodyOutput::default();
        group.throughput(Throughput::Elements(per_body));
        let mut puck = 0;
        group.bench_function(format!("one_body/{per_body}_vertices"), |bench| {
            bench.iter(|| {
                puck = (puck + 1) % work.pucks();
                black_box(work.solve(black_box(puck), &mut out))
            })
        });
        group.throughput(Throughput::Elements(work.vertices() as u64));
        group.bench_function(
            format!("gas_1000_pucks/{per_body}_vertices_each"),
            |bench| {
                bench.iter(|| {
                    (0..work.pucks())
                        .map(|puck| work.solve(puck, &mut out))
                        .sum::<usize>()
                })
            },
        );
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = emission_solves
}
criterion_main!(benches);
