//! The publisher's command line (`lightcone tracker ARGS`,
//! `lightcone-tracker-publisher ARGS`), read with clap: each option's
//! range is checked as it is read, and the error names the option.

use clap::Parser;

use super::{Args, DTrackSource, VrpnSource};
use crate::DEFAULT_SERVICE_NAME;
use crate::motion::{CsvTrack, Faults, MotionConfig, Path, PoseSource};
use crate::vrpn;

/// Longest `--duration`, s (about 32 years).
pub const MAX_DURATION_S: f64 = 1e9;

/// The options, as clap reads them.
#[derive(Parser, Debug)]
#[command(
    name = "lightcone tracker",
    about = "The head tracker: publishes a simulated or recorded head track, or a real \
             tracking system's (DTrack, VRPN), on an iceoryx2 service.",
    disable_version_flag = true
)]
struct Cli {
    /// The iceoryx2 service name.
    #[arg(long, default_value = DEFAULT_SERVICE_NAME)]
    service: String,
    /// Simulated head path: still, circle, walk, figure8.
    #[arg(long, value_name = "still|circle|walk|figure8", value_parser = path)]
    path: Option<Path>,
    /// Replay a recorded track instead: header `t,x,y,z,qx,qy,qz,qw[,valid]`,
    /// then one row per sample.
    #[arg(long, value_name = "FILE", conflicts_with = "path", value_parser = csv_track)]
    csv: Option<CsvTrack>,
    /// Sample rate, Hz, in (0, 100000].
    #[arg(long, value_name = "HZ", allow_negative_numbers = true, value_parser = rate)]
    rate: Option<f64>,
    /// Gaussian position noise per axis, m (≥ 0).
    #[arg(long, value_name = "METRES", allow_negative_numbers = true, value_parser = noise)]
    noise: Option<f64>,
    /// Noise seed.
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    seed: Option<u64>,
    /// First sequence number (simulates a restarted tracker).
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    first_seq: Option<u64>,
    /// Stop after S seconds, in (0, 1e9] (default: until stopped).
    #[arg(long, value_name = "S", allow_negative_numbers = true, value_parser = duration)]
    duration: Option<f64>,
    /// Stop after N samples.
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    count: Option<u64>,
    /// Fault: every Nth sample NaN.
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    nan_every: Option<u64>,
    /// Fault: swap every Nth pair.
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    reorder_every: Option<u64>,
    /// Fault: send nothing for DURATION s from START s.
    #[arg(long, value_name = "START,DURATION", allow_hyphen_values = true, value_parser = window)]
    stall: Option<(f64, f64)>,
    /// Fault: send `valid = 0` for DURATION s from START s (repeatable).
    #[arg(long, value_name = "START,DURATION", allow_hyphen_values = true, value_parser = window)]
    dropout: Vec<(f64, f64)>,
    /// No messages (malformed DTrack packets are still reported).
    #[arg(long)]
    quiet: bool,
    /// Publish the head from ART DTrack's ASCII UDP output on this port.
    #[arg(long, value_name = "PORT", allow_negative_numbers = true, conflicts_with_all = ["path", "csv"])]
    dtrack_udp: Option<u16>,
    /// The address DTrack's packets are received on (default every
    /// interface, 0.0.0.0).
    #[arg(long, value_name = "ADDR", requires = "dtrack_udp")]
    dtrack_bind: Option<std::net::IpAddr>,
    /// The DTrack body ID of the head.
    #[arg(
        long,
        value_name = "ID",
        default_value_t = 0,
        allow_negative_numbers = true,
        requires = "dtrack_udp"
    )]
    dtrack_body: u32,
    /// Publish the head from a VRPN server's tracker device (default port
    /// 3883; an IPv6 host in brackets).
    #[arg(
        long,
        value_name = "NAME@HOST[:PORT]",
        value_parser = vrpn_device,
        conflicts_with_all = ["path", "csv", "dtrack_udp"]
    )]
    vrpn: Option<vrpn::Device>,
    /// The VRPN device's sensor that is the head (≥ 0).
    #[arg(
        long,
        value_name = "N",
        default_value_t = 0,
        allow_negative_numbers = true,
        value_parser = sensor,
        requires = "vrpn"
    )]
    vrpn_sensor: i32,
}

fn number<T: std::str::FromStr>(v: &str) -> Result<T, String> {
    v.trim()
        .parse()
        .map_err(|_| format!("`{v}` is not a valid number"))
}

fn path(v: &str) -> Result<Path, String> {
    Path::by_name(v).ok_or_else(|| format!("unknown path `{v}` (still, circle, walk, figure8)"))
}

fn csv_track(v: &str) -> Result<CsvTrack, String> {
    CsvTrack::from_path(v).map_err(|e| e.to_string())
}

fn rate(v: &str) -> Result<f64, String> {
    let r: f64 = number(v)?;
    if r.is_finite() && r > 0.0 && r <= 100_000.0 {
        Ok(r)
    } else {
        Err(format!("{r} must be in (0, 100000] Hz"))
    }
}

fn noise(v: &str) -> Result<f64, String> {
    let n: f64 = number(v)?;
    if n.is_finite() && n >= 0.0 {
        Ok(n)
    } else {
        Err(format!("{n} must be >= 0"))
    }
}

fn duration(v: &str) -> Result<f64, String> {
    let d: f64 = number(v)?;
    if d.is_finite() && d > 0.0 && d <= MAX_DURATION_S {
        Ok(d)
    } else {
        Err(format!(
            "{v} must be seconds in (0, {MAX_DURATION_S:e}] (leave it out to publish until stopped)"
        ))
    }
}

fn window(v: &str) -> Result<(f64, f64), String> {
    let (a, b) = v
        .split_once(',')
        .ok_or_else(|| format!("expected START,DURATION, got `{v}`"))?;
    let (start, dur): (f64, f64) = (number(a)?, number(b)?);
    if start.is_finite() && dur.is_finite() && dur >= 0.0 {
        Ok((start, dur))
    } else {
        Err(format!("`{v}` must be finite with DURATION >= 0"))
    }
}

fn vrpn_device(v: &str) -> Result<vrpn::Device, String> {
    vrpn::Device::parse(v)
}

fn sensor(v: &str) -> Result<i32, String> {
    let s: i32 = number(v)?;
    if s >= 0 {
        Ok(s)
    } else {
        Err(format!("{v} must be >= 0"))
    }
}

/// The options in one line, as `lightcone tracker --help` prints them
/// (the same as clap's [`usage`]).
pub const USAGE: &str = "options: [--service NAME] \
[--path still|circle|walk|figure8] [--csv FILE] [--rate HZ] [--noise METRES] [--seed N] \
[--first-seq N] [--duration S] [--count N] [--nan-every N] [--reorder-every N] \
[--stall START,DURATION] [--dropout START,DURATION]... [--quiet] \
[--dtrack-udp PORT [--dtrack-bind ADDR] [--dtrack-body ID]] \
[--vrpn NAME@HOST[:PORT] [--vrpn-sensor N]]";

/// The options' help, for `--help`.
#[must_use]
pub fn usage() -> String {
    use clap::CommandFactory;
    Cli::command().render_help().to_string()
}

/// Parses the options (without the program name).
///
/// # Errors
/// clap's message naming the option and what was wrong (an unknown
/// option, a missing value, a value out of its range, two sources), or
/// the help for `--help`.
pub fn parse_args(argv: impl IntoIterator<Item = String>) -> Result<Args, String> {
    let cli = Cli::try_parse_from(std::iter::once("lightcone tracker".to_owned()).chain(argv))
        .map_err(|e| e.render().to_string().trim_end().to_owned())?;
    let source = match (cli.csv, cli.path) {
        (Some(track), _) => PoseSource::Replay(track),
        (None, Some(p)) => PoseSource::Path(p),
        (None, None) => PoseSource::Path(Path::by_name("circle").ok_or("no circle path")?),
    };
    let defaults = MotionConfig::default();
    let config = MotionConfig {
        source,
        noise_std_m: cli.noise.unwrap_or(defaults.noise_std_m),
        seed: cli.seed.unwrap_or(defaults.seed),
        rate_hz: cli.rate.unwrap_or(defaults.rate_hz),
        first_sequence: cli.first_seq.unwrap_or(defaults.first_sequence),
        faults: Faults {
            nan_every: cli.nan_every,
            reorder_every: cli.reorder_every,
            stall: cli.stall,
            dropouts: cli.dropout,
        },
    };
    Ok(Args {
        service: cli.service,
        config,
        duration: cli.duration,
        count: cli.count,
        quiet: cli.quiet,
        dtrack: cli.dtrack_udp.map(|port| DTrackSource {
            bind: std::net::SocketAddr::new(
                cli.dtrack_bind
                    .unwrap_or(std::net::IpAddr::from([0, 0, 0, 0])),
                port,
            ),
            body: cli.dtrack_body,
        }),
        vrpn: cli.vrpn.map(|device| VrpnSource {
            device,
            sensor: cli.vrpn_sensor,
        }),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(list: &[&str]) -> Result<Args, String> {
        parse_args(list.iter().map(|s| (*s).to_owned()))
    }

    #[test]
    fn a_vrpn_source_is_named_and_checked() {
        let a = args(&["--vrpn", "Head@tracking-pc:3900", "--vrpn-sensor", "2"]).unwrap();
        let v = a.vrpn.expect("a VRPN source");
        assert_eq!(v.device.to_string(), "Head@tracking-pc:3900");
        assert_eq!(v.sensor, 2);
        for (bad, says) in [
            (&["--vrpn", "Head"][..], "`Head` is not NAME@HOST"),
            (
                &["--vrpn", "Head@h", "--vrpn-sensor", "-1"][..],
                "-1 must be >= 0",
            ),
            (
                &["--vrpn", "Head@h", "--dtrack-udp", "5000"][..],
                "cannot be used with",
            ),
            (&["--vrpn-sensor", "1"][..], "--vrpn <NAME@HOST[:PORT]>"),
        ] {
            let e = args(bad).map(|_| ()).unwrap_err();
            assert!(e.contains(says), "{bad:?}: {e}");
        }
    }

    #[test]
    fn every_option_is_read_and_its_range_checked() {
        let a = args(&[
            "--service",
            "s/1",
            "--path",
            "walk",
            "--rate",
            "250",
            "--noise",
            "0.001",
            "--seed",
            "7",
            "--first-seq",
            "3",
            "--duration",
            "2.5",
            "--count",
            "9",
            "--nan-every",
            "5",
            "--reorder-every",
            "6",
            "--stall",
            "1,0.5",
            "--dropout",
            "0,0.1",
            "--dropout",
            "-1,2",
            "--quiet",
        ])
        .unwrap();
        assert_eq!(a.service, "s/1");
        assert_eq!(
            a.config.source,
            PoseSource::Path(Path::by_name("walk").unwrap())
        );
        assert_eq!((a.config.rate_hz, a.config.noise_std_m), (250.0, 0.001));
        assert_eq!((a.config.seed, a.config.first_sequence), (7, 3));
        assert_eq!((a.duration, a.count, a.quiet), (Some(2.5), Some(9), true));
        let f = &a.config.faults;
        assert_eq!((f.nan_every, f.reorder_every), (Some(5), Some(6)));
        assert_eq!(f.stall, Some((1.0, 0.5)));
        assert_eq!(f.dropouts, [(0.0, 0.1), (-1.0, 2.0)]);
        let d = args(&["--dtrack-udp", "5000", "--dtrack-body", "2"]).unwrap();
        let d = d.dtrack.expect("a DTrack source");
        assert_eq!((d.bind.to_string(), d.body), ("0.0.0.0:5000".to_owned(), 2));
        let defaults = args(&[]).unwrap();
        assert_eq!(defaults.service, DEFAULT_SERVICE_NAME);
        assert_eq!(
            defaults.config.source,
            PoseSource::Path(Path::by_name("circle").unwrap())
        );
        for (bad, says) in [
            (
                &["--duration", "nan"][..],
                "nan must be seconds in (0, 1e9]",
            ),
            (&["--duration", "-1"][..], "-1 must be seconds in (0, 1e9]"),
            (&["--duration", "1e10"][..], "must be seconds in (0, 1e9]"),
            (&["--rate", "0"][..], "0 must be in (0, 100000] Hz"),
            (&["--noise", "-1"][..], "must be >= 0"),
            (&["--stall", "1"][..], "expected START,DURATION, got `1`"),
            (
                &["--dropout", "1,-2"][..],
                "must be finite with DURATION >= 0",
            ),
            (&["--path", "spiral"][..], "unknown path `spiral`"),
            (&["--seed", "x"][..], "--seed <N>"),
            (
                &["--count", "-3"][..],
                "invalid value '-3' for '--count <N>'",
            ),
            (&["--rate", "-5"][..], "-5 must be in (0, 100000] Hz"),
            (&["--bogus"][..], "unexpected argument '--bogus'"),
            (&["--rate"][..], "a value is required for '--rate <HZ>'"),
            (&["--dtrack-udp", "70000"][..], "--dtrack-udp <PORT>"),
            (&["--dtrack-body", "1"][..], "--dtrack-udp <PORT>"),
            (
                &["--csv", "/no/such.csv"][..],
                "cannot read track file /no/such.csv",
            ),
        ] {
            let e = args(bad).map(|_| ()).unwrap_err();
            assert!(e.contains(says), "{bad:?}: {e}");
        }
        assert!(usage().contains("--dtrack-udp <PORT>"), "{}", usage());
    }
}
