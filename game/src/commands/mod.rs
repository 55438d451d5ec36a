//! One module per subcommand.

pub mod args;
pub mod bench;
pub mod bench_optics;
pub mod bench_render;
pub mod bench_tracker;
pub mod cave;
pub mod check;
pub mod diagram;
pub mod lesson;
pub mod link;
pub mod looks;
pub mod names;
pub mod observe;
pub mod play;
pub mod record;
pub mod render;
pub mod simulate;
pub mod tracker;
pub mod wall;
