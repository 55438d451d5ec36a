//! The Lightcone game: its command-line tools, the wgpu renderer, and the
//! interactive front end. The physics and optics live in `lightcone-engine`.

pub mod assets;
pub mod cave;
pub mod commands;
pub mod interrupt;
pub mod lesson;
pub mod output;
pub mod play;
pub mod progress;
pub mod python;
pub mod render;
pub mod tracker_bridge;

/// The scene used when none is named.
pub const DEFAULT_SCENE: &str = "assets/scenes/paper_carom.toml";
