//! The Lightcone game: its command-line tools and the interactive front end
//! (window, lessons, CAVE). The physics and optics live in
//! `lightcone-engine`, the drawing in `lightcone-render`, the Python classes
//! in `lightcone-py`.

#![warn(missing_docs)]

// Desktop-only modules (`cfg(not(target_arch = "wasm32"))`): the command
// line, the lessons (embedded Python, child processes), the head tracker's
// bridge process and the render cluster. The browser build has the model,
// the window's framework and the game's frame in it (`play::web_app`).
pub mod assets;
pub mod cave;
#[cfg(not(target_arch = "wasm32"))]
pub mod cluster;
#[cfg(not(target_arch = "wasm32"))]
pub mod commands;
#[cfg(not(target_arch = "wasm32"))]
pub mod interrupt;
#[cfg(not(target_arch = "wasm32"))]
pub mod lesson;
pub mod lesson_game;
pub mod links;
pub mod model;
pub mod output;
pub mod play;
#[cfg(not(target_arch = "wasm32"))]
pub mod progress;
#[cfg(not(target_arch = "wasm32"))]
pub mod tracker_bridge;

/// The scene used when none is named.
pub const DEFAULT_SCENE: &str = "assets/scenes/paper_carom.toml";
