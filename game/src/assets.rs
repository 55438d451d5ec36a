//! The default scene and CAVE description, built into the binary so that
//! `lightcone play`, `check` and `cave` work from any folder (and after
//! `cargo install`), not only from the checkout.

use lightcone_engine::scene::{self, Scene, SceneErrors};
use lightcone_tracker::cave::CaveConfig;

/// The text of `assets/scenes/paper_carom.toml`, the default scene.
pub const DEFAULT_SCENE_TOML: &str = include_str!("../../assets/scenes/paper_carom.toml");

/// The name the built-in scene goes by in messages and summaries.
pub const DEFAULT_SCENE_NAME: &str = "(built in) paper_carom.toml";

/// The text of `assets/cave.toml`, the default CAVE.
pub const DEFAULT_CAVE_TOML: &str = include_str!("../../assets/cave.toml");

/// The default scene (the paper's carom shot).
pub fn default_scene() -> Result<Scene, SceneErrors> {
    scene::parse(DEFAULT_SCENE_TOML, DEFAULT_SCENE_NAME)
}

/// The default CAVE (three walls and a floor, see `assets/cave.toml`).
pub fn default_cave() -> Result<CaveConfig, String> {
    CaveConfig::from_toml_str(DEFAULT_CAVE_TOML).map_err(|e| format!("(built in) cave.toml: {e}"))
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_built_in_assets_are_valid() {
        assert!(super::default_scene().is_ok());
        assert!(super::default_cave().is_ok());
    }
}
