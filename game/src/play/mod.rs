//! `lightcone play [SCENE]`: the interactive game. [`crate::model`] holds
//! the game's logic (time, replay, cue, flight, effects), testable without
//! a window; [`window`] is the framework (winit, wgpu, egui) and [`app`]
//! the game's frame in it, put together from one file per concern. The
//! browser build (wasm32) has `web_app` in place of `app`: the same
//! frame without lessons, tracker, CAVE outputs, cluster or screenshots.

pub mod actions;
#[cfg(not(target_arch = "wasm32"))]
pub mod app;
#[cfg(not(target_arch = "wasm32"))]
pub mod cave_role;
#[cfg(not(target_arch = "wasm32"))]
pub mod cluster_role;
pub mod collision_arcs;
pub mod diagram;
pub mod input;
pub mod labels;
pub mod layout;
#[cfg(not(target_arch = "wasm32"))]
pub mod lesson_host;
pub mod lesson_panel;
pub mod magnifier;
#[cfg(not(target_arch = "wasm32"))]
pub mod outputs;
pub mod overlay;
pub mod panels;
pub mod pictures;
pub mod scene_menu;
#[cfg(not(target_arch = "wasm32"))]
pub mod screenshot;
pub mod shown;
pub mod sidecar;
#[cfg(not(target_arch = "wasm32"))]
pub mod slide;
pub mod stage;
pub mod trails;
pub mod ui_paint;
#[cfg(target_arch = "wasm32")]
pub mod web_app;
#[cfg(target_arch = "wasm32")]
pub mod web_lesson;
pub mod window;
