//! The tracker's shared memory is read in a child process, never in the
//! game's.
//!
//! iceoryx2 maps the tracker service's segments (its own bookkeeping as well
//! as the samples) into every process that subscribes. A crashed or hostile
//! peer can write anything there, and iceoryx2 follows offsets and indices
//! it reads from those segments: random bytes in them can make a reader
//! segfault, loop, or allocate without end. No validation of the *samples*
//! protects against that, so the game does not map them at all:
//!
//! * `lightcone tracker-bridge --service NAME` (the game's own binary,
//!   re-executed; hidden from `--help`) subscribes through iceoryx2 and
//!   writes every sample it receives to its standard output as a frame of
//!   this module's tiny protocol (below), plus a heartbeat every 100 ms and a
//!   line of status when the connection state changes.
//! * The game ([`Bridge`]) reads the pipe on a thread, decodes the frames
//!   with safe byte conversions (every field of a sample is then validated by
//!   the [`Follower`](lightcone_tracker::Follower) as before) and, when the
//!   child dies, sends a frame it does not understand, or stays silent for
//!   [`SILENCE_LIMIT`], kills it and starts a new one after a back-off
//!   ([`RESPAWN_MIN`] doubling to [`RESPAWN_MAX`]). Meanwhile the follower
//!   holds the last good pose and goes stale, then lost, as for a dead
//!   tracker.
//!
//! The child limits its own address space ([`MEMORY_LIMIT_MB`]), dies with
//! the game (`PR_SET_PDEATHSIG`) and sits in its own process group (Ctrl-C
//! in the terminal is the game's). Dead iceoryx2 nodes (a killed bridge, a
//! crashed publisher) are cleaned each time a bridge opens the service
//! ([`lightcone_tracker::transport::cleanup_dead_nodes`]).
//!
//! # Protocol (child → game)
//!
//! Each frame is a tag byte, a little-endian `u16` payload length and the
//! payload: tag 1, a sample (80 bytes, the layout of [`TrackerSample`], all
//! fields little-endian); tag 2, a status (UTF-8, at most 1024 bytes; empty
//! means connected); tag 3, a heartbeat (no payload). Anything else is a
//! protocol error and ends that child.

use std::collections::VecDeque;
use std::io::{Read, Write};
use std::os::unix::process::{CommandExt, ExitStatusExt};
use std::process::{Child, Command, ExitCode, ExitStatus, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use lightcone_tracker::{Subscriber, TrackerSample};

/// Tag of a sample frame.
const TAG_SAMPLE: u8 = 1;
/// Tag of a status frame.
const TAG_STATUS: u8 = 2;
/// Tag of a heartbeat frame.
const TAG_HEARTBEAT: u8 = 3;
/// Size of a sample on the wire.
const SAMPLE_BYTES: usize = 80;
/// Longest status text.
const STATUS_BYTES: usize = 1024;

/// How often the child says it is alive.
pub const HEARTBEAT: Duration = Duration::from_millis(100);
/// A child silent this long (a hang in corrupted bookkeeping) is killed.
pub const SILENCE_LIMIT: Duration = Duration::from_secs(2);
/// First wait before starting a new child after one died.
pub const RESPAWN_MIN: Duration = Duration::from_millis(250);
/// Longest wait between starts while children keep dying.
pub const RESPAWN_MAX: Duration = Duration::from_secs(4);
/// Address-space limit of the child, MiB: a corrupted size in shared
/// memory must not make it eat the machine.
pub const MEMORY_LIMIT_MB: u64 = 1024;
/// Frames kept for the game between two polls (the newest).
const INBOX_LIMIT: usize = 4096;
/// The child's default pause between two drains of the subscriber.
pub const DEFAULT_POLL: Duration = Duration::from_micros(100);

/// Encodes a sample as the protocol's 80 bytes.
pub fn encode_sample(s: &TrackerSample) -> [u8; SAMPLE_BYTES] {
    let mut b = [0u8; SAMPLE_BYTES];
    b[0..8].copy_from_slice(&s.timestamp_ns.to_le_bytes());
    b[8..16].copy_from_slice(&s.sequence.to_le_bytes());
    for (i, x) in s.position.iter().chain(&s.orientation).enumerate() {
        b[16 + 8 * i..24 + 8 * i].copy_from_slice(&x.to_le_bytes());
    }
    b[72] = s.valid;
    b
}

/// Decodes 80 bytes into a sample. Any bytes give a sample (its fields
/// may be NaN, unnormalised, anything: the follower validates them).
pub fn decode_sample(b: &[u8; SAMPLE_BYTES]) -> TrackerSample {
    let u64_at = |i: usize| {
        let mut w = [0u8; 8];
        w.copy_from_slice(&b[i..i + 8]);
        w
    };
    let f = |i: usize| f64::from_le_bytes(u64_at(16 + 8 * i));
    TrackerSample {
        timestamp_ns: u64::from_le_bytes(u64_at(0)),
        sequence: u64::from_le_bytes(u64_at(8)),
        position: [f(0), f(1), f(2)],
        orientation: [f(3), f(4), f(5), f(6)],
        valid: b[72],
        _pad: [0; 7],
    }
}

fn write_frame(out: &mut impl Write, tag: u8, payload: &[u8]) -> std::io::Result<()> {
    let len = u16::try_from(payload.len()).unwrap_or(u16::MAX);
    let mut frame = Vec::with_capacity(3 + payload.len());
    frame.push(tag);
    frame.extend_from_slice(&len.to_le_bytes());
    frame.extend_from_slice(&payload[..usize::from(len)]);
    out.write_all(&frame)
}

/// A status text cut to the protocol's limit on a character boundary.
fn status_bytes(text: &str) -> &[u8] {
    let mut end = text.len().min(STATUS_BYTES);
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    &text.as_bytes()[..end]
}

/// The child: `lightcone tracker-bridge --service NAME [--poll-us N]`.
/// Subscribes and forwards until its standard output is closed (the game
/// is gone). Exit status 0 then; 2 for bad arguments.
pub fn child_main(args: &[String]) -> ExitCode {
    let mut service = None;
    let mut poll = DEFAULT_POLL;
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match (a.as_str(), it.next()) {
            ("--service", Some(s)) => service = Some(s.clone()),
            ("--poll-us", Some(n)) => match n.parse::<u64>() {
                Ok(n) if n <= 1_000_000 => poll = Duration::from_micros(n),
                _ => {
                    crate::errln!("lightcone tracker-bridge: --poll-us {n:?}: give 0 … 1000000");
                    return ExitCode::from(2);
                }
            },
            _ => {
                crate::errln!(
                    "lightcone tracker-bridge: usage: --service NAME [--poll-us N] (started by `play --tracker`)"
                );
                return ExitCode::from(2);
            }
        }
    }
    let Some(service) = service else {
        crate::errln!("lightcone tracker-bridge: --service NAME is required");
        return ExitCode::from(2);
    };
    // SAFETY: plain system calls on this process.
    unsafe {
        libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGKILL);
        // Wake from each poll's sleep on time (the default slack of 50 µs
        // would add to every sample's latency).
        libc::prctl(libc::PR_SET_TIMERSLACK, 1 as libc::c_ulong);
        let bytes = MEMORY_LIMIT_MB << 20;
        let limit = libc::rlimit {
            rlim_cur: bytes,
            rlim_max: bytes,
        };
        libc::setrlimit(libc::RLIMIT_AS, &limit);
    }
    if std::os::unix::process::parent_id() == 1 {
        return ExitCode::SUCCESS; // the game is already gone
    }
    lightcone_tracker::transport::quiet_iceoryx_logs();
    match forward(&service, poll, &mut std::io::stdout().lock()) {
        // Only a closed pipe ends the loop: the game is gone or done.
        Err(_) | Ok(()) => ExitCode::SUCCESS,
    }
}

/// The child's loop: open (retrying every second), drain, forward.
fn forward(service: &str, poll: Duration, out: &mut impl Write) -> std::io::Result<()> {
    let mut subscriber: Option<Subscriber> = None;
    let mut retry_at = Instant::now();
    let mut last_status: Option<String> = None;
    let mut beat_at = Instant::now();
    let mut batch = Vec::new();
    loop {
        let now = Instant::now();
        if subscriber.is_none() && now >= retry_at {
            let status = match Subscriber::open(service) {
                Ok(s) => {
                    subscriber = Some(s);
                    String::new()
                }
                Err(e) => {
                    retry_at = now + Duration::from_secs(1);
                    e.to_string()
                }
            };
            if last_status.as_ref() != Some(&status) {
                write_frame(out, TAG_STATUS, status_bytes(&status))?;
                out.flush()?;
                last_status = Some(status);
            }
        }
        if let Some(sub) = &subscriber {
            batch.clear();
            if let Err(e) = sub.drain_into(&mut batch) {
                let status = e.to_string();
                if last_status.as_ref() != Some(&status) {
                    write_frame(out, TAG_STATUS, status_bytes(&status))?;
                    last_status = Some(status);
                }
            } else if last_status.as_ref().is_some_and(|s| !s.is_empty()) {
                write_frame(out, TAG_STATUS, &[])?;
                last_status = Some(String::new());
            }
            for s in &batch {
                write_frame(out, TAG_SAMPLE, &encode_sample(s))?;
            }
            if !batch.is_empty() {
                out.flush()?;
            }
        }
        if now >= beat_at {
            write_frame(out, TAG_HEARTBEAT, &[])?;
            out.flush()?;
            beat_at = now + HEARTBEAT;
        }
        std::thread::sleep(poll);
    }
}

/// What the reading thread hands the game.
#[derive(Default)]
struct Inbox {
    samples: VecDeque<TrackerSample>,
    /// The newest status text (empty: connected), if one came.
    status: Option<String>,
    /// When the last frame of any kind came.
    heard: Option<Instant>,
    /// The pipe ended, or carried something that is not a frame.
    closed: Option<String>,
}

/// Reads frames until the pipe ends or breaks the protocol.
fn read_frames(mut pipe: impl Read, inbox: &Mutex<Inbox>) {
    let lock = || inbox.lock().unwrap_or_else(|e| e.into_inner());
    let reason = loop {
        let mut head = [0u8; 3];
        if pipe.read_exact(&mut head).is_err() {
            break None;
        }
        let len = usize::from(u16::from_le_bytes([head[1], head[2]]));
        let ok = match head[0] {
            TAG_SAMPLE => len == SAMPLE_BYTES,
            TAG_STATUS => len <= STATUS_BYTES,
            TAG_HEARTBEAT => len == 0,
            _ => false,
        };
        if !ok {
            break Some(format!(
                "sent a malformed frame (tag {}, {len} bytes)",
                head[0]
            ));
        }
        let mut payload = vec![0u8; len];
        if pipe.read_exact(&mut payload).is_err() {
            break None;
        }
        let mut inbox = lock();
        inbox.heard = Some(Instant::now());
        match head[0] {
            TAG_SAMPLE => {
                let mut b = [0u8; SAMPLE_BYTES];
                b.copy_from_slice(&payload);
                if inbox.samples.len() >= INBOX_LIMIT {
                    inbox.samples.pop_front();
                }
                inbox.samples.push_back(decode_sample(&b));
            }
            TAG_STATUS => inbox.status = Some(String::from_utf8_lossy(&payload).into_owned()),
            _ => {}
        }
    };
    lock().closed = Some(reason.unwrap_or_else(|| "closed its output".to_owned()));
}

/// How the bridge to the tracker stands.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum BridgeState {
    /// The child runs; `status` is its last word (empty: connected).
    Running {
        /// Why it is not connected, or empty.
        status: String,
    },
    /// The child died (or was killed) and a new one starts at `next`.
    Restarting {
        /// What happened to it.
        reason: String,
    },
}

/// The game's side: a supervised `tracker-bridge` child.
pub struct Bridge {
    make: Box<dyn Fn() -> Command + Send>,
    service: String,
    child: Option<(Child, Arc<Mutex<Inbox>>, Instant)>,
    state: BridgeState,
    respawn_at: Instant,
    backoff: Duration,
    /// Children that died or were killed so far.
    pub deaths: u64,
}

impl std::fmt::Debug for Bridge {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Bridge")
            .field("service", &self.service)
            .field("state", &self.state)
            .field("deaths", &self.deaths)
            .finish_non_exhaustive()
    }
}

/// A command that runs this very program (the game re-executes itself).
pub fn this_program() -> Command {
    match std::env::current_exe() {
        Ok(exe) => Command::new(exe),
        // Spawning fails, and the status says so.
        Err(_) => Command::new("/proc/self/exe"),
    }
}

impl Bridge {
    /// A bridge to `service`, started by `make()` with `tracker-bridge
    /// --service NAME` appended (normally [`this_program`]; tests give the
    /// built binary, or a stand-in that misbehaves).
    pub fn new(service: &str, make: impl Fn() -> Command + Send + 'static) -> Self {
        let mut bridge = Self {
            make: Box::new(make),
            service: service.to_owned(),
            child: None,
            state: BridgeState::Running {
                status: "starting".to_owned(),
            },
            respawn_at: Instant::now(),
            backoff: RESPAWN_MIN,
            deaths: 0,
        };
        bridge.spawn(Instant::now());
        bridge
    }

    fn spawn(&mut self, now: Instant) {
        let mut cmd = (self.make)();
        cmd.args(["tracker-bridge", "--service", &self.service])
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .process_group(0);
        match cmd.spawn() {
            Ok(mut child) => {
                let inbox = Arc::new(Mutex::new(Inbox::default()));
                if let Some(out) = child.stdout.take() {
                    let inbox = Arc::clone(&inbox);
                    std::thread::spawn(move || read_frames(out, &inbox));
                }
                self.child = Some((child, inbox, now));
                self.state = BridgeState::Running {
                    status: "starting".to_owned(),
                };
            }
            Err(e) => self.died(
                now,
                format!("cannot start the tracker's reader process: {e}"),
            ),
        }
    }

    fn died(&mut self, now: Instant, reason: String) {
        self.deaths += 1;
        self.state = BridgeState::Restarting { reason };
        self.respawn_at = now + self.backoff;
        self.backoff = (self.backoff * 2).min(RESPAWN_MAX);
    }

    /// Appends the samples that arrived to `out`; watches the child and
    /// restarts it when needed. Never blocks.
    pub fn poll(&mut self, now: Instant, out: &mut Vec<TrackerSample>) {
        if self.child.is_none() {
            if now >= self.respawn_at {
                self.spawn(now);
            }
            return;
        }
        let Some((child, inbox, started)) = &mut self.child else {
            return;
        };
        let (closed, heard) = {
            let mut inbox = inbox.lock().unwrap_or_else(|e| e.into_inner());
            out.extend(inbox.samples.drain(..));
            if let Some(s) = inbox.status.take() {
                self.state = BridgeState::Running { status: s };
            }
            (inbox.closed.take(), inbox.heard)
        };
        if !out.is_empty() {
            self.backoff = RESPAWN_MIN;
        }
        let silent = now.saturating_duration_since(heard.unwrap_or(*started));
        let problem = match (closed, child.try_wait()) {
            (_, Ok(Some(status))) => Some(describe(status)),
            (Some(why), _) => Some(why),
            (None, _) if silent > SILENCE_LIMIT => Some(format!(
                "stopped answering ({:.1} s silent)",
                silent.as_secs_f64()
            )),
            _ => None,
        };
        if let Some(why) = problem {
            let _ = child.kill();
            let _ = child.wait();
            self.child = None;
            self.died(now, format!("the tracker's reader process {why}"));
        }
    }

    /// Where the bridge stands.
    pub fn state(&self) -> &BridgeState {
        &self.state
    }

    /// The child's process id, while one runs.
    pub fn pid(&self) -> Option<u32> {
        self.child.as_ref().map(|(c, _, _)| c.id())
    }
}

impl Drop for Bridge {
    fn drop(&mut self) {
        if let Some((child, _, _)) = &mut self.child {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

/// "exited with status 3", "was killed by SIGSEGV (signal 11)".
fn describe(status: ExitStatus) -> String {
    match (status.code(), status.signal()) {
        (Some(code), _) => format!("exited with status {code}"),
        (None, Some(sig)) => {
            let name = match sig {
                libc::SIGSEGV => "SIGSEGV",
                libc::SIGBUS => "SIGBUS",
                libc::SIGABRT => "SIGABRT",
                libc::SIGKILL => "SIGKILL",
                libc::SIGILL => "SIGILL",
                libc::SIGFPE => "SIGFPE",
                _ => "a signal",
            };
            format!("was killed by {name} (signal {sig})")
        }
        _ => "ended".to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DQuat, DVec3};

    /// A stand-in child: `sh -c SCRIPT` (the appended arguments become
    /// `$0`, `$1`, … and are ignored).
    fn shell(script: &'static str) -> impl Fn() -> Command + Send + 'static {
        move || {
            let mut c = Command::new("sh");
            c.args(["-c", script]);
            c
        }
    }

    fn wait_for(bridge: &mut Bridge, timeout: Duration, cond: impl Fn(&Bridge) -> bool) -> bool {
        let deadline = Instant::now() + timeout;
        let mut out = Vec::new();
        while Instant::now() < deadline {
            bridge.poll(Instant::now(), &mut out);
            if cond(bridge) {
                return true;
            }
            std::thread::sleep(Duration::from_millis(5));
        }
        false
    }

    #[test]
    fn a_sample_survives_the_wire_bit_for_bit() {
        let s = TrackerSample::new(
            123,
            u64::MAX,
            DVec3::new(1.5, -f64::MIN_POSITIVE, f64::NAN),
            DQuat::from_xyzw(0.1, 0.2, 0.3, 0.9),
            true,
        );
        let d = decode_sample(&encode_sample(&s));
        assert_eq!(d.timestamp_ns, 123);
        assert_eq!(d.sequence, u64::MAX);
        assert_eq!(d.position[0], 1.5);
        assert_eq!(d.position[1], -f64::MIN_POSITIVE);
        assert!(d.position[2].is_nan());
        assert_eq!(d.orientation, s.orientation);
        assert_eq!(d.valid, 1);
    }

    #[test]
    fn frames_are_read_back_and_garbage_ends_the_stream() {
        let mut wire = Vec::new();
        write_frame(&mut wire, TAG_STATUS, b"no service").unwrap();
        write_frame(
            &mut wire,
            TAG_SAMPLE,
            &encode_sample(&TrackerSample::default()),
        )
        .unwrap();
        write_frame(&mut wire, TAG_HEARTBEAT, &[]).unwrap();
        wire.extend_from_slice(&[9, 0, 0]);
        let inbox = Mutex::new(Inbox::default());
        read_frames(&wire[..], &inbox);
        let inbox = inbox.into_inner().unwrap();
        assert_eq!(inbox.samples.len(), 1);
        assert_eq!(inbox.status.as_deref(), Some("no service"));
        assert!(inbox.closed.unwrap().contains("malformed frame (tag 9"));
    }

    #[test]
    fn a_crashing_reader_is_reported_and_restarted() {
        let mut bridge = Bridge::new("x", shell("kill -SEGV $$"));
        assert!(wait_for(&mut bridge, Duration::from_secs(5), |b| b.deaths >= 2));
        match bridge.state() {
            BridgeState::Restarting { reason } => {
                assert!(reason.contains("SIGSEGV"), "{reason}")
            }
            s => panic!("{s:?}"),
        }
    }

    #[test]
    fn a_reader_that_sends_garbage_is_killed() {
        let mut bridge = Bridge::new("x", shell("head -c 5000 /dev/urandom; sleep 30"));
        assert!(wait_for(&mut bridge, Duration::from_secs(5), |b| b.deaths >= 1));
    }

    #[test]
    fn a_silent_reader_is_killed_after_the_limit() {
        let start = Instant::now();
        let mut bridge = Bridge::new("x", shell("exec sleep 30"));
        assert!(wait_for(&mut bridge, Duration::from_secs(6), |b| b.deaths >= 1));
        let waited = start.elapsed();
        // Not before the limit; the bound above is loose for a loaded machine.
        assert!(
            waited >= SILENCE_LIMIT && waited < SILENCE_LIMIT + Duration::from_secs(3),
            "{waited:?}"
        );
        match bridge.state() {
            BridgeState::Restarting { reason } => {
                assert!(reason.contains("stopped answering"), "{reason}")
            }
            s => panic!("{s:?}"),
        }
    }
}
