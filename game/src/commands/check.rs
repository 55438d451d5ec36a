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
            number(figure(a)),
            number(figure(s.c * s.c / a))
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

/// `x` rounded to 12 significant digits (1.9620000000000002 → 1.962),
/// which keeps a deceleration of 10⁻¹² m/s² (rounding to six decimals
/// printed it as 0) and a horizon of 10³⁰ m.
fn figure(x: f64) -> f64 {
    format!("{x:.11e}").parse().unwrap_or(x)
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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A summary's numbers: every word that reads as a float.
    fn numbers(summary: &str) -> Vec<f64> {
        summary
            .split(|c: char| c.is_whitespace() || "(),;:=×".contains(c))
            .filter_map(|w| w.trim_end_matches(['m', 's', 'k', 'g']).parse::<f64>().ok())
            .collect()
    }

    proptest! {
        /// Scenes at the ends of the ranges (docs/guide/src/scenes.md, "What the engine
        /// holds") that the loader accepts: `check`'s summary prints
        /// finite figures only, and the braking ones as their size, not 0.
        #[test]
        fn the_summary_of_any_accepted_scene_is_finite(
            c in proptest::sample::select(vec![1e-6, 1.0, 1e9]),
            friction in proptest::sample::select(vec![0.0, 1e-6, 0.2, 100.0, 5e-324]),
            gravity in proptest::sample::select(vec![1e-6, 9.80665, 1e6]),
            u in proptest::sample::select(vec![0.0, 1e-300, 1.0, 1e12]),
            radius in proptest::sample::select(vec![1e-6, 0.0305, 1e3]),
        ) {
            let text = format!(
                "c = {c:e}\n[table]\nsize = [1e6, 1e6]\nfriction = {friction:e}\n\
                 gravity = {gravity:e}\n[[puck]]\nposition = [5e5, 5e5]\nu = [{u:e}, 0]\n\
                 radius = {radius:e}\n"
            );
            let Ok(s) = scene::parse(&text, "ends.toml") else {
                // Refused: a range or the braking horizon; not this test's.
                prop_assert!(friction == 5e-324 || radius >= c * c / (friction * gravity));
                return Ok(());
            };
            let out = summary(Path::new("ends.toml"), &s);
            prop_assert!(!out.contains("inf") && !out.contains("NaN"), "{}", out);
            prop_assert!(numbers(&out).iter().all(|x| x.is_finite()), "{}", out);
            if friction > 0.0 {
                let mug = friction * gravity;
                prop_assert!(
                    out.contains(&format!("brake at μg = {} m/s²", number(figure(mug)))),
                    "{}", out
                );
                prop_assert!((figure(mug) / mug - 1.0).abs() < 1e-11);
            }
        }
    }
}
