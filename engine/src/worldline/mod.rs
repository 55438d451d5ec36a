//! Worldlines: the history of each body as analytic segments, the body's
//! shape at any board time, and the rest-frame meshes.

pub mod contraction;
mod linear;
pub mod mesh;
mod shape;
pub mod sliding;

pub use linear::{BodyState, Segment, Worldline, WorldlineError};
pub use contraction::{ContractedShape, LorentzMap, Rigid, SegmentShape, ShapeMaps};
pub use shape::{RestShape, contract};
