//! What the tracker's process tests share: a publisher (the
//! `lightcone-tracker-publisher` binary) in a child process on a service of
//! the test's own, its stderr read line by line.

use lightcone_tracker::unix_now_ns;
use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;

/// The publisher's process, killed when dropped.
pub struct Publisher {
    child: Child,
    /// The iceoryx2 service it publishes on.
    pub service: String,
}

impl Publisher {
    /// Starts a publisher with `args` (after `--service`), named by `test`;
    /// its stderr, a line at a time (read on after it is dropped).
    pub fn spawn(test: &str, args: &[&str]) -> (Self, mpsc::Receiver<String>) {
        let service = format!(
            "lightcone/test/{test}/{}/{}",
            std::process::id(),
            unix_now_ns()
        );
        let mut child = Command::new(env!("CARGO_BIN_EXE_lightcone-tracker-publisher"))
            .args(["--service", &service])
            .args(args)
            .stdin(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("spawn publisher");
        let stderr = child.stderr.take().expect("stderr");
        let (tx, lines) = mpsc::channel::<String>();
        std::thread::spawn(move || {
            for line in BufReader::new(stderr).lines().map_while(Result::ok) {
                let _ = tx.send(line);
            }
        });
        (Self { child, service }, lines)
    }
}

impl Publisher {
    /// The publisher's resident memory, kB (Linux: `VmRSS` in
    /// `/proc/PID/status`).
    #[allow(dead_code)] // not every test binary measures it
    pub fn resident_kb(&self) -> u64 {
        let status = std::fs::read_to_string(format!("/proc/{}/status", self.child.id()))
            .expect("the publisher's /proc status");
        status
            .lines()
            .find_map(|l| l.strip_prefix("VmRSS:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
            .expect("VmRSS")
    }
}

impl Drop for Publisher {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
