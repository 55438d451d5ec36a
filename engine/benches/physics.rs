//! Criterion benchmarks of the physics: one 60 fps frame of the paper's
//! scenes, and a slice of a dense gas. `cargo bench -p lightcone-engine`.
//! (`lightcone bench physics` prints the tables of BENCHMARKS.md.)

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use lightcone_engine::physics::Billiard;
use lightcone_engine::physics::gas::dense_box;
use lightcone_engine::scene;

fn scene_frames(c: &mut Criterion) {
    for name in ["paper_carom", "ten_pucks"] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../assets/scenes")
            .join(format!("{name}.toml"));
        let s = match scene::load(&path) {
            Ok(s) => s,
            Err(e) => panic!("{e}"),
        };
        let mut billiard = Billiard::from_scene(&s);
        let mut frame = 0u64;
        c.bench_function(&format!("frame_60fps/{name}"), |b| {
            b.iter(|| {
                frame += 1;
                if frame > 60 * 600 {
                    billiard = Billiard::from_scene(&s);
                    frame = 1;
                }
                billiard.advance_to(black_box(frame as f64 / 60.0));
            })
        });
    }
}

fn gas(c: &mut Criterion) {
    for n in [100usize, 1000] {
        let mut g = dense_box(n, 0.0305, 3.0 * 0.0305, 0.8, 1.42, 7);
        g.set_recording(false);
        g.set_keep_history(false);
        let mut t = 0.0;
        c.bench_function(&format!("gas_1ms/{n}"), |b| {
            b.iter(|| {
                t += 1e-3;
                g.advance_to(black_box(t));
            })
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30);
    targets = scene_frames, gas
}
criterion_main!(benches);
