//! `lightcone bench render [--quick]`: headless frames per second, split
//! into the CPU's part (physics, optics, building the triangle list) and the
//! GPU's (drawing and reading the image back), for the paper's scene and a
//! large one.

use std::process::ExitCode;
use std::time::Instant;

use glam::{DVec2, DVec3};
use lightcone_engine::scene::{Color, Effects, ObserverSpec, PuckSpec, Scene, TableSpec};
use lightcone_engine::spacetime::ProperVelocity;

use lightcone_render::frame::{self, ViewMeshes};
use lightcone_render::{gpu, headless};

/// A large scene: `n` pucks on a grid with assorted velocities.
fn large(n: usize) -> Scene {
    let per_row = (n as f64).sqrt().ceil() as usize;
    let size = DVec2::new(0.2 * per_row as f64 + 0.4, 0.2 * per_row as f64 + 0.4);
    Scene {
        title: format!("{n} pucks"),
        description: String::new(),
        c: size.x / 2.0,
        table: TableSpec::frictionless(size, 1.0),
        restitution: 1.0,
        effects: Effects::default(),
        optics: Default::default(),
        before_start: Default::default(),
        pucks: (0..n)
            .map(|i| {
                let phi = i as f64 * 2.399;
                PuckSpec {
                    name: format!("p{i}"),
                    position: DVec2::new(
                        0.3 + 0.2 * (i % per_row) as f64,
                        0.3 + 0.2 * (i / per_row) as f64,
                    ),
                    u: ProperVelocity::try_from_beta(DVec3::new(phi.cos(), phi.sin(), 0.0) * 0.7)
                        .unwrap_or(ProperVelocity::ZERO),
                    radius: 0.0305,
                    height: 0.02,
                    mass: 0.21,
                    color: Color::default_for(i),
                }
            })
            .collect(),
        observers: vec![ObserverSpec {
            name: "eye".into(),
            position: DVec3::new(size.x / 2.0, -1.5, 2.0),
            look_at: Some(DVec3::new(size.x / 2.0, size.y / 2.0, 0.0)),
            u: ProperVelocity::ZERO,
        }],
    }
}

/// Runs the benchmark.
pub fn run(quick: bool) -> ExitCode {
    let gpu = match gpu::headless() {
        Ok(g) => g,
        Err(e) => {
            crate::errln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let paper = match crate::assets::shipped_at("assets/scenes/paper_carom.toml") {
        Ok(s) => s,
        Err(e) => {
            crate::errln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    crate::sayln!(
        "### Headless frame time, 1280×720, adapter: {}\n\n\
         | scene | pucks | triangles | CPU: physics + optics + triangles (ms) | GPU: draw + read back (ms) | frames/s |\n\
         | --- | --- | --- | --- | --- | --- |",
        gpu.adapter
    );
    let frames = if quick { 3 } else { 30 };
    let progress = crate::progress::steps(2 * frames as u64, "bench render");
    for scene in [paper, large(if quick { 100 } else { 1100 })] {
        progress.step(&scene.title);
        let (mut sim, view) =
            frame::scene_view(&scene, 0, 0.0, frame::ViewKind::Seen, 1280.0 / 720.0);
        let meshes = ViewMeshes::new(&mut sim);
        let mut vertices = Vec::new();
        let (mut cpu, mut gpu_time) = (0.0, 0.0);
        let mut target = headless::Offscreen::new(&gpu, 1280, 720);
        for f in 1..=frames {
            let t = f as f64 / 60.0;
            let start = Instant::now();
            sim.advance_to(t);
            let (Some(apparent), Some(camera)) = (sim.apparent(view), sim.camera(view)) else {
                crate::errln!("the benchmarked view is gone");
                return ExitCode::FAILURE;
            };
            frame::build_view(apparent, &meshes, &mut vertices);
            let camera = frame::Camera::from(camera);
            let mid = Instant::now();
            if let Err(e) = target.draw(&gpu, &vertices, &camera) {
                crate::errln!("{e}");
                return ExitCode::FAILURE;
            }
            cpu += (mid - start).as_secs_f64();
            gpu_time += mid.elapsed().as_secs_f64();
            progress.inc();
        }
        let n = f64::from(frames);
        progress.suspend(|| {
            crate::sayln!(
                "| {} | {} | {} | {:.2} | {:.2} | {:.1} |",
                scene.title,
                scene.pucks.len(),
                vertices.len() / 3,
                cpu / n * 1e3,
                gpu_time / n * 1e3,
                n / (cpu + gpu_time)
            )
        });
    }
    progress.finish();
    views_per_frame(&gpu, quick)
}

/// Frame time per number of views shown at once (1, 2, 4): the paper's
/// scene and 1 000 pucks, each view the scene's observer with the scene's
/// effects, side by side in a 1280×720 window (each view drawn into its
/// share of the width). CPU: one run of the frame schedule for all views,
/// then each view's triangle list; GPU: drawing and reading back each.
fn views_per_frame(gpu: &gpu::Gpu, quick: bool) -> ExitCode {
    let paper = match crate::assets::shipped_at("assets/scenes/paper_carom.toml") {
        Ok(s) => s,
        Err(e) => {
            crate::errln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    crate::sayln!(
        "\n### Frame time per number of views, 1280×720 split side by side\n\n\
         | scene | views | CPU: schedule + triangles (ms) | GPU: draw + read back (ms) | frames/s |\n\
         | --- | --- | --- | --- | --- |"
    );
    let frames = if quick { 3 } else { 20 };
    for scene in [paper, large(if quick { 100 } else { 1000 })] {
        for n in [1usize, 2, 4] {
            let aspect = 1280.0 / (720.0 * n as f64);
            let (mut sim, first) = frame::scene_view(&scene, 0, 0.0, frame::ViewKind::Seen, aspect);
            let observer = sim.observer_of(first);
            let mut views = vec![first];
            for k in 1..n {
                let (Some(o), Some(framing)) = (observer, sim.framing(first)) else {
                    break;
                };
                views.push(sim.add_view(
                    &format!("view {k}"),
                    o,
                    scene.effects,
                    framing,
                    lightcone_engine::ecs::Vantage::OnWorldline,
                ));
            }
            let meshes = ViewMeshes::new(&mut sim);
            let width = (1280 / n as u32).max(1);
            let mut target = headless::Offscreen::new(gpu, width, 720);
            let mut vertices = Vec::new();
            let (mut cpu, mut gpu_time) = (0.0, 0.0);
            for f in 1..=frames {
                let t = f as f64 / 60.0;
                let start = Instant::now();
                sim.advance_to(t);
                let mut lists = Vec::with_capacity(n);
                for &v in &views {
                    let (Some(apparent), Some(camera)) = (sim.apparent(v), sim.camera(v)) else {
                        crate::errln!("a benchmarked view is gone");
                        return ExitCode::FAILURE;
                    };
                    frame::build_view(apparent, &meshes, &mut vertices);
                    lists.push((vertices.clone(), frame::Camera::from(camera)));
                }
                let mid = Instant::now();
                for (list, camera) in &lists {
                    if let Err(e) = target.draw(gpu, list, camera) {
                        crate::errln!("{e}");
                        return ExitCode::FAILURE;
                    }
                }
                cpu += (mid - start).as_secs_f64();
                gpu_time += mid.elapsed().as_secs_f64();
            }
            let k = f64::from(frames);
            crate::sayln!(
                "| {} | {n} | {:.2} | {:.2} | {:.1} |",
                scene.title,
                cpu / k * 1e3,
                gpu_time / k * 1e3,
                k / (cpu + gpu_time)
            );
        }
    }
    ExitCode::SUCCESS
}
