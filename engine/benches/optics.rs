//! Criterion benchmarks of the optics: the exact emission solve and
//! aberration of every vertex of one body, and of a 1 000-puck gas on one
//! thread. `cargo bench -p lightcone-engine --bench optics`.
//! (`lightcone bench optics` and the `optics_rate` example print the
//! solves-per-second table of BENCHMARKS.md, on 1 and 2 threads.)

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec3;
use lightcone_engine::optics::eye::{Eye, Seen};
use lightcone_engine::optics::view::{self, Method};
use lightcone_engine::optics::{Emission, mesh};
use lightcone_engine::physics::gas::dense_box;
use lightcone_engine::scene::Effects;
use lightcone_engine::spacetime::{Event, ProperVelocity};
use lightcone_engine::worldline::ContractedShape;

fn emission_solves(c: &mut Criterion) {
    // The gas of BENCHMARKS.md's table, run 2 s so worldlines have kinks.
    let n = 1000;
    let r = 0.0305;
    let mut b = dense_box(n, r, 3.0 * r, 0.8, 1.42, 11);
    b.advance_to(2.0);
    let size = b.table();
    let eye = Eye {
        event: Event::new(2.0, DVec3::new(size.x / 2.0, -1.0, 0.8)),
        u: ProperVelocity::ZERO,
    };
    let effects = Effects::default();
    let contracted: Vec<ContractedShape> = (0..n)
        .map(|i| ContractedShape::of(b.worldline(i)))
        .collect();
    let mut group = c.benchmark_group("emission_solves");
    for segments in [48u32, 512] {
        let shape = mesh::puck(r, 0.02, segments);
        let (mut e, mut s): (Vec<Emission>, Vec<Seen>) = (Vec::new(), Vec::new());
        let mut solve = |puck: usize| {
            view::emissions_with_shape(
                &contracted[puck],
                puck,
                b.worldline(puck),
                &shape.vertices,
                &eye,
                &effects,
                Method::Exact,
                &mut e,
            );
            view::seen(&eye, b.c(), &effects, &e, &mut s);
            s.len()
        };
        let per_body = shape.vertices.len() as u64;
        group.throughput(Throughput::Elements(per_body));
        let mut puck = 0;
        group.bench_function(format!("one_body/{per_body}_vertices"), |bench| {
            bench.iter(|| {
                puck = (puck + 1) % n;
                black_box(solve(black_box(puck)))
            })
        });
        group.throughput(Throughput::Elements(per_body * n as u64));
        group.bench_function(
            format!("gas_1000_pucks/{per_body}_vertices_each"),
            |bench| bench.iter(|| (0..n).map(&mut solve).sum::<usize>()),
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
