//! `lightcone simulate SCENE --until T [--out FILE]`: run the physics
//! headless and write every collision, then the final state, as JSON lines.

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use lightcone_engine::physics::Billiard;
use lightcone_engine::report::{CollisionLine, StateLine};
use lightcone_engine::scene;

/// Runs `scene` to board time `until` and writes the JSON lines to `out`
/// (stdout when `None`). Warnings (e.g. a Zeno sequence merged) go to stderr.
pub fn run(scene_path: &Path, until: f64, out: Option<&PathBuf>) -> ExitCode {
    if !until.is_finite() || until < 0.0 {
        eprintln!("--until {until}: give a finite board time ≥ 0 in seconds");
        return ExitCode::FAILURE;
    }
    let scene = match scene::load(scene_path) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let mut billiard = Billiard::from_scene(&scene);
    billiard.advance_to(until);
    for w in billiard.warnings() {
        eprintln!("{}: warning: {w}", scene_path.display());
    }
    let result = match out {
        Some(path) => match std::fs::File::create(path) {
            Ok(f) => write_lines(&billiard, until, BufWriter::new(f)),
            Err(e) => {
                eprintln!("{}: cannot create: {e}", path.display());
                return ExitCode::FAILURE;
            }
        },
        None => write_lines(&billiard, until, BufWriter::new(std::io::stdout().lock())),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("cannot write the output: {e}");
            ExitCode::FAILURE
        }
    }
}

fn write_lines(billiard: &Billiard, until: f64, mut w: impl Write) -> std::io::Result<()> {
    for c in billiard.collisions() {
        serde_json::to_writer(&mut w, &CollisionLine::new(billiard, c))?;
        w.write_all(b"\n")?;
    }
    serde_json::to_writer(&mut w, &StateLine::new(billiard, until))?;
    w.write_all(b"\n")?;
    w.flush()
}
