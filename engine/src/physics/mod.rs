//! Event-anticipation physics (the paper's §3.3 and Appendix): every future
//! collision is predicted in closed form, the simulation runs freely to the
//! earliest, resolves it, and re-predicts only what changed.
//!
//! * [`predict`]: when and where two pucks, or a puck and a cushion, meet;
//! * [`resolve`]: what comes out of a collision (4-momentum conserved);
//! * `calendar`: one pending event per puck, in time order (Paul's
//!   calendar queue), invalidated lazily by the partner's version;
//! * `broadphase`: rapier's broad-phase BVH on position shells, used only
//!   to find candidate pairs;
//! * [`Billiard`]: the event loop tying them together.
//!
//! Conventions (the paper's §3.3.1): pucks are rigid about their centres.
//! A puck–puck contact is found in the frame where the two pucks move with
//! equal and opposite speeds (for equal masses this is the paper's
//! centre-of-momentum frame, Eq. 3), where their contracted shapes are
//! congruent; both pucks' velocities change at the events on their centres'
//! worldlines simultaneous with the contact in that frame (not when light
//! from the contact reaches each centre, the paper's Appendix convention,
//! which lets pucks pass through each other at high γ; see [`overlap`] for
//! what the chosen convention still allows). A cushion is infinitely
//! massive and at rest on the board; the puck's velocity changes at the
//! board-frame instant of contact.

mod billiard;
mod broadphase;
mod calendar;
pub mod fixed_step;
pub mod gas;
pub mod overlap;
pub mod predict;
pub mod resolve;

pub use billiard::{Billiard, Collision, CollisionKind, PuckInit, PuckOutcome, Stats};
pub use predict::Cushion;
