//! Special-relativistic kinematics: events, 4-vectors, proper velocities,
//! Lorentz boosts, velocity composition and 4-momentum.
//!
//! Everything here is stated in a way that keeps its digits at any Lorentz
//! factor the engine can meet (tested up to γ = 10⁹):
//!
//! * a velocity is held as the **proper velocity** `u = γβ` (dimensionless),
//!   never as `β`, so `γ = √(1 + u²)` is exact and no state can reach `c`;
//! * nothing computes `1 − v²/c²`: where `1 − β` or `γ − 1` is needed it is
//!   obtained as a quotient of positive terms;
//! * boosts are applied in **light-cone coordinates** `ct ± x∥`, in which a
//!   boost is a pair of multiplications by `e^{∓η}`: no difference of two
//!   large numbers is formed, so a boost followed by its inverse returns the
//!   input to a few ulps whatever the rapidity.

mod boost;
mod event;
mod momentum;
mod simultaneity;
mod velocity;
mod wigner;

pub use boost::{Boost, compose};
pub use event::{Event, FourVector};
pub use momentum::FourMomentum;
pub use simultaneity::{simultaneity_slope, simultaneous_board_time};
pub use velocity::{ProperVelocity, SpeedError};
pub use wigner::{rotate_about_normal, rotation_of_velocity_change, wigner_angle};
