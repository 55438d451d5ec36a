//! How a lesson's own process is started: which binary, and the memory it
//! may take. Plain data, shared by the window's lesson host
//! ([`super::remote`]) and the headless runs ([`super::headless`]), so that
//! neither imports the other.

use std::path::PathBuf;

/// How the window (or a headless run waited hook by hook) starts its
/// lesson's process.
#[derive(Clone, Debug)]
pub struct Isolation {
    /// The `lightcone` binary to start (the game's own).
    pub exe: PathBuf,
    /// Address-space limit of the lesson's process, MiB.
    pub memory_mb: u64,
}
