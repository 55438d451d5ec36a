//! The Lightcone game: its command-line tools and the interactive front end
//! (window, lessons, CAVE). The physics and optics live in
//! `lightcone-engine`, the drawing in `lightcone-render`, the Python classes
//! in `lightcone-py`.

pub mod assets;
pub mod cave;
pub mod cluster;
pub mod commands;
pub mod interrupt;
pub mod lesson;
pub mod model;
pub mod output;
pub mod play;
pub mod progress;
pub mod tracker_bridge;

/// The scene used when none is named.
pub const DEFAULT_SCENE: &str = "assets/scenes/paper_carom.toml";
