//! Worldlines: the history of each body as analytic segments, the body's
//! contracted shape along it (segment by segment), and the rest-frame
//! meshes.

pub mod contraction;
mod linear;
pub mod mesh;
mod shape;
pub mod sliding;

pub use contraction::{ContractedShape, LorentzMap, Rigid, SegmentShape, ShapeMaps};
pub use linear::{BodyState, Segment, Worldline, WorldlineError};
pub use shape::{RestShape, contract};
