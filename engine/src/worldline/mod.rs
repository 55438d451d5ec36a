//! Worldlines: the history of each body as analytic segments, the body's
//! shape at any board time, and the rest-frame meshes.

mod linear;
pub mod mesh;
mod shape;
pub mod sliding;

pub use linear::{BodyState, Segment, Worldline, WorldlineError};
pub use shape::{RestShape, contract};
