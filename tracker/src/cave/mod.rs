//! CAVE display geometry and head-tracked off-axis projection: the walls,
//! how tracker space sits in board space, and the CAVE file that says both.
//!
//! Why: in a CAVE each wall is a fixed physical window into the scene. The
//! correct image for a viewer is a perspective from their *tracked eye*
//! through that window, i.e. an asymmetric (off-axis) frustum whose edges
//! pass through the wall's corners: Robert Kooima's "Generalized
//! Perspective Projection" (2008), in [`projection`]. [`board`] maps
//! tracker space to the game's board, and [`config`] reads the CAVE file
//! (walls, video outputs, the tracker's placement).
//!
//! # Coordinate frames
//!
//! * **Tracker space**: the tracker's frame, metres. Wall corners and head
//!   poses are given in it. By default y is up (`up_axis = "y"`, as OpenVR
//!   and OptiTrack); set `up_axis = "z"` for z-up trackers.
//! * **Board space**: the game's frame (z up, metres, origin at a table
//!   corner). A tracker point `p` maps to
//!   `board = origin + scale * Rz(yaw) * A * p`, where `A` is identity for a
//!   z-up tracker and the +90° rotation about x (`(x, y, z) -> (x, -z, y)`)
//!   for a y-up tracker, so tracker "up" becomes board +z and tracker
//!   "forward" (-z) becomes board +y.
//!
//! Projections are computed in tracker space (near/far are tracker metres);
//! [`CaveConfig::view_projection_board`] appends the board→tracker transform
//! so the game can feed board-space vertices directly.

pub mod board;
pub mod config;
pub mod projection;

pub use board::{TrackerToBoard, UpAxis};
pub use config::{CaveConfig, CaveConfigError, Output, OutputEyes, Placement};
pub use projection::{
    DEFAULT_EYE_SEPARATION, Frustum, ProjectionError, Wall, WallProjection, off_axis_projection,
    stereo_eyes,
};
