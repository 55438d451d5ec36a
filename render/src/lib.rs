//! The renderer: draws what the optics produced (apparent positions,
//! Doppler factors, intensities) and knows nothing of relativity.
//!
//! * [`camera`]: framing the table (direction and field of view from a
//!   fixed eye);
//! * [`diagram`]: the space-time diagram, drawn on the CPU;
//! * [`frame`]: turns an observer's view into a triangle list in the
//!   observer's frame, relative to the eye (f32 only here);
//! * [`pipeline`]: the wgpu pipeline (`scene.wgsl` beside it), with
//!   `new / resize / render`; the device and queue are passed in;
//! * [`gpu`]: adapter and device, with one clear line when there is none;
//! * [`headless`]: render to a PNG (`lightcone render`, the image tests).

pub mod camera;
pub mod diagram;
pub mod frame;
pub mod gpu;
pub mod headless;
pub mod pipeline;
