//! The simulated head tracker: publishes a generated or replayed head track
//! on an iceoryx2 service, with optional fault injection. `lightcone
//! tracker ARGS` and `lightcone-tracker-publisher ARGS` both run this.
//!
//! ```text
//! [--service NAME] [--path still|circle|walk|figure8]
//!     [--csv FILE] [--rate HZ] [--noise METRES] [--seed N] [--first-seq N]
//!     [--duration S] [--count N] [--nan-every N] [--reorder-every N]
//!     [--stall START,DURATION] [--dropout START,DURATION]... [--quiet]
//!     [--dtrack-udp PORT [--dtrack-bind ADDR] [--dtrack-body ID]]
//!     [--vrpn NAME@HOST[:PORT] [--vrpn-sensor N]]
//! ```
//!
//! With `--dtrack-udp` the samples come from a real tracking system instead:
//! ART DTrack's ASCII UDP output ([`crate::dtrack`]), one sample per packet,
//! the chosen body's pose (a packet without it: a sample with no fix,
//! holding the last pose). A malformed packet is reported on stderr with
//! its content and dropped; the publisher keeps listening.
//!
//! With `--vrpn` they come from a VRPN server over TCP ([`crate::vrpn`]):
//! one sample per `Pos_Quat` report of the named device's sensor. A report
//! that is not finite is reported with its content and dropped; a
//! connection that fails, closes, stays silent for 5 s or loses its
//! framing is reported and made again (every second, every address of the
//! host, IPv4 first), the game's follower meanwhile seeing the tracker go
//! stale.
//!
//! The command line is read with clap ([`parse_args`]).
//!
//! Stop it with Ctrl-C or kill: a killed publisher's shared-memory resources
//! are reclaimed by the next iceoryx2 node created on the machine.

mod args;

pub use args::{MAX_DURATION_S, USAGE, parse_args, usage};

use crate::motion::{MotionConfig, MotionGenerator};
use crate::transport::quiet_iceoryx_logs;
use crate::{Publisher, TrackerSample, dtrack, unix_now_ns, vrpn};
use std::time::{Duration, Instant};

/// What to publish, and for how long.
pub struct Args {
    /// The iceoryx2 service name.
    pub service: String,
    /// The motion, noise and faults.
    pub config: MotionConfig,
    /// Stop after this many seconds.
    pub duration: Option<f64>,
    /// Stop after this many samples.
    pub count: Option<u64>,
    /// No messages on stderr.
    pub quiet: bool,
    /// Read poses from DTrack's UDP output instead of the motion source.
    pub dtrack: Option<DTrackSource>,
    /// Read poses from a VRPN server instead of the motion source.
    pub vrpn: Option<VrpnSource>,
}

/// Which VRPN device and sensor is the head.
#[derive(Clone, Debug, PartialEq)]
pub struct VrpnSource {
    /// The tracker device and its server.
    pub device: vrpn::Device,
    /// The device's sensor that is the head (from 0).
    pub sensor: i32,
}

/// Where DTrack's packets arrive and which body is the head.
#[derive(Clone, Debug, PartialEq)]
pub struct DTrackSource {
    /// Address and port to listen on.
    pub bind: std::net::SocketAddr,
    /// The head's DTrack body ID (from 0).
    pub body: u32,
}

/// Publishes until the duration or count is reached (forever without
/// either). Returns the number of samples sent.
pub fn run(args: Args) -> Result<u64, String> {
    run_until(args, &|| false)
}

/// As [`run`], and also stops (cleanly, the service closed) as soon as
/// `stop()` says so (Ctrl-C), checked every period.
pub fn run_until(args: Args, stop: &dyn Fn() -> bool) -> Result<u64, String> {
    if args.quiet {
        quiet_iceoryx_logs();
    }
    let publisher = Publisher::open(&args.service).map_err(|e| e.to_string())?;
    if let Some(source) = args.dtrack.clone() {
        return run_dtrack(&args, &source, &publisher, stop);
    }
    if let Some(source) = args.vrpn.clone() {
        return run_vrpn(&args, &source, &publisher, stop);
    }
    let mut generator = MotionGenerator::new(args.config);
    let period = Duration::from_secs_f64(generator.period_s());
    if !args.quiet {
        eprintln!(
            "lightcone tracker: publishing on {:?} at {:.0} Hz",
            args.service,
            1.0 / generator.period_s()
        );
    }
    let start = Instant::now();
    let mut next = start;
    let mut sent: u64 = 0;
    let mut consecutive_errors = 0u32;
    loop {
        if stop() {
            break;
        }
        if let Some(d) = args.duration
            && start.elapsed().as_secs_f64() >= d
        {
            break;
        }
        if let Some(c) = args.count
            && sent >= c
        {
            break;
        }
        for sample in generator.tick(unix_now_ns()) {
            match publisher.send(&sample) {
                Ok(_) => {
                    sent += 1;
                    consecutive_errors = 0;
                }
                Err(e) => {
                    consecutive_errors += 1;
                    eprintln!("lightcone tracker: {e}");
                    if consecutive_errors > 100 {
                        return Err(format!("giving up after 100 failed sends: {e}"));
                    }
                }
            }
        }
        // Absolute schedule: no drift; if we fell behind by more than one
        // period, resynchronise instead of bursting.
        next += period;
        let now = Instant::now();
        if next > now {
            // In slices, so that `stop` is seen within 50 ms at any rate.
            let mut left = next - now;
            while !left.is_zero() && !stop() {
                let nap = left.min(Duration::from_millis(50));
                std::thread::sleep(nap);
                left -= nap;
            }
        } else if now - next > period {
            next = now;
        }
    }
    if !args.quiet {
        eprintln!("lightcone tracker: sent {sent} samples");
    }
    Ok(sent)
}

/// Malformed packets reported one by one; after that, one line per 1 000.
const REPORTED_PACKETS: u64 = 20;

/// Publishes one sample per DTrack packet until the duration or count is
/// reached or `stop()` (checked every 50 ms).
fn run_dtrack(
    args: &Args,
    source: &DTrackSource,
    publisher: &Publisher,
    stop: &dyn Fn() -> bool,
) -> Result<u64, String> {
    let socket = std::net::UdpSocket::bind(source.bind)
        .map_err(|e| format!("--dtrack-udp: cannot listen on {}: {e}", source.bind))?;
    socket
        .set_read_timeout(Some(Duration::from_millis(50)))
        .map_err(|e| format!("--dtrack-udp: {e}"))?;
    if !args.quiet {
        eprintln!(
            "lightcone tracker: publishing DTrack body {} from UDP {} on {:?}",
            source.body, source.bind, args.service
        );
    }
    let start = Instant::now();
    let mut buf = vec![0u8; dtrack::MAX_PACKET];
    let (mut sent, mut dropped, mut own_sequence) = (0u64, 0u64, 0u64);
    let mut last = TrackerSample::default();
    loop {
        if over(args, start, sent, stop) {
            break;
        }
        let (n, from) = match socket.recv_from(&mut buf) {
            Ok(got) => got,
            Err(e)
                if matches!(
                    e.kind(),
                    std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
                ) =>
            {
                continue;
            }
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(format!("--dtrack-udp: {e}")),
        };
        let packet = match dtrack::parse(&buf[..n]) {
            Ok(p) => p,
            Err(e) => {
                dropped += 1;
                if dropped <= REPORTED_PACKETS {
                    eprintln!(
                        "lightcone tracker: dropped a malformed DTrack packet from {from}: {e}; \
                         content: \"{}\"",
                        dtrack::show_content(&buf[..n], 200)
                    );
                } else if dropped % 1000 == 0 {
                    eprintln!(
                        "lightcone tracker: {dropped} malformed DTrack packets dropped so far"
                    );
                }
                continue;
            }
        };
        own_sequence += 1;
        let sequence = packet.frame.unwrap_or(own_sequence);
        let sample = match packet.bodies.iter().find(|b| b.id == source.body) {
            Some(b) => TrackerSample::new(
                unix_now_ns(),
                sequence,
                b.position,
                dtrack::quaternion(b.rotation),
                true,
            ),
            // Not tracked in this frame: no fix, the last pose held.
            None => TrackerSample {
                timestamp_ns: unix_now_ns(),
                sequence,
                valid: 0,
                ..last
            },
        };
        match publisher.send(&sample) {
            Ok(_) => {
                sent += 1;
                last = sample;
            }
            Err(e) => eprintln!("lightcone tracker: {e}"),
        }
    }
    if !args.quiet {
        eprintln!("lightcone tracker: sent {sent} samples, dropped {dropped} malformed packets");
    }
    Ok(sent)
}

/// How long to wait between attempts to reach a VRPN server.
const VRPN_RETRY: Duration = Duration::from_secs(1);

/// Whether the run is over: stopped, or its duration or count reached.
fn over(args: &Args, start: Instant, sent: u64, stop: &dyn Fn() -> bool) -> bool {
    stop()
        || args
            .duration
            .is_some_and(|d| start.elapsed().as_secs_f64() >= d)
        || args.count.is_some_and(|c| sent >= c)
}

/// Publishes one sample per `Pos_Quat` report of the chosen device and
/// sensor until the duration or count is reached or `stop()` (checked every
/// 50 ms), connecting again whenever the connection is lost.
fn run_vrpn(
    args: &Args,
    source: &VrpnSource,
    publisher: &Publisher,
    stop: &dyn Fn() -> bool,
) -> Result<u64, String> {
    if !args.quiet {
        eprintln!(
            "lightcone tracker: publishing VRPN {} sensor {} on {:?}",
            source.device, source.sensor, args.service
        );
    }
    let start = Instant::now();
    let mut counts = VrpnCounts::default();
    while !over(args, start, counts.sent, stop) {
        counts.connections += 1;
        let why = match vrpn_connection(args, source, publisher, stop, start, &mut counts) {
            Ok(()) => continue, // over
            Err(why) => why,
        };
        eprintln!(
            "lightcone tracker: VRPN {}: {why}; connecting again in {} s",
            source.device,
            VRPN_RETRY.as_secs()
        );
        let until = Instant::now() + VRPN_RETRY;
        while Instant::now() < until && !over(args, start, counts.sent, stop) {
            std::thread::sleep(Duration::from_millis(50));
        }
    }
    if !args.quiet {
        eprintln!(
            "lightcone tracker: sent {} samples, refused {} reports, {} connection attempts",
            counts.sent, counts.refused, counts.connections
        );
    }
    Ok(counts.sent)
}

/// What a VRPN run did, over all its connections.
#[derive(Default)]
struct VrpnCounts {
    sent: u64,
    refused: u64,
    /// Connection attempts, made or failed.
    connections: u64,
    /// The samples' sequence: one per report taken, never restarting (the
    /// follower drops samples whose sequence goes back).
    sequence: u64,
}

/// One connection to the VRPN server: `Ok` when the run is over, else why
/// the connection ended.
fn vrpn_connection(
    args: &Args,
    source: &VrpnSource,
    publisher: &Publisher,
    stop: &dyn Fn() -> bool,
    start: Instant,
    counts: &mut VrpnCounts,
) -> Result<(), String> {
    use std::io::{Read, Write};
    use std::net::ToSocketAddrs;
    let device = &source.device;
    // Every address the name has, IPv4 first (VRPN's servers listen on
    // IPv4; `localhost` may resolve to ::1 first).
    let mut addrs: Vec<std::net::SocketAddr> = (device.host.as_str(), device.port)
        .to_socket_addrs()
        .map_err(|e| format!("cannot resolve {}: {e}", device.host))?
        .collect();
    addrs.sort_by_key(|a| a.is_ipv6());
    let mut failed = Vec::new();
    let mut connected = None;
    for a in &addrs {
        match std::net::TcpStream::connect_timeout(a, Duration::from_secs(2)) {
            Ok(tcp) => {
                connected = Some((tcp, *a));
                break;
            }
            Err(e) => failed.push(format!("{a}: {e}")),
        }
    }
    let Some((mut tcp, addr)) = connected else {
        return Err(format!(
            "cannot connect ({})",
            if failed.is_empty() {
                format!("{} has no address", device.host)
            } else {
                failed.join("; ")
            }
        ));
    };
    let _ = tcp.set_nodelay(true);
    tcp.set_read_timeout(Some(Duration::from_millis(50)))
        .map_err(|e| e.to_string())?;
    tcp.write_all(&vrpn::cookie())
        .map_err(|e| format!("cannot send the cookie: {e}"))?;
    let mut stream = vrpn::Stream::following(&device.name);
    let mut cookie: Vec<u8> = Vec::with_capacity(vrpn::COOKIE_LEN);
    let mut buf = vec![0u8; 64 * 1024];
    let shaken = Instant::now();
    // A tracker reports many times a second: a connection silent for
    // longer than this is taken as lost (a server whose machine stopped
    // sends no reset).
    const SILENT: Duration = Duration::from_secs(5);
    let mut heard = Instant::now();
    loop {
        if over(args, start, counts.sent, stop) {
            return Ok(());
        }
        let n = match tcp.read(&mut buf) {
            Ok(0) => return Err("the server closed the connection".to_owned()),
            Ok(n) => {
                heard = Instant::now();
                n
            }
            Err(e)
                if matches!(
                    e.kind(),
                    std::io::ErrorKind::WouldBlock
                        | std::io::ErrorKind::TimedOut
                        | std::io::ErrorKind::Interrupted
                ) =>
            {
                if cookie.len() < vrpn::COOKIE_LEN && shaken.elapsed() > SILENT {
                    return Err("no cookie from the server within 5 s".to_owned());
                }
                if heard.elapsed() > SILENT {
                    return Err("nothing from the server for 5 s".to_owned());
                }
                continue;
            }
            Err(e) => return Err(format!("cannot read: {e}")),
        };
        let mut bytes = &buf[..n];
        if cookie.len() < vrpn::COOKIE_LEN {
            let take = (vrpn::COOKIE_LEN - cookie.len()).min(bytes.len());
            cookie.extend_from_slice(&bytes[..take]);
            bytes = &bytes[take..];
            if cookie.len() == vrpn::COOKIE_LEN {
                let (major, minor) = vrpn::check_cookie(&cookie).map_err(|e| e.to_string())?;
                if !args.quiet {
                    eprintln!(
                        "lightcone tracker: connected to VRPN {major:02}.{minor:02} at {addr}"
                    );
                }
            }
        }
        stream.push(bytes);
        while let Some(event) = stream
            .next_event()
            .map_err(|e| format!("lost the framing: {e}"))?
        {
            match event {
                vrpn::Event::Pose { sender, pose }
                    if sender == device.name && pose.sensor == source.sensor =>
                {
                    counts.sequence += 1;
                    let sample = TrackerSample::new(
                        unix_now_ns(),
                        counts.sequence,
                        pose.position,
                        pose.orientation,
                        true,
                    );
                    match publisher.send(&sample) {
                        Ok(_) => counts.sent += 1,
                        Err(e) => eprintln!("lightcone tracker: {e}"),
                    }
                }
                vrpn::Event::Pose { .. } => {} // another device or sensor
                vrpn::Event::Refused(e) => {
                    counts.refused += 1;
                    if counts.refused <= REPORTED_PACKETS {
                        let what = if e.field.starts_with("description") {
                            "description"
                        } else {
                            "report"
                        };
                        eprintln!("lightcone tracker: dropped a malformed VRPN {what}: {e}");
                    } else if counts.refused.is_multiple_of(1000) {
                        eprintln!(
                            "lightcone tracker: {} malformed VRPN reports and descriptions dropped",
                            counts.refused
                        );
                    }
                }
                vrpn::Event::Disconnect => return Err("the server disconnected".to_owned()),
            }
        }
    }
}
