//! Collision prediction in closed form, one kernel per pair of shapes.

pub mod bounds;
pub mod braking;
mod braking_kicks;
mod braking_motion;
pub mod isolation;
pub mod pair;
pub mod puck_cushion;
pub mod puck_puck;

pub use puck_cushion::Cushion;
