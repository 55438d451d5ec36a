//! Exact emission solves per second, the table "Exact emission solves per
//! second" of BENCHMARKS.md (`lightcone bench optics` prints the same):
//! `cargo run --release -p lightcone-engine --example optics_rate -- [SEGMENTS] [REPS] [THREADS]`
//!
//! 1 000 pucks of a gas run for 2 s, a puck mesh of `SEGMENTS` around
//! (default 512: 1 024 000 vertices), every vertex's emission event and
//! apparent position (aberration on), best of `REPS` runs (default 10),
//! on `THREADS` threads (1 or 2; default both). Two ways to keep the
//! output: each thread's arrays used for one body after another (in
//! cache), and one pair of arrays per body kept from frame to frame, as
//! the frame pipeline keeps them. Also prints the CPU time per vertex of
//! the first, steadier than the wall clock on a shared machine.

use std::time::Instant;

use glam::DVec3;
use lightcone_engine::optics::eye::{Eye, Seen};
use lightcone_engine::optics::view::{self, Method};
use lightcone_engine::optics::{Emission, mesh};
use lightcone_engine::physics::gas::dense_box;
use lightcone_engine::scene::Effects;
use lightcone_engine::spacetime::{Event, ProperVelocity};
use lightcone_engine::worldline::ContractedShape;
use rayon::prelude::*;

fn main() {
    let mut args = std::env::args().skip(1);
    let segments: u32 = args.next().and_then(|s| s.parse().ok()).unwrap_or(512);
    let reps: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(10);
    let threads: Option<usize> = args.next().and_then(|s| s.parse().ok());
    let n = 1000;
    let r = 0.0305;
    let mut b = dense_box(n, r, 3.0 * r, 0.8, 1.42, 11);
    b.advance_to(2.0);
    let shape = mesh::puck(r, 0.02, segments);
    let size = b.table();
    let eye = Eye {
        event: Event::new(2.0, DVec3::new(size.x / 2.0, -1.0, 0.8)),
        u: ProperVelocity::ZERO,
    };
    let effects = Effects::default();
    let vertices = n * shape.vertices.len();
    let contracted: Vec<ContractedShape> = (0..n)
        .map(|i| ContractedShape::of(b.worldline(i)))
        .collect();
    let work = |puck: usize, e: &mut Vec<Emission>, s: &mut Vec<Seen>| {
        view::emissions_with_shape(
            &contracted[puck],
            puck,
            b.worldline(puck),
            &shape.vertices,
            &eye,
            &effects,
            Method::Exact,
            e,
        );
        view::seen(&eye, b.c(), &effects, e, s);
        s.len()
    };
    let mut kept: Vec<(Vec<Emission>, Vec<Seen>)> =
        (0..n).map(|_| (Vec::new(), Vec::new())).collect();
    for t in [1, 2] {
        if threads.is_some_and(|k| k != t) {
            continue;
        }
        let Ok(pool) = rayon::ThreadPoolBuilder::new().num_threads(t).build() else {
            eprintln!("no thread pool of {t}");
            continue;
        };
        pool.install(|| {
            let (mut per_thread, mut per_body) = (f64::INFINITY, f64::INFINITY);
            let cpu0 = cpu_seconds();
            for _ in 0..reps {
                let start = Instant::now();
                let total: usize = (0..n)
                    .into_par_iter()
                    .map_init(
                        || (Vec::new(), Vec::new()),
                        |(e, s), puck| work(puck, e, s),
                    )
                    .sum();
                assert_eq!(total, vertices);
                per_thread = per_thread.min(start.elapsed().as_secs_f64());
            }
            let cpu = cpu_seconds() - cpu0;
            for _ in 0..reps {
                let start = Instant::now();
                let total: usize = kept
                    .par_iter_mut()
                    .enumerate()
                    .map(|(puck, (e, s))| work(puck, e, s))
                    .sum();
                assert_eq!(total, vertices);
                per_body = per_body.min(start.elapsed().as_secs_f64());
            }
            println!(
                "{vertices} vertices, {t} thread(s), best of {reps}: arrays per thread {:.3e} solves/s \
                 ({:.1} ns/vertex, {:.1} CPU ns/vertex); arrays per body {:.3e} solves/s",
                vertices as f64 / per_thread,
                per_thread * 1e9 / vertices as f64,
                cpu * 1e9 / (vertices * reps) as f64,
                vertices as f64 / per_body,
            );
        });
    }
}

/// This process's user + system CPU time, s (Linux; 0 elsewhere).
fn cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    // Fields after the command name (which is in parentheses).
    let Some(rest) = stat.rsplit(')').next() else {
        return 0.0;
    };
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |k: usize| f.get(k).and_then(|s| s.parse::<f64>().ok()).unwrap_or(0.0);
    // utime and stime are fields 14 and 15 of the file, 12 and 13 here.
    (ticks(11) + ticks(12)) / 100.0
}
