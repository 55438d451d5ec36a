//! What a Lightcone lesson sees and shows, without Python.
//!
//! A lesson's hooks are given a world: the running game (board time,
//! pucks, effects, view) and the lesson's voice on screen (text,
//! questions, checked claims, bar charts). This crate holds that world's
//! every operation, checked ([`WorldCall`], on a [`WorldCore`] and the game it borrows), what it puts on screen
//! ([`LessonUi`]), and the JSON protocol by which a lesson run elsewhere
//! asks for them ([`protocol`]). Python's `lightcone.World` (lightcone-py)
//! wraps a `WorldCore`; the game serves a lesson run in its own process,
//! or in a browser's Web Worker, through `protocol`: one implementation
//! of the world for all of them.

#![warn(clippy::must_use_candidate)]

mod args;
pub mod error;
mod game;
pub mod protocol;
pub mod query;
pub mod scene_code;
mod screen;
pub mod simulation;
pub mod standin;
mod world;

pub use error::{ErrorKind, WorldError, WorldResult};
pub use game::LessonGame;
pub use screen::{
    Bars, Claim, LessonUi, MAX_BINS, MAX_CHARTS, MAX_CHOICES, MAX_CLAIM_BYTES, MAX_CLAIMS,
    MAX_TEXT_BYTES, Pictures, Question,
};
pub use world::{NO_GAME, WorldCall, WorldCore, cut};
