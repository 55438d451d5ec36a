//! `lightcone wall --join ENDPOINT --wall NAME`: a render node of a CAVE
//! cluster (see [`crate::cluster`]).

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use crate::cluster::node::{self, ClusterNode, Headless};

/// The command line of `wall`.
pub struct WallArgs {
    /// The master's Zenoh endpoint.
    pub join: String,
    /// The walls this node draws.
    pub walls: Vec<String>,
    /// Compute and log, draw nothing.
    pub headless: bool,
    /// Frames before stopping (0: until the master is silent).
    pub frames: u64,
    /// The frame log.
    pub frame_log: Option<PathBuf>,
    /// Seconds without a frame before stopping.
    pub silence: f64,
    /// Screenshot after `frames` frames (with a window).
    pub screenshot: Option<PathBuf>,
}

/// Runs the node.
pub fn run(args: &WallArgs) -> ExitCode {
    if !(args.silence.is_finite() && args.silence > 0.0 && args.silence <= 3600.0) {
        eprintln!(
            "lightcone wall: --silence {}: give seconds, more than 0 and at most 3600",
            args.silence
        );
        return ExitCode::from(2);
    }
    let mut joined = match ClusterNode::join(
        &args.join,
        &args.walls,
        Duration::from_secs_f64(args.silence),
    ) {
        Ok(n) => n,
        Err(e) => {
            crate::errln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let options = Headless {
        frames: args.frames,
        log: args.frame_log.clone(),
        silence: Duration::from_secs_f64(args.silence),
        screenshot: args.screenshot.clone(),
    };
    if args.screenshot.is_some() && (args.headless || args.frames == 0) {
        eprintln!("--screenshot needs a window and --frames N");
        return ExitCode::FAILURE;
    }
    let result = if args.headless {
        node::run_headless(&mut joined, &options)
    } else {
        crate::play::app::run_node(joined, &options)
    };
    match result {
        Ok(shown) => {
            eprintln!(
                "lightcone wall {}: {shown} frames shown",
                args.walls.join(", ")
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            crate::errln!("{e}");
            ExitCode::FAILURE
        }
    }
}
