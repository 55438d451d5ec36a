//! Scene files (TOML): schema, loading, validation and error messages that
//! name the file, line and field.
//!
//! See the README section "Scene files" for the format. A scene is read in
//! two steps: [`raw`] mirrors the file with the position of every value,
//! then [`validate`] checks the physics (speed below `c`, pucks on the table
//! and apart, finite numbers) and builds the engine's [`Scene`].

mod error;
mod model;
mod raw;
mod validate;

pub use error::{SceneError, SceneErrors};
pub use model::{
    BeforeStart, Color, Effect, Effects, ObserverSpec, OpticsSpec, PuckSpec, Scene, TableSpec,
};

use std::path::Path;

/// Reads and validates the scene file at `path`.
pub fn load(path: &Path) -> Result<Scene, SceneErrors> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| {
        SceneErrors::single(SceneError::whole_file(&file, format!("cannot read: {e}")))
    })?;
    parse(&text, &file)
}

/// Parses and validates scene text; `file` is the name used in messages.
pub fn parse(text: &str, file: &str) -> Result<Scene, SceneErrors> {
    let raw = raw::parse(text, file)?;
    validate::validate(raw, text, file)
}
