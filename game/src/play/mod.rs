//! `lightcone play [SCENE]`: the interactive game. [`crate::model`] holds
//! the game's logic (time, replay, cue, flight, effects), testable without
//! a window; [`app`] is the winit + wgpu + egui front end.

pub mod app;
pub mod collision_arcs;
pub mod diagram_controls;
pub mod lesson_panel;
pub mod outputs;
pub mod overlay;
pub mod scene_menu;
