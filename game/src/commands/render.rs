//! `lightcone render SCENE --at T --observer NAME -o out.png [--size WxH]
//! [--view seen|truth]`: a headless image of what an observer sees.

use std::path::Path;
use std::process::ExitCode;

use lightcone_engine::scene;

use lightcone_render::frame::ViewKind;
use lightcone_render::{gpu, headless};

/// Parses `WxH`.
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("--size {s}: give WIDTHxHEIGHT, e.g. 1280x720"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<u32>()
            .ok()
            .filter(|n| (1..=16384).contains(n))
    };
    match (parse(w), parse(h)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => Err(format!(
            "--size {s}: width and height must be whole numbers from 1 to 16384"
        )),
    }
}

/// Renders and writes the PNG.
pub fn run(
    path: &Path,
    at: f64,
    observer: Option<&str>,
    out: &Path,
    size: &str,
    view: ViewKind,
) -> ExitCode {
    let fail = |msg: String| {
        crate::errln!("{msg}");
        ExitCode::FAILURE
    };
    if !at.is_finite() {
        return fail(format!("--at {at}: give a finite board time in seconds"));
    }
    let (width, height) = match parse_size(size) {
        Ok(s) => s,
        Err(e) => return fail(e),
    };
    let scene = match scene::load(path) {
        Ok(s) => s,
        Err(e) => return fail(e.to_string()),
    };
    let index = match observer_index(&scene, path, observer) {
        Ok(i) => i,
        Err(e) => return fail(e),
    };
    let gpu = match gpu::headless() {
        Ok(g) => g,
        Err(e) => return fail(e),
    };
    match headless::render_scene(&gpu, &scene, at, index, view, width, height)
        .and_then(|img| img.save_png(out))
    {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => fail(e),
    }
}

/// Index of the observer `name` in `scene` (the first when `None`), or a
/// message naming the file and the observers it has.
pub fn observer_index(
    scene: &lightcone_engine::scene::Scene,
    path: &Path,
    name: Option<&str>,
) -> Result<usize, String> {
    let Some(name) = name else {
        return Ok(0);
    };
    scene
        .observers
        .iter()
        .position(|o| o.name == name)
        .ok_or_else(|| {
            let names: Vec<_> = scene.observers.iter().map(|o| o.name.as_str()).collect();
            format!(
                "{}: no observer named \"{name}\"; the scene has: {}",
                path.display(),
                names.join(", ")
            )
        })
}
