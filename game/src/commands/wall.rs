//! `lightcone wall --join ENDPOINT --wall NAME`: a render node of a CAVE
//! cluster (see [`crate::cluster`]).

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use crate::cluster::node::{self, ClusterNode, Headless};

/// The command line of `wall`.
#[derive(clap::Args)]
pub struct WallArgs {
    /// The master's Zenoh endpoint, e.g. tcp/192.168.1.10:7447.
    #[arg(long)]
    pub join: String,
    /// The CAVE's cluster key: a copy of the key file beside the master's
    /// CAVE file (`lightcone cluster-key CAVE.toml` makes it).
    #[arg(long)]
    pub key: PathBuf,
    /// A wall of the master's CAVE file to draw (repeatable).
    #[arg(long = "wall", required = true)]
    pub walls: Vec<String>,
    /// Draw nothing: compute the walls' eyes, keep the swap lock and log
    /// (tests, benchmarks, a node without a display).
    #[arg(long)]
    pub headless: bool,
    /// Stop after this many frames (0: until the master is silent).
    #[arg(long, default_value_t = 0)]
    pub frames: u64,
    /// Write each frame shown, one JSON line a frame (as `play
    /// --frame-log`).
    #[arg(long)]
    pub frame_log: Option<PathBuf>,
    /// Wait this many seconds for the master to be there, and stop after
    /// this many without a frame from it.
    #[arg(long, default_value_t = 10.0)]
    pub silence: f64,
    /// Save a screenshot of the node's windows (the main one, and one
    /// per output as FILE.OUTPUT.png) after --frames frames, then stop.
    #[arg(long, value_parser = super::args::png_file)]
    pub screenshot: Option<PathBuf>,
}

/// Runs the node.
pub fn run(args: &WallArgs) -> ExitCode {
    if !(args.silence.is_finite() && args.silence > 0.0 && args.silence <= 3600.0) {
        crate::errln!(
            "lightcone wall: --silence {}: give seconds, more than 0 and at most 3600",
            args.silence
        );
        return ExitCode::from(2);
    }
    let key = match crate::cluster::key::load(&args.key) {
        Ok(k) => k,
        Err(e) => {
            crate::errln!("lightcone wall: --key {e}");
            return ExitCode::from(2);
        }
    };
    let mut joined = match ClusterNode::join(
        &args.join,
        &args.walls,
        Duration::from_secs_f64(args.silence),
        key,
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
        crate::errln!("--screenshot needs a window and --frames N");
        return ExitCode::FAILURE;
    }
    let result = if args.headless {
        node::run_headless(&mut joined, &options)
    } else {
        crate::play::app::run_node(joined, &options)
    };
    match result {
        Ok(shown) => {
            crate::errln!(
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

/// `lightcone cluster-key CAVE.toml [--replace]`: writes the CAVE's cluster
/// key beside its file (see [`crate::cluster::key`]), and says where to
/// copy it.
pub fn keygen(cave: &std::path::Path, replace: bool) -> ExitCode {
    if let Err(e) = crate::cave::load(cave) {
        crate::errln!("lightcone cluster-key: {e}");
        return ExitCode::FAILURE;
    }
    let path = crate::cluster::key::beside(cave);
    match crate::cluster::key::generate(&path, replace) {
        Ok(()) => {
            crate::sayln!("{}", path.display());
            crate::errln!(
                "lightcone cluster-key: wrote {}; copy it to every render node \
                 (`lightcone wall --key FILE`), keep it off shared folders",
                path.display()
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            crate::errln!("lightcone cluster-key: {e}");
            ExitCode::FAILURE
        }
    }
}
