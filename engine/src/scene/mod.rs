//! Scene files (TOML): schema, loading, validation and error messages that
//! name the file, line and field.
//!
//! See the guide, docs/guide/src/scenes.md, for the format. A scene is read in
//! two steps: the private `raw` module mirrors the file with the position of every value,
//! then `validate` checks the physics (speed below `c`, pucks on the table
//! and apart, finite numbers) and builds the engine's [`Scene`]. The rules
//! themselves are stated once, in [`rules`], for the file loader and for
//! scenes built in code ([`Scene::add_puck`] …) alike; a broken one is a
//! [`BuildError`].

mod build;
mod effects;
mod error;
mod model;
mod overlap;
mod raw;
pub mod rules;
mod validate;

pub use effects::{Effect, Effects};
pub use error::{SceneError, SceneErrors, number};
pub use model::{BeforeStart, Color, ObserverSpec, OpticsSpec, PuckSpec, Scene, TableSpec};
pub use overlap::{first_overlaps, overlap};
pub use rules::{
    BuildError, C_RANGE, GRAVITY_RANGE, LENGTH_RANGE, MASS_RANGE, MAX_DICHOTOMY_STEPS,
    MAX_FRICTION, MAX_HISTORY_FRAMES, MAX_OBSERVER_DISTANCE, MAX_OBSERVERS, MAX_PUCKS, MAX_U,
    MIN_FRICTION, Quantity, braking_horizon,
};
pub use validate::MAX_ERRORS_PER_KIND;

use std::path::Path;

/// The largest scene file read, bytes: a million pucks written out in full
/// (about 150 bytes each) fit; `/dev/zero` or a video given by mistake is
/// refused instead of read until memory runs out.
pub const MAX_SCENE_BYTES: u64 = 256 << 20;

/// Reads and validates the scene file at `path` (at most
/// [`MAX_SCENE_BYTES`]).
pub fn load(path: &Path) -> Result<Scene, SceneErrors> {
    let text = read_text(path)?;
    parse(&text, &path.display().to_string())
}

/// The text of the scene file at `path` (at most [`MAX_SCENE_BYTES`],
/// UTF-8), read once: what [`load`] parses, for a caller that keeps the
/// text too.
pub fn read_text(path: &Path) -> Result<String, SceneErrors> {
    use std::io::Read;
    let file = path.display().to_string();
    let cannot = |e: std::io::Error| {
        SceneErrors::single(SceneError::whole_file(&file, format!("cannot read: {e}")))
    };
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(MAX_SCENE_BYTES + 1).read_to_end(&mut bytes))
        .map_err(cannot)?;
    if bytes.len() as u64 > MAX_SCENE_BYTES {
        return Err(SceneErrors::single(SceneError::whole_file(
            &file,
            format!("more than {} MiB: not a scene file", MAX_SCENE_BYTES >> 20),
        )));
    }
    utf8(&bytes, &file)?;
    // UTF-8, checked just above (with the error located).
    Ok(String::from_utf8(bytes).unwrap_or_default())
}

/// The bytes as text, or an error at the line and column of the first byte
/// that is not UTF-8.
pub fn utf8<'a>(bytes: &'a [u8], file: &str) -> Result<&'a str, SceneErrors> {
    std::str::from_utf8(bytes).map_err(|e| {
        let good = e.valid_up_to();
        let before = std::str::from_utf8(&bytes[..good]).unwrap_or_default();
        SceneErrors::single(SceneError::at(
            file,
            before,
            good,
            "",
            format!(
                "byte 0x{:02x} is not UTF-8: save the scene as UTF-8 text",
                bytes[good]
            ),
        ))
    })
}

/// Parses and validates scene text; `file` is the name used in messages.
pub fn parse(text: &str, file: &str) -> Result<Scene, SceneErrors> {
    let raw = raw::parse(text, file)?;
    validate::validate(raw, text, file)
}
