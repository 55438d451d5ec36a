//! `lightcone observe SCENE --at T --observer NAME [--vertices] [--effects LIST]`:
//! what an observer sees at board time T, as one JSON object.

use std::path::Path;
use std::process::ExitCode;

use lightcone_engine::scene::{self, Effect, Effects};
use lightcone_render::observe::report_at;

/// Parses `--effects`: `scene` (as the scene says), `all`, `none`, or a
/// comma-separated list of effect keys to turn on (the others off).
pub fn parse_effects(spec: &str, scene: Effects) -> Result<Effects, String> {
    match spec {
        "scene" => return Ok(scene),
        "all" => {
            let mut e = Effects::NONE;
            for k in Effect::ALL {
                e.set(k, true);
            }
            return Ok(e);
        }
        "none" => return Ok(Effects::NONE),
        _ => {}
    }
    if spec.split(',').all(|k| k.trim().is_empty()) {
        return Err(format!(
            "--effects `{spec}`: give effect names separated by commas, or scene, all, none"
        ));
    }
    let mut e = Effects::NONE;
    for key in spec.split(',').map(str::trim).filter(|k| !k.is_empty()) {
        let effect = Effect::ALL.iter().find(|x| x.key() == key).ok_or_else(|| {
            let known: Vec<_> = Effect::ALL.iter().map(|x| x.key()).collect();
            format!(
                "--effects: unknown effect `{key}`; known: scene, all, none, {}",
                known.join(", ")
            )
        })?;
        e.set(*effect, true);
    }
    Ok(e)
}

/// Prints what `observer` (default: the scene's first) sees at `at`.
pub fn run_named(
    path: &Path,
    at: f64,
    observer: Option<&str>,
    vertices: bool,
    effects: &str,
) -> ExitCode {
    match observer {
        Some(name) => run(path, at, name, vertices, effects),
        None => match scene::load(path) {
            Ok(s) => run(path, at, &s.observers[0].name, vertices, effects),
            Err(e) => {
                crate::errln!("{e}");
                ExitCode::FAILURE
            }
        },
    }
}

/// Prints what `observer` sees at board time `at`.
pub fn run(path: &Path, at: f64, observer: &str, vertices: bool, effects: &str) -> ExitCode {
    if !at.is_finite() {
        crate::errln!("--at {at}: give a finite board time in seconds");
        return ExitCode::FAILURE;
    }
    let scene = match scene::load(path) {
        Ok(s) => s,
        Err(e) => {
            crate::errln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let effects = match parse_effects(effects, scene.effects) {
        Ok(e) => e,
        Err(e) => {
            crate::errln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let index = match super::names::observer_index(&scene, path, Some(observer)) {
        Ok(i) => i,
        Err(e) => {
            crate::errln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let Some(report) = report_at(&scene, index, at, effects, vertices) else {
        crate::errln!("{}: no observer number {index}", path.display());
        return ExitCode::FAILURE;
    };
    match serde_json::to_string(&report) {
        Ok(s) => match crate::outln!("{s}") {
            Ok(()) => ExitCode::SUCCESS,
            Err(stop) => stop.exit(),
        },
        Err(e) => {
            crate::errln!("cannot write the output: {e}");
            ExitCode::FAILURE
        }
    }
}
