//! The systems of the frame schedule, one module per phase, and the input
//! kinks of observers' worldlines ([`input`]: plain functions called
//! between frames). Each reads and writes only the types of
//! [`super::components`] and [`super::resources`]; the schedule
//! ([`super::schedule`]) orders them.

pub mod history;
pub mod input;
pub mod kinematics;
pub mod optics;
