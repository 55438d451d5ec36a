//! `lightcone cave SCENE --config CAVE.toml --out-dir DIR`: every wall of a
//! CAVE, both eyes, rendered headless to PNG.

use std::path::Path;
use std::process::ExitCode;

use glam::{DQuat, DVec3};
use lightcone_engine::scene;

use crate::cave::{self, DEFAULT_HEAD};
use crate::model::GameState;

/// Parses `x,y,z`.
pub fn parse_head(text: &str) -> Result<DVec3, String> {
    let v: Vec<f64> = text
        .split(',')
        .map(|p| p.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("--head {text:?}: give x,y,z in tracker metres"))?;
    match v.as_slice() {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok(DVec3::new(*x, *y, *z)),
        _ => Err(format!("--head {text:?}: give three finite numbers x,y,z")),
    }
}

/// Renders the walls at board time `at` for a head at `head` (tracker space,
/// facing the front), writing `DIR/<wall>_<left|right>.png`. `scene_path`
/// `None` is the built-in default scene, `config` `None` the built-in
/// `assets/cave.toml`.
pub fn run(
    scene_path: Option<&Path>,
    config: Option<&Path>,
    out_dir: &Path,
    at: f64,
    head: Option<&str>,
    scale: f64,
) -> ExitCode {
    let fail = |e: String| {
        crate::errln!("{e}");
        ExitCode::FAILURE
    };
    if !(at.is_finite() && at >= 0.0) {
        return fail(format!("--at {at}: give a board time ≥ 0"));
    }
    if !(scale.is_finite() && scale > 0.0 && scale <= 4.0) {
        return fail(format!("--scale {scale}: give a number in (0, 4]"));
    }
    let head = match head.map(parse_head).transpose() {
        Ok(h) => h.unwrap_or(DEFAULT_HEAD),
        Err(e) => return fail(e),
    };
    let loaded = match scene_path {
        Some(path) => scene::load(path),
        None => crate::assets::default_scene(),
    };
    let scene = match loaded {
        Ok(s) => s,
        Err(e) => return fail(e.to_string()),
    };
    let config = match config.map_or_else(crate::assets::default_cave, cave::load) {
        Ok(c) => c,
        Err(e) => return fail(e),
    };
    let mut game = GameState::new(scene);
    {
        // The physics to `at`, with a bar (the walls are quick after it).
        let progress = crate::progress::bar(at, "board s");
        while !game.physics_mut().step_until(at, 16_384) {
            progress.set_position_f64(game.physics().time());
            if crate::interrupt::interrupted() {
                progress.finish();
                return crate::interrupt::exit_code("cave stopped");
            }
        }
        progress.finish();
    }
    game.step(at);
    let gpu = match lightcone_render::gpu::headless() {
        Ok(g) => g,
        Err(e) => return fail(e),
    };
    if let Err(e) = std::fs::create_dir_all(out_dir) {
        return fail(format!("{}: {e}", out_dir.display()));
    }
    let images = match cave::render_walls(&gpu, &mut game, &config, (head, DQuat::IDENTITY), scale)
    {
        Ok(i) => i,
        Err(e) => return fail(e),
    };
    let progress = crate::progress::steps(images.len() as u64, "cave: writing");
    for (wall, side, image) in images {
        let path = out_dir.join(format!("{wall}_{}.png", side.name()));
        progress.step(&path.display().to_string());
        if let Err(e) = image.save_png(&path) {
            progress.finish();
            return fail(e);
        }
        progress.inc();
        if let Err(stop) = progress.suspend(|| crate::outln!("{}", path.display())) {
            return stop.exit();
        }
    }
    ExitCode::SUCCESS
}
