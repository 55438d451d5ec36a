//! What a frame of the schedule costs (BENCHMARKS.md, "What each effect
//! costs" and "Frame time per number of views"): the real pipeline
//! ([`Simulation`], the one every view runs) on a scene of pucks in lanes,
//! timed per effect and per number of views. Used by `lightcone bench
//! optics` and `cargo run --release -p lightcone-engine --example
//! pipeline_bench`.

use std::time::Instant;

use glam::{DVec2, DVec3};

use super::{Simulation, Vantage};
use crate::scene::{Color, Effect, Effects, ObserverSpec, PuckSpec, Scene, TableSpec};
use crate::spacetime::ProperVelocity;
use crate::worldline::mesh::{self, PUCK_SEGMENTS};

/// `n` pucks in lanes, 40 to a row 25 cm apart, on a table four times the
/// paper's, made longer (along y) when the rows need it (from 841
/// pucks), a moving eye.
#[must_use]
pub fn lanes(n: usize) -> Scene {
    let per_row = 40;
    let rows = n.div_ceil(per_row);
    let size = DVec2::new(2.84 * 4.0, (1.42 * 4.0f64).max(0.4 + 0.25 * rows as f64));
    let pucks = (0..n)
        .map(|i| PuckSpec {
            name: format!("p{i}"),
            position: DVec2::new(
                0.2 + 0.25 * (i % per_row) as f64,
                0.2 + 0.25 * (i / per_row) as f64,
            ),
            u: ProperVelocity::try_from_beta(DVec3::new(
                0.5 + 0.4 * ((i * 7 % 10) as f64 / 10.0),
                0.3,
                0.0,
            ))
            .unwrap_or(ProperVelocity::ZERO),
            radius: 0.0305,
            height: 0.02,
            mass: 0.21,
            color: Color::default_for(i),
        })
        .collect();
    Scene {
        title: "lanes".into(),
        description: String::new(),
        c: size.x / 2.0,
        table: TableSpec::frictionless(size, 1.0),
        restitution: 1.0,
        effects: Effects::NONE,
        optics: Default::default(),
        before_start: Default::default(),
        pucks,
        observers: vec![ObserverSpec {
            name: "eye".into(),
            position: DVec3::new(size.x / 2.0, -1.0, 1.0),
            look_at: Some(DVec3::new(size.x / 2.0, size.y / 2.0, 0.0)),
            u: ProperVelocity::try_from_beta(DVec3::new(0.3, 0.0, 0.0))
                .unwrap_or(ProperVelocity::ZERO),
        }],
    }
}

/// Milliseconds per frame of `sim` at 60 fps: the best of five runs of
/// `frames / 5` frames each (the machine is shared; the best run is the
/// one least disturbed).
pub fn ms_per_frame(sim: &mut Simulation, frames: u32) -> f64 {
    sim.advance_to(1.0 / 60.0); // warm-up
    let per_run = (frames / 5).max(1);
    let mut f = 1;
    let mut best = f64::INFINITY;
    for _ in 0..5 {
        let start = Instant::now();
        for _ in 0..per_run {
            f += 1;
            sim.advance_to(f64::from(f) / 60.0);
        }
        best = best.min(start.elapsed().as_secs_f64() * 1e3 / f64::from(per_run));
    }
    best
}

/// The Markdown table of what each effect costs: the lanes scene of `n`
/// pucks with each effect alone, none, and all, `frames` frames each.
#[must_use]
pub fn effect_costs(n: usize, frames: u32) -> String {
    let vertices = n * mesh::puck(0.0305, 0.02, PUCK_SEGMENTS).vertices.len();
    let mut out = format!(
        "### What each effect costs: one frame of the schedule, {n} pucks \
         (48-segment meshes, {vertices} vertices), one view of a moving observer\n\n\
         | effects on | ms per frame |\n| --- | --- |\n"
    );
    let mut configs: Vec<(String, Effects)> = vec![("none".into(), Effects::NONE)];
    for e in Effect::ALL {
        let mut fx = Effects::NONE;
        fx.set(e, true);
        configs.push((e.key().into(), fx));
    }
    let mut all = Effects::NONE;
    for e in Effect::ALL {
        all.set(e, true);
    }
    configs.push(("all".into(), all));
    for (name, fx) in configs {
        let mut s = lanes(n);
        s.effects = fx;
        let mut sim = Simulation::new(&s);
        out += &format!("| {name} | {:.3} |\n", ms_per_frame(&mut sim, frames));
    }
    out
}

/// `sim` with `views` views of its first observer: the scene's view, then
/// the board-frame truth, then copies of the scene's.
#[must_use]
pub fn with_views(scene: &Scene, views: usize) -> Simulation {
    let mut sim = Simulation::new(scene);
    let first = sim.views()[0];
    let observer = sim.observer_of(first).expect("the scene's view");
    let framing = sim.framing(first).unwrap_or_default();
    let truth = Effects {
        contraction: true,
        ..Effects::NONE
    };
    for k in 1..views {
        let (name, fx) = if k % 2 == 1 {
            (format!("truth {k}"), truth)
        } else {
            (format!("seen {k}"), scene.effects)
        };
        sim.add_view(&name, observer, fx, framing, Vantage::OnWorldline);
    }
    sim
}

/// The Markdown table of frame time per number of views (1, 2, 4) for
/// each named scene, `frames` frames each.
#[must_use]
pub fn view_counts(scenes: &[(&str, Scene)], frames: u32) -> String {
    let mut out = String::from(
        "### Frame time per number of views (the scene's effects, then truth, seen, truth)\n\n\
         | scene | vertices per view | 1 view, ms | 2 views, ms | 4 views, ms |\n\
         | --- | --- | --- | --- | --- |\n",
    );
    for (name, scene) in scenes {
        let vertices: usize = scene
            .pucks
            .iter()
            .map(|_| mesh::puck(0.0305, 0.02, PUCK_SEGMENTS).vertices.len())
            .sum();
        let times: Vec<String> = [1, 2, 4]
            .iter()
            .map(|&v| format!("{:.3}", ms_per_frame(&mut with_views(scene, v), frames)))
            .collect();
        out += &format!("| {name} | {vertices} | {} |\n", times.join(" | "));
    }
    out
}
