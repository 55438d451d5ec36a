//! `lightcone check SCENE...`: validate scenes and summarise them.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use lightcone_engine::scene::{self, Effect, Scene, number};

use crate::output;

/// Checks every scene, printing a summary of each good one to stdout and
/// every error (file:line:column: field: message) to stderr. Fails if any
/// scene is bad. With no paths, checks the built-in default scene.
pub fn run(paths: &[PathBuf]) -> ExitCode {
    if paths.is_empty() {
        let name = Path::new(crate::assets::DEFAULT_SCENE_NAME);
        return match crate::assets::default_scene() {
            Ok(s) => match output::print(&summary(name, &s)) {
                Ok(()) => ExitCode::SUCCESS,
                Err(stop) => stop.exit(),
            },
            Err(errors) => {
                crate::errln!("{errors}");
                ExitCode::FAILURE
            }
        };
    }
    let mut bad = 0;
    for path in paths {
        match scene::load(path) {
            Ok(s) => {
                if let Err(stop) = output::print(&summary(path, &s)) {
                    // A closed stdout still fails a run that found bad scenes.
                    let code = stop.exit();
                    return if bad > 0 { ExitCode::FAILURE } else { code };
                }
            }
            Err(errors) => {
                bad += 1;
                crate::errln!("{errors}");
            }
        }
    }
    if bad > 0 {
        crate::errln!("{bad} of {} scene(s) have errors", paths.len());
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// A few lines that say what a scene holds: speeds as β and γ, effects.
pub fn summary(path: &Path, s: &Scene) -> String {
    let mut out = String::new();
    let on: Vec<_> = Effect::ALL
        .iter()
        .filter(|e| s.effects.is_on(**e))
        .map(|e| e.key())
        .collect();
    let off: Vec<_> = Effect::ALL
        .iter()
        .filter(|e| !s.effects.is_on(**e))
        .map(|e| e.key())
        .collect();
    let _ = writeln!(out, "{}: ok: {}", path.display(), s.title);
    let _ = writeln!(
        out,
        "  c = {} m/s; table {} x {} m (light crosses it in {} s); restitution {} (cushions {})",
        number(s.c),
        number(s.table.size.x),
        number(s.table.size.y),
        number(s.table.size.x.max(s.table.size.y) / s.c),
        s.restitution,
        s.table.cushion_restitution
    );
    if s.table.friction > 0.0 {
        let a = s.table.deceleration();
        let _ = writeln!(
            out,
            "  sliding friction μ = {} at g = {} m/s²: pucks brake at μg = {} m/s² \
             (a puck at γ stops after (c²/μg)(γ − 1) = {} m × (γ − 1))",
            number(s.table.friction),
            number(s.table.gravity),
            number((a * 1e6).round() / 1e6),
            number((s.c * s.c / a * 1e6).round() / 1e6)
        );
    } else {
        let _ = writeln!(
            out,
            "  no friction (friction = 0): pucks glide uniformly between contacts"
        );
    }
    let _ = writeln!(out, "  effects on: {}; off: {}", list(&on), list(&off));
    let _ = writeln!(out, "  {} puck(s):", s.pucks.len());
    for p in &s.pucks {
        let beta = p.u.beta();
        let _ = writeln!(
            out,
            "    {:<10} at ({:.4}, {:.4}) m  β = ({:+.6}, {:+.6}) |β| = {:.9}  γ = {}  r = {} m  m = {} kg  {}",
            p.name,
            p.position.x,
            p.position.y,
            beta.x,
            beta.y,
            beta.length(),
            gamma(p.u.gamma()),
            number(p.radius),
            number(p.mass),
            p.color.to_hex()
        );
    }
    let _ = writeln!(out, "  {} observer(s):", s.observers.len());
    for o in &s.observers {
        let aim = match o.look_at {
            Some(p) => format!("looking at ({:.3}, {:.3}, {:.3})", p.x, p.y, p.z),
            None => "framing the table".to_owned(),
        };
        let _ = writeln!(
            out,
            "    {:<10} at ({:.3}, {:.3}, {:.3}) m {aim}  |β| = {:.6}  γ = {}",
            o.name,
            o.position.x,
            o.position.y,
            o.position.z,
            o.u.beta().length(),
            gamma(o.u.gamma())
        );
    }
    out
}

/// γ to six decimals below 10⁶, in exponent form above (never inf: the
/// scene loader holds |u| ≤ 10¹²).
fn gamma(g: f64) -> String {
    if g < 1e6 {
        format!("{g:.6}")
    } else {
        format!("{g:.6e}")
    }
}

fn list(items: &[&str]) -> String {
    if items.is_empty() {
        "none".to_owned()
    } else {
        items.join(", ")
    }
}
