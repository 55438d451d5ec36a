//! `lightcone diagram SCENE --at T [--observer NAME] [--frame PUCK]
//! [--axis x|y] [--size WxH] -o out.png`: the space-time diagram of a scene
//! at board time T (see [`lightcone_render::diagram`]).

use std::path::Path;
use std::process::ExitCode;

use lightcone_engine::physics::Billiard;
use lightcone_engine::scene;

use lightcone_render::diagram;

/// The index of puck `name` in `scene` (given as option `flag`, e.g.
/// `--frame`), or a message listing the names.
pub fn puck_index(
    scene: &lightcone_engine::scene::Scene,
    path: &Path,
    flag: &str,
    name: &str,
) -> Result<usize, String> {
    scene
        .pucks
        .iter()
        .position(|p| p.name == name)
        .ok_or_else(|| {
            let names: Vec<&str> = scene.pucks.iter().map(|p| p.name.as_str()).collect();
            format!(
                "{}: {flag} {name:?}: no such puck; the pucks are {}",
                path.display(),
                names.join(", ")
            )
        })
}

/// Draws and writes the PNG; prints each puck's emission event (where the
/// eye's past light cone meets its worldline), and with a frame the line of
/// simultaneity drawn.
pub fn run(
    path: &Path,
    at: f64,
    observer: Option<&str>,
    frame: Option<&str>,
    axis: diagram::Axis,
    out: &Path,
    size: &str,
) -> ExitCode {
    let fail = |msg: String| {
        crate::errln!("{msg}");
        ExitCode::FAILURE
    };
    if !at.is_finite() {
        return fail(format!("--at {at}: give a finite board time in seconds"));
    }
    let (width, height) = match super::render::parse_sides(size) {
        Ok(s) => s,
        Err(e) => return fail(e),
    };
    if let Err(e) = crate::output::not_the_input(out, path) {
        return fail(e);
    }
    let scene = match scene::load(path) {
        Ok(s) => s,
        Err(e) => return fail(e.to_string()),
    };
    let index = match super::names::observer_index(&scene, path, observer) {
        Ok(i) => i,
        Err(e) => return fail(e),
    };
    let frame = match frame
        .map(|f| puck_index(&scene, path, "--frame", f))
        .transpose()
    {
        Ok(f) => f,
        Err(e) => return fail(e),
    };
    let mut billiard = Billiard::from_scene(&scene);
    billiard.advance_to(at);
    let drawn = diagram::draw_with(
        &scene,
        &billiard,
        index,
        at,
        (width, height),
        diagram::Options { axis, frame },
    );
    if let Err(e) = drawn.image.save_png(out) {
        return fail(e);
    }
    let axis_name = axis.name();
    for (p, e) in scene.pucks.iter().zip(&drawn.emissions) {
        println!(
            "{}: seen from t = {:.6} s at {axis_name} = {:.6} m",
            p.name,
            e.t,
            axis.of(e.position)
        );
    }
    if let Some(sim) = drawn.simultaneity {
        println!(
            "{}'s now: through t = {:.6} s, {axis_name} = {:.6} m, slope dt/d{axis_name} = {:.6} s/m",
            scene.pucks[sim.puck].name,
            sim.event.t,
            axis.of(sim.event.position),
            sim.slope
        );
    }
    ExitCode::SUCCESS
}
