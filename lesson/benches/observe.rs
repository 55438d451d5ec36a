//! Criterion benchmark of one `observe` of a running simulation (Python's
//! `lightcone.Simulation.observe`, the browser stand-in's): through the
//! simulation's own persistent view (`SimulationCore::observe`, now), and
//! the way it was done before (a new ECS world built for the scene, the
//! billiard cloned into it, one frame run: `lightcone_render::observe::
//! report`, which a lesson's `world.observe` still takes).
//! `cargo bench -p lightcone-lesson --bench observe`.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use lightcone_lesson::simulation::SimulationCore;

fn observe(c: &mut Criterion) {
    let mut group = c.benchmark_group("observe");
    for name in ["paper_carom.toml", "ten_pucks.toml"] {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../assets/scenes")
            .join(name);
        let scene = lightcone_engine::scene::load(&path).unwrap();
        let mut core = SimulationCore::new(&scene, None).unwrap();
        core.advance_to(10.0);
        let fx = scene.effects;
        let mut k = 0u32;
        // Times that differ call to call, as a notebook's loop asks them.
        let mut at = || {
            k = (k + 1) % 100;
            5.0 + 0.05 * f64::from(k)
        };
        group.bench_function(format!("{name}/persistent_view"), |b| {
            b.iter(|| black_box(core.observe(None, at(), false, fx).unwrap()))
        });
        group.bench_function(format!("{name}/new_world_per_call"), |b| {
            b.iter(|| {
                black_box(
                    lightcone_render::observe::report(&scene, core.billiard(), 0, at(), fx, false)
                        .unwrap(),
                )
            })
        });
    }
    group.finish();
}

criterion_group!(benches, observe);
criterion_main!(benches);
