//! Exact emission solves per second, the table "Exact emission solves per
//! second" of BENCHMARKS.md (`lightcone bench optics` prints the same, from
//! the same workload, [`lightcone_engine::optics::solve_rate`]):
//! `cargo run --release -p lightcone-engine --example optics_rate -- [SEGMENTS] [REPS] [THREADS] [MU_G]`
//!
//! 1 000 pucks of a gas run for 2 s, a puck mesh of `SEGMENTS` around
//! (default 512: 1 024 000 vertices), every vertex's emission event and
//! apparent position (aberration on), best of `REPS` runs (default 10),
//! on `THREADS` threads (1 or 2; 0 or none for both); with `MU_G` (m/s²)
//! the gas runs on a cloth of that sliding friction, so every worldline
//! brakes ([`SolveRate::gas_on_cloth`]). Two ways to keep the
//! output: each thread's arrays used for one body after another (in
//! cache), and one pair of arrays per body kept from frame to frame, as
//! the frame pipeline keeps them.

use std::time::Instant;

use lightcone_engine::optics::solve_rate::{BodyOutput, SolveRate};

fn main() {
    let mut args = std::env::args().skip(1);
    let segments: u32 = args.next().and_then(|s| s.parse().ok()).unwrap_or(512);
    let reps: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(10);
    let threads: Option<usize> = args.next().and_then(|s| s.parse().ok());
    let mu_g: f64 = args.next().and_then(|s| s.parse().ok()).unwrap_or(0.0);
    let build = Instant::now();
    let work = SolveRate::gas_on_cloth(1000, segments, mu_g);
    eprintln!("gas built in {:.1} s", build.elapsed().as_secs_f64());
    let vertices = work.vertices();
    let mut kept = vec![BodyOutput::default(); work.pucks()];
    // Best of `reps` runs of `run` (which returns the vertices solved), s.
    let best = |run: &mut dyn FnMut() -> usize| {
        (0..reps)
            .map(|_| {
                let start = Instant::now();
                assert_eq!(run(), vertices);
                start.elapsed().as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min)
    };
    for t in [1, 2] {
        if threads.is_some_and(|k| k != 0 && k != t) {
            continue;
        }
        let Ok(pool) = rayon::ThreadPoolBuilder::new().num_threads(t).build() else {
            eprintln!("no thread pool of {t}");
            continue;
        };
        let (per_thread, per_body) = pool.install(|| {
            (
                best(&mut || work.per_thread()),
                best(&mut || work.per_body(&mut kept)),
            )
        });
        println!(
            "{vertices} vertices, {t} thread(s), best of {reps}: arrays per thread {:.3e} solves/s \
             ({:.1} ns/vertex); arrays per body {:.3e} solves/s",
            vertices as f64 / per_thread,
            per_thread * 1e9 / vertices as f64,
            vertices as f64 / per_body,
        );
    }
}
