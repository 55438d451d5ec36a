//! `lightcone play [SCENE]`: the interactive game. [`crate::model`] holds
//! the game's logic (time, replay, cue, flight, effects), testable without
//! a window; [`window`] is the framework (winit, wgpu, egui) and [`app`]
//! the game's frame in it, put together from one file per concern.

pub mod actions;
pub mod app;
pub mod cave_role;
pub mod cluster_role;
pub mod collision_arcs;
pub mod diagram_controls;
pub mod input;
pub mod labels;
pub mod layout;
pub mod lesson_host;
pub mod lesson_panel;
pub mod outputs;
pub mod overlay;
pub mod panels;
pub mod pictures;
pub mod scene_menu;
pub mod screenshot;
pub mod shown;
pub mod window;
