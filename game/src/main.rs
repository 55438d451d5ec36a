//! `lightcone`: the relativistic carom billiard and its command-line tools.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod commands;

/// The scene used when none is named.
pub const DEFAULT_SCENE: &str = "assets/scenes/paper_carom.toml";

#[derive(Parser)]
#[command(
    name = "lightcone",
    version,
    about = "A relativistic carom billiard for learning Special Relativity"
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Validate scene files and print a short summary of each.
    Check {
        /// Scene files (TOML); the default scene when none is given.
        scenes: Vec<PathBuf>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Some(Command::Check { scenes }) => commands::check::run(&scenes),
        None => commands::check::run(&[]),
    }
}
