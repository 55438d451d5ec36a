//! The renderer (`lightcone-render`): draws what the optics produced
//! (apparent positions, Doppler factors, intensities) and knows nothing of
//! relativity. It needs a GPU adapter but no window: the game's window,
//! `lightcone render` and the Python wheel all draw through it.
//!
//! * [`camera`]: framing the table (direction and field of view from a
//!   fixed eye);
//! * [`diagram`]: the space-time diagram, drawn on the CPU;
//! * [`frame`]: turns an observer's view into a triangle list in the
//!   observer's frame, relative to the eye (f32 only here);
//! * [`pipeline`]: the wgpu pipeline (`scene.wgsl` beside it), with
//!   `new / resize / render`; the device and queue are passed in;
//! * [`gpu`]: adapter and device, with one clear line when there is none;
//! * [`headless`]: render to a PNG (`lightcone render`, the image tests);
//! * [`observe`]: what an observer sees, as the report `lightcone observe`
//!   prints and Python's `observe` returns.

#![warn(missing_docs)]
#![warn(clippy::must_use_candidate)]

pub mod camera;
pub mod diagram;
pub mod frame;
pub mod gpu;
pub mod headless;
pub mod observe;
pub mod pipeline;
