//! `lightcone diagram SCENE --at T [--observer NAME] [--size WxH] -o out.png`:
//! the space-time diagram of a scene at board time T (see
//! [`lightcone_render::diagram`]).

use std::path::Path;
use std::process::ExitCode;

use lightcone_engine::physics::Billiard;
use lightcone_engine::scene;

use lightcone_render::diagram;

/// Draws and writes the PNG; prints each puck's emission event (where the
/// eye's past light cone meets its worldline).
pub fn run(path: &Path, at: f64, observer: Option<&str>, out: &Path, size: &str) -> ExitCode {
    let fail = |msg: String| {
        eprintln!("{msg}");
        ExitCode::FAILURE
    };
    if !at.is_finite() {
        return fail(format!("--at {at}: give a finite board time in seconds"));
    }
    let (width, height) = match super::render::parse_size(size) {
        Ok(s) => s,
        Err(e) => return fail(e),
    };
    let scene = match scene::load(path) {
        Ok(s) => s,
        Err(e) => return fail(e.to_string()),
    };
    let index = match super::render::observer_index(&scene, path, observer) {
        Ok(i) => i,
        Err(e) => return fail(e),
    };
    let mut billiard = Billiard::from_scene(&scene);
    billiard.advance_to(at);
    let drawn = diagram::draw(&scene, &billiard, index, at, width, height);
    if let Err(e) = drawn.image.save_png(out) {
        return fail(e);
    }
    for (p, e) in scene.pucks.iter().zip(&drawn.emissions) {
        println!(
            "{}: seen from t = {:.6} s at x = {:.6} m",
            p.name, e.t, e.position.x
        );
    }
    ExitCode::SUCCESS
}
