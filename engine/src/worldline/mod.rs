//! Worldlines: the history of each body as analytic segments, and the
//! body's shape at any board time.

mod linear;
mod shape;
pub mod sliding;

pub use linear::{BodyState, Segment, Worldline, WorldlineError};
pub use shape::{RestShape, contract};
