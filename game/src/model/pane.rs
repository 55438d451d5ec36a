//! Which pictures the window shows: each an eye (the one looked through,
//! the free eye, a scene observer) and a kind (seen or truth), and the
//! `--views` list that names them.

use lightcone_engine::scene::Scene;
use lightcone_render::frame::ViewKind;

/// Whose eye a picture looks through.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EyeChoice {
    /// The eye the player looks through ([`crate::model::GameState::observer`]: the
    /// free eye, or the scene observer chosen in the panel).
    Current,
    /// The free eye ("you").
    You,
    /// The scene's observer `i`.
    Scene(usize),
}

/// One picture of the window: an eye, and what it shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pane {
    /// Whose eye.
    pub eye: EyeChoice,
    /// Seen (the effects on) or the truth.
    pub kind: ViewKind,
}

impl Pane {
    /// Parses a comma-separated list of pictures, shown side by side:
    /// each `seen` or `truth` (through the eye looked through), `you` or
    /// an observer's name (what that eye sees), or `EYE:seen`,
    /// `EYE:truth`. E.g. `seen,truth`, or `you,observer` for two eyes.
    pub fn parse_list(spec: &str, scene: &Scene) -> Result<Vec<Pane>, String> {
        let kind = |k: &str| match k {
            "seen" => Ok(ViewKind::Seen),
            "truth" => Ok(ViewKind::Truth),
            other => Err(format!("--views: {other:?} is not seen or truth")),
        };
        let eye = |e: &str| {
            if e == "you" {
                return Ok(EyeChoice::You);
            }
            scene
                .observers
                .iter()
                .position(|o| o.name == e)
                .map(EyeChoice::Scene)
                .ok_or_else(|| {
                    let names: Vec<&str> =
                        scene.observers.iter().map(|o| o.name.as_str()).collect();
                    format!(
                        "--views: no eye {e:?} (you, or an observer of the scene: {})",
                        names.join(", ")
                    )
                })
        };
        let mut out = Vec::new();
        for item in spec.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let pane = match item.split_once(':') {
                Some((e, k)) => Pane {
                    eye: eye(e.trim())?,
                    kind: kind(k.trim())?,
                },
                None => match kind(item) {
                    Ok(k) => Pane {
                        eye: EyeChoice::Current,
                        kind: k,
                    },
                    Err(_) => Pane {
                        eye: eye(item)?,
                        kind: ViewKind::Seen,
                    },
                },
            };
            out.push(pane);
        }
        if out.is_empty() {
            return Err("--views: give at least one picture (e.g. seen,truth)".into());
        }
        if out.len() > 8 {
            return Err("--views: at most 8 pictures".into());
        }
        Ok(out)
    }
}
