//! Simulated (or replayed) head motion for the tracker publisher.
//!
//! Why: the CAVE and a real tracker are not always available, and the game's
//! fault handling must be exercised deterministically. [`MotionGenerator`]
//! produces the stream of [`TrackerSample`]s a tracker would, from either a
//! parametric [`Path`] or a recorded CSV track ([`CsvTrack`]), with seeded
//! Gaussian noise, dropouts (`valid = 0`) and injectable faults (NaN
//! positions, swapped pairs, stalls). Same seed and same tick sequence give
//! bit-identical output.
//!
//! Tracker space conventions used by the paths: metres, **y up**, the CAVE
//! floor at y = 0, a standing head around y = 1.7.
//!
//! # CSV format
//!
//! ```text
//! t,x,y,z,qx,qy,qz,qw,valid
//! 0.000,0.0,1.7,0.0,0,0,0,1,1
//! 0.010,0.001,1.7,0.0,0,0,0,1,1
//! ```
//!
//! A header line is required (`valid` column optional; missing means valid).
//! `t` is seconds from the start of the recording and must not decrease.
//! Blank lines and lines starting with `#` are skipped; a field may be
//! quoted. Records are split by the `csv` crate; errors name the 1-based
//! line number and the field.

use crate::sample::TrackerSample;
use glam::{DQuat, DVec3};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::{Rng as _, SeedableRng};
use std::f64::consts::TAU;
use std::path::Path as FsPath;
use thiserror::Error;

/// Seeded pseudo-random numbers for simulated sensor noise: the
/// workspace's one generator (xoshiro256++, `rand_xoshiro`, seeded by
/// `SeedableRng::seed_from_u64`), with normal draws by Box-Muller.
#[derive(Debug, Clone)]
pub struct Prng {
    rng: Xoshiro256PlusPlus,
    spare_gaussian: Option<f64>,
}

impl Prng {
    /// A generator with the given seed (any value, including 0, is fine).
    #[must_use]
    pub fn new(seed: u64) -> Self {
        Self {
            rng: Xoshiro256PlusPlus::seed_from_u64(seed),
            spare_gaussian: None,
        }
    }

    /// Next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.rng.next_u64()
    }

    /// Uniform in `[0, 1)` with 53 bits of precision.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Standard normal (mean 0, sd 1) by the Box-Muller transform.
    pub fn gaussian(&mut self) -> f64 {
        if let Some(g) = self.spare_gaussian.take() {
            return g;
        }
        // u1 in (0, 1] so ln(u1) is finite.
        let u1 = 1.0 - self.next_f64();
        let u2 = self.next_f64();
        let r = (-2.0 * u1.ln()).sqrt();
        let (s, c) = (TAU * u2).sin_cos();
        self.spare_gaussian = Some(r * s);
        r * c
    }
}

/// A parametric head path in tracker space (metres, y up).
#[derive(Debug, Clone, PartialEq)]
pub enum Path {
    /// Standing still at `position`, looking down -z.
    Still {
        /// Head position.
        position: DVec3,
    },
    /// Walking a horizontal circle around `center`, always facing it.
    Circle {
        /// Circle centre (its y is the head height).
        center: DVec3,
        /// Radius in metres.
        radius: f64,
        /// Seconds per lap.
        period_s: f64,
    },
    /// Walking back and forth along x (sinusoidally), facing -z.
    Walk {
        /// Middle of the walk.
        center: DVec3,
        /// Distance from the middle to either end.
        half_length: f64,
        /// Seconds for one there-and-back.
        period_s: f64,
    },
    /// A horizontal figure eight (lemniscate of Gerono), heading along the
    /// direction of travel.
    Figure8 {
        /// Crossing point.
        center: DVec3,
        /// Half-width along x (the z extent is half of that).
        size: f64,
        /// Seconds per full eight.
        period_s: f64,
    },
}

impl Path {
    /// Looks up a path by CLI name with typical CAVE parameters:
    /// `still`, `circle` (r 0.5 m, 8 s), `walk` (±1 m, 6 s), `figure8`
    /// (0.8 m, 10 s), all at head height 1.7 m around the CAVE centre.
    #[must_use]
    pub fn by_name(name: &str) -> Option<Self> {
        let c = DVec3::new(0.0, 1.7, 0.0);
        match name {
            "still" => Some(Self::Still { position: c }),
            "circle" => Some(Self::Circle {
                center: c,
                radius: 0.5,
                period_s: 8.0,
            }),
            "walk" => Some(Self::Walk {
                center: c,
                half_length: 1.0,
                period_s: 6.0,
            }),
            "figure8" => Some(Self::Figure8 {
                center: c,
                size: 0.8,
                period_s: 10.0,
            }),
            _ => None,
        }
    }

    /// Noise-free pose at time `t` seconds. A non-positive or non-finite
    /// period freezes the path at its start.
    #[must_use]
    pub fn pose_at(&self, t: f64) -> (DVec3, DQuat) {
        let phase = |period: f64| {
            if period.is_finite() && period > 0.0 && t.is_finite() {
                TAU * t / period
            } else {
                0.0
            }
        };
        match *self {
            Path::Still { position } => (position, DQuat::IDENTITY),
            Path::Circle {
                center,
                radius,
                period_s,
            } => {
                let a = phase(period_s);
                let offset = DVec3::new(radius * a.cos(), 0.0, radius * a.sin());
                // Facing the centre: local -z points along -offset.
                let yaw = offset.x.atan2(offset.z);
                (center + offset, DQuat::from_rotation_y(yaw))
            }
            Path::Walk {
                center,
                half_length,
                period_s,
            } => {
                let a = phase(period_s);
                (
                    center + DVec3::new(half_length * a.sin(), 0.0, 0.0),
                    DQuat::IDENTITY,
                )
            }
            Path::Figure8 {
                center,
                size,
                period_s,
            } => {
                let a = phase(period_s);
                let offset = DVec3::new(size * a.sin(), 0.0, size * a.sin() * a.cos());
                // Velocity direction (derivative of the offset w.r.t. a).
                let vx = size * a.cos();
                let vz = size * (2.0 * a).cos();
                // Heading: local -z along the velocity.
                let yaw = (-vx).atan2(-vz);
                (center + offset, DQuat::from_rotation_y(yaw))
            }
        }
    }
}

/// Errors reading a recorded CSV track.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CsvError {
    /// The file could not be read.
    #[error("cannot read track file {path}: {message}")]
    Io {
        /// The path given.
        path: String,
        /// The OS error.
        message: String,
    },
    /// The first non-comment line is not the expected header.
    #[error("line {line}: bad header: expected `t,x,y,z,qx,qy,qz,qw[,valid]`, found `{found}`")]
    Header {
        /// 1-based line number.
        line: usize,
        /// The line as found.
        found: String,
    },
    /// A data field could not be used.
    #[error("line {line}: field `{field}`: {message}")]
    Field {
        /// 1-based line number.
        line: usize,
        /// Column name from the header.
        field: &'static str,
        /// What is wrong.
        message: String,
    },
    /// The text does not split into CSV records.
    #[error("line {line}: {message}")]
    Syntax {
        /// 1-based line number.
        line: usize,
        /// The csv crate's message.
        message: String,
    },
    /// A data line has the wrong number of fields.
    #[error("line {line}: expected {expected} fields, found {found}")]
    FieldCount {
        /// 1-based line number.
        line: usize,
        /// Columns in the header.
        expected: usize,
        /// Columns on this line.
        found: usize,
    },
    /// No data lines.
    #[error("track has no samples")]
    Empty,
}

/// One row of a recorded track.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackRow {
    /// Seconds from the start of the recording.
    pub t: f64,
    /// Position (metres, tracker space).
    pub position: DVec3,
    /// Orientation as recorded (not normalised: faults are replayed as-is).
    pub orientation: DQuat,
    /// Whether the tracker had a fix.
    pub valid: bool,
}

const CSV_FIELDS: [&str; 9] = ["t", "x", "y", "z", "qx", "qy", "qz", "qw", "valid"];

/// The 1-based line of `text` a record that the csv crate says starts at
/// byte `offset` is on: the line of `offset`, past the blank and comment
/// lines the reader skipped from there.
fn line_at(text: &str, offset: u64) -> usize {
    let end = usize::try_from(offset)
        .unwrap_or(usize::MAX)
        .min(text.len());
    let mut line = 1 + text.as_bytes()[..end]
        .iter()
        .filter(|b| **b == b'\n')
        .count();
    let mut rest = text.get(end..).unwrap_or("");
    while let Some((first, after)) = rest.split_once('\n') {
        let first = first.trim();
        if !(first.is_empty() || first.starts_with('#')) {
            break;
        }
        line += 1;
        rest = after;
    }
    line
}

/// A recorded head track, replayable by [`MotionGenerator`].
#[derive(Debug, Clone, PartialEq)]
pub struct CsvTrack {
    rows: Vec<TrackRow>,
}

impl CsvTrack {
    /// Parses CSV text (see the module docs for the format).
    pub fn parse(text: &str) -> Result<Self, CsvError> {
        // The csv crate splits the records (quoting, CR LF, `#` comment
        // lines, blank lines); the fields' meaning is checked here, each
        // error at the record's line.
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(false)
            .flexible(true)
            .trim(csv::Trim::All)
            .comment(Some(b'#'))
            .from_reader(text.as_bytes());
        let mut columns: Option<usize> = None;
        let mut rows: Vec<TrackRow> = Vec::new();
        let mut record = csv::StringRecord::new();
        loop {
            let more = reader
                .read_record(&mut record)
                .map_err(|e| CsvError::Syntax {
                    line: line_at(text, e.position().map_or(0, |p| p.byte())),
                    message: e.to_string(),
                })?;
            if !more {
                break;
            }
            // From the record's byte offset: the csv crate's own line count
            // skips the comment lines.
            let line_no = line_at(text, record.position().map_or(0, |p| p.byte()));
            let fields: Vec<&str> = record.iter().collect();
            if fields.iter().all(|f| f.is_empty()) {
                continue;
            }
            let Some(ncols) = columns else {
                let ok = (fields.len() == 8 || fields.len() == 9)
                    && fields
                        .iter()
                        .zip(CSV_FIELDS.iter())
                        .all(|(a, b)| a.eq_ignore_ascii_case(b));
                if !ok {
                    return Err(CsvError::Header {
                        line: line_no,
                        found: fields.join(","),
                    });
                }
                columns = Some(fields.len());
                continue;
            };
            if fields.len() != ncols {
                return Err(CsvError::FieldCount {
                    line: line_no,
                    expected: ncols,
                    found: fields.len(),
                });
            }
            let mut vals = [0.0f64; 8];
            for (i, v) in vals.iter_mut().enumerate() {
                let s = fields[i];
                let parsed: f64 = s.parse().map_err(|_| CsvError::Field {
                    line: line_no,
                    field: CSV_FIELDS[i],
                    message: format!("`{s}` is not a number"),
                })?;
                // NaN/inf in a pose field is a fault worth replaying, but
                // time must be usable.
                if i == 0 && !parsed.is_finite() {
                    return Err(CsvError::Field {
                        line: line_no,
                        field: "t",
                        message: format!("`{s}` is not a finite time"),
                    });
                }
                *v = parsed;
            }
            let valid = if ncols == 9 {
                match fields[8] {
                    "1" | "true" => true,
                    "0" | "false" => false,
                    s => {
                        return Err(CsvError::Field {
                            line: line_no,
                            field: "valid",
                            message: format!("`{s}` is not 0/1/true/false"),
                        });
                    }
                }
            } else {
                true
            };
            if let Some(prev) = rows.last()
                && vals[0] < prev.t
            {
                return Err(CsvError::Field {
                    line: line_no,
                    field: "t",
                    message: format!("time goes backwards ({} < {})", vals[0], prev.t),
                });
            }
            rows.push(TrackRow {
                t: vals[0],
                position: DVec3::new(vals[1], vals[2], vals[3]),
                orientation: DQuat::from_xyzw(vals[4], vals[5], vals[6], vals[7]),
                valid,
            });
        }
        if columns.is_none() {
            return Err(CsvError::Header {
                line: 1,
                found: String::new(),
            });
        }
        if rows.is_empty() {
            return Err(CsvError::Empty);
        }
        Ok(Self { rows })
    }

    /// Reads and parses a CSV file.
    pub fn from_path(path: impl AsRef<FsPath>) -> Result<Self, CsvError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| CsvError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        Self::parse(&text)
    }

    /// The rows, in time order.
    #[must_use]
    pub fn rows(&self) -> &[TrackRow] {
        &self.rows
    }

    /// Time of the last row relative to the first.
    #[must_use]
    pub fn duration(&self) -> f64 {
        match (self.rows.first(), self.rows.last()) {
            (Some(a), Some(b)) => b.t - a.t,
            _ => 0.0,
        }
    }

    /// Pose at `t` seconds after the first row, looping over the track:
    /// positions are interpolated linearly, orientations by slerp when both
    /// rows are finite unit-ish quaternions (otherwise the earlier row is
    /// replayed as recorded), validity is the earlier row's.
    #[must_use]
    pub fn pose_at(&self, t: f64) -> (DVec3, DQuat, bool) {
        let first = self.rows[0];
        let dur = self.duration();
        let local = if dur > 0.0 && t.is_finite() {
            t.rem_euclid(dur)
        } else {
            0.0
        };
        let target = first.t + local;
        // Last row with time <= target.
        let i = self
            .rows
            .partition_point(|r| r.t <= target)
            .saturating_sub(1);
        let a = self.rows[i];
        let Some(b) = self.rows.get(i + 1) else {
            return (a.position, a.orientation, a.valid);
        };
        let span = b.t - a.t;
        if span <= 0.0 {
            return (a.position, a.orientation, a.valid);
        }
        let f = ((target - a.t) / span).clamp(0.0, 1.0);
        let pos = a.position.lerp(b.position, f);
        let qa = a.orientation;
        let qb = b.orientation;
        let unitish = |q: DQuat| q.is_finite() && (q.length() - 1.0).abs() < 1e-3;
        let q = if unitish(qa) && unitish(qb) {
            qa.normalize().slerp(qb.normalize(), f)
        } else {
            qa
        };
        (pos, q, a.valid)
    }
}

/// Where the noise-free poses come from.
#[derive(Debug, Clone, PartialEq)]
pub enum PoseSource {
    /// A parametric path.
    Path(Path),
    /// A recorded track, looped.
    Replay(CsvTrack),
}

/// Fault injection switches (all off by default).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Faults {
    /// Every n-th sample (sequence % n == n - 1) gets a NaN x position.
    pub nan_every: Option<u64>,
    /// Every n-th sample is held back and sent after its successor, so the
    /// receiver sees the pair swapped.
    pub reorder_every: Option<u64>,
    /// `(start_s, duration_s)`: no samples at all in that window of
    /// simulation time (the publisher is frozen; sequence numbers continue
    /// without a gap afterwards, timestamps jump).
    pub stall: Option<(f64, f64)>,
    /// `(start_s, duration_s)` windows in which samples have `valid = 0`
    /// (tracker lost line of sight).
    pub dropouts: Vec<(f64, f64)>,
}

/// Complete description of a simulated tracker.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionConfig {
    /// Pose source.
    pub source: PoseSource,
    /// Standard deviation of Gaussian position noise, metres per axis.
    pub noise_std_m: f64,
    /// PRNG seed.
    pub seed: u64,
    /// Ticks per second of simulation time.
    pub rate_hz: f64,
    /// Sequence number of the first sample (lets a restarted publisher
    /// simulate "a small number after a restart").
    pub first_sequence: u64,
    /// Fault injection.
    pub faults: Faults,
}

impl Default for MotionConfig {
    /// Still head, 0.5 mm noise, 500 Hz, seed 1, no faults.
    fn default() -> Self {
        Self {
            source: PoseSource::Path(Path::Still {
                position: DVec3::new(0.0, 1.7, 0.0),
            }),
            noise_std_m: 0.0005,
            seed: 1,
            rate_hz: 500.0,
            first_sequence: 0,
            faults: Faults::default(),
        }
    }
}

/// Produces the sample stream tick by tick.
#[derive(Debug, Clone)]
pub struct MotionGenerator {
    config: MotionConfig,
    rng: Prng,
    tick: u64,
    next_sequence: u64,
    held: Option<TrackerSample>,
}

impl MotionGenerator {
    /// A generator at tick 0.
    #[must_use]
    pub fn new(config: MotionConfig) -> Self {
        let rng = Prng::new(config.seed);
        let next_sequence = config.first_sequence;
        Self {
            config,
            rng,
            tick: 0,
            next_sequence,
            held: None,
        }
    }

    /// The configuration.
    #[must_use]
    pub fn config(&self) -> &MotionConfig {
        &self.config
    }

    /// Seconds between ticks (`1 / rate_hz`; 1 ms if the rate is unusable).
    #[must_use]
    pub fn period_s(&self) -> f64 {
        1.0 / self.rate_hz()
    }

    fn rate_hz(&self) -> f64 {
        let r = self.config.rate_hz;
        if r.is_finite() && r > 0.0 { r } else { 1000.0 }
    }

    /// Simulation time of the next tick (`tick / rate_hz`, computed by
    /// division so that round rates give round times).
    #[must_use]
    pub fn time_s(&self) -> f64 {
        self.tick as f64 / self.rate_hz()
    }

    /// Advances one tick and returns the samples to publish now, in order:
    /// usually one, none during a stall or while a reordered sample is held
    /// back, two right after a hold (successor first). New samples are
    /// stamped with `timestamp_ns` (the caller's wall clock, so latency can
    /// be measured); a held sample keeps its original stamp.
    pub fn tick(&mut self, timestamp_ns: u64) -> Vec<TrackerSample> {
        let t = self.time_s();
        self.tick += 1;
        let faults = &self.config.faults;
        if let Some((start, dur)) = faults.stall
            && t >= start
            && t < start + dur
        {
            return Vec::new();
        }
        let (clean_pos, q, mut valid) = match &self.config.source {
            PoseSource::Path(p) => {
                let (pos, q) = p.pose_at(t);
                (pos, q, true)
            }
            PoseSource::Replay(track) => track.pose_at(t),
        };
        if faults
            .dropouts
            .iter()
            .any(|&(start, dur)| t >= start && t < start + dur)
        {
            valid = false;
        }
        let sd = self.config.noise_std_m;
        let noise = if sd.is_finite() && sd > 0.0 {
            DVec3::new(
                self.rng.gaussian(),
                self.rng.gaussian(),
                self.rng.gaussian(),
            ) * sd
        } else {
            DVec3::ZERO
        };
        let seq = self.next_sequence;
        self.next_sequence = self.next_sequence.wrapping_add(1);
        let mut pos = clean_pos + noise;
        let hits = |every: Option<u64>| matches!(every, Some(n) if n > 0 && seq % n == n - 1);
        if hits(faults.nan_every) {
            pos.x = f64::NAN;
        }
        let sample = TrackerSample::new(timestamp_ns, seq, pos, q, valid);
        if let Some(held) = self.held.take() {
            return vec![sample, held];
        }
        if hits(faults.reorder_every) {
            self.held = Some(sample);
            return Vec::new();
        }
        vec![sample]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(config: MotionConfig, ticks: u64) -> Vec<TrackerSample> {
        let mut g = MotionGenerator::new(config);
        let mut out = Vec::new();
        for k in 0..ticks {
            out.extend(g.tick(1_000_000 * k));
        }
        out
    }

    #[test]
    fn prng_is_deterministic_and_gaussian() {
        let mut a = Prng::new(3);
        let mut b = Prng::new(3);
        for _ in 0..10 {
            assert_eq!(a.next_u64(), b.next_u64());
        }
        let mut r = Prng::new(11);
        let n = 200_000;
        let xs: Vec<f64> = (0..n).map(|_| r.gaussian()).collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64;
        assert!(mean.abs() < 0.01, "{mean}");
        assert!((var - 1.0).abs() < 0.02, "{var}");
        let u: Vec<f64> = (0..1000).map(|_| r.next_f64()).collect();
        assert!(u.iter().all(|&x| (0.0..1.0).contains(&x)));
    }

    #[test]
    fn paths_have_expected_geometry() {
        let c = DVec3::new(0.0, 1.7, 0.0);
        let circle = Path::Circle {
            center: c,
            radius: 0.5,
            period_s: 4.0,
        };
        for i in 0..40 {
            let (p, q) = circle.pose_at(i as f64 * 0.1);
            assert!(((p - c).length() - 0.5).abs() < 1e-12);
            // Facing the centre: local -z maps onto the direction to c.
            let fwd = q * DVec3::NEG_Z;
            assert!((fwd - (c - p).normalize()).length() < 1e-9);
        }
        let walk = Path::by_name("walk").expect("walk");
        let xs: Vec<f64> = (0..600)
            .map(|i| walk.pose_at(i as f64 * 0.01).0.x)
            .collect();
        let max = xs.iter().cloned().fold(f64::MIN, f64::max);
        let min = xs.iter().cloned().fold(f64::MAX, f64::min);
        assert!(max > 0.99 && min < -0.99);
        let f8 = Path::by_name("figure8").expect("figure8");
        let (p0, _) = f8.pose_at(0.0);
        let (p_half, _) = f8.pose_at(5.0);
        assert!((p0 - c).length() < 1e-12 && (p_half - c).length() < 1e-9);
        // Heading follows the direction of travel.
        let (pa, q) = f8.pose_at(1.0);
        let (pb, _) = f8.pose_at(1.001);
        let dir = (pb - pa).normalize();
        assert!(((q * DVec3::NEG_Z) - dir).length() < 1e-3);
        assert!(Path::by_name("nope").is_none());
        // Degenerate period: frozen, finite.
        let bad = Path::Circle {
            center: c,
            radius: 1.0,
            period_s: 0.0,
        };
        assert!(bad.pose_at(3.0).0.is_finite());
    }

    #[test]
    fn noise_has_requested_sd_and_is_seeded() {
        let cfg = MotionConfig {
            noise_std_m: 0.002,
            ..MotionConfig::default()
        };
        let a = run(cfg.clone(), 5000);
        let b = run(cfg, 5000);
        assert_eq!(a, b);
        let xs: Vec<f64> = a.iter().map(|s| s.position[0]).collect();
        let var = xs.iter().map(|x| x * x).sum::<f64>() / xs.len() as f64;
        assert!((var.sqrt() - 0.002).abs() < 0.0002, "{}", var.sqrt());
        let seqs: Vec<u64> = a.iter().map(|s| s.sequence).collect();
        assert_eq!(seqs, (0..5000).collect::<Vec<_>>());
    }

    #[test]
    fn faults_are_injected() {
        let cfg = MotionConfig {
            rate_hz: 100.0,
            first_sequence: 10,
            faults: Faults {
                nan_every: Some(5),
                reorder_every: Some(7),
                stall: Some((0.495, 0.2)),
                dropouts: vec![(0.105, 0.05)],
            },
            ..MotionConfig::default()
        };
        let out = run(cfg, 100);
        // Stall: 20 ticks produce nothing; sequence continues without a gap.
        let ts: Vec<u64> = out.iter().map(|s| s.timestamp_ns / 1_000_000).collect();
        assert!(!ts.iter().any(|&t| (50..70).contains(&t)));
        assert_eq!(out.len(), 80);
        let mut seqs: Vec<u64> = out.iter().map(|s| s.sequence).collect();
        // Reorder: 13 (13 % 7 == 6) comes after 14.
        let i13 = seqs.iter().position(|&s| s == 13).expect("13 sent");
        assert_eq!(seqs[i13 - 1], 14);
        // The held sample keeps its older timestamp.
        assert!(out[i13].timestamp_ns < out[i13 - 1].timestamp_ns);
        seqs.sort_unstable();
        assert_eq!(seqs, (10..90).collect::<Vec<_>>());
        for s in &out {
            assert_eq!(s.position[0].is_nan(), s.sequence % 5 == 4, "{s:?}");
        }
        // Dropout at t in [0.105, 0.155): ticks 11..=15.
        for s in &out {
            let t_ms = s.timestamp_ns / 1_000_000;
            assert_eq!(s.valid == 0, (11..16).contains(&t_ms), "{s:?}");
        }
    }

    const CSV: &str = "t,x,y,z,qx,qy,qz,qw,valid\n\
        # comment\n\
        0.0,0,1.7,0,0,0,0,1,1\n\
        \n\
        1.0,1,1.7,0,0,0,0,1,0\n\
        2.0,2,1.7,0,0,0,0,1,1\n";

    #[test]
    fn csv_parses_and_interpolates() {
        let track = CsvTrack::parse(CSV).expect("parse");
        assert_eq!(track.rows().len(), 3);
        assert_eq!(track.duration(), 2.0);
        let (p, q, v) = track.pose_at(0.5);
        assert!((p.x - 0.5).abs() < 1e-12 && v);
        assert!((q.length() - 1.0).abs() < 1e-12);
        let (p, _, v) = track.pose_at(1.25);
        assert!((p.x - 1.25).abs() < 1e-12 && !v);
        // Loops.
        let (p, _, _) = track.pose_at(2.5);
        assert!((p.x - 0.5).abs() < 1e-12);
        let no_valid = CsvTrack::parse("t,x,y,z,qx,qy,qz,qw\n0,1,2,3,0,0,0,1\n").expect("8 cols");
        assert!(no_valid.rows()[0].valid);
        // Replay through the generator.
        let cfg = MotionConfig {
            source: PoseSource::Replay(track),
            noise_std_m: 0.0,
            rate_hz: 4.0,
            ..MotionConfig::default()
        };
        let out = run(cfg, 8);
        let xs: Vec<f64> = out.iter().map(|s| s.position[0]).collect();
        assert_eq!(xs, vec![0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75]);
    }

    #[test]
    fn csv_errors_name_line_and_field() {
        let cases = [
            ("x,y\n", "line 1: bad header"),
            (
                "t,x,y,z,qx,qy,qz,qw\n0,1,2,3,0,0,0\n",
                "line 2: expected 8 fields, found 7",
            ),
            (
                "t,x,y,z,qx,qy,qz,qw\n0,1,2,3,0,0,0,1\n1,1,abc,3,0,0,0,1\n",
                "line 3: field `y`: `abc` is not a number",
            ),
            (
                "t,x,y,z,qx,qy,qz,qw,valid\n0,1,2,3,0,0,0,1,2\n",
                "line 2: field `valid`",
            ),
            (
                "t,x,y,z,qx,qy,qz,qw\n1,1,2,3,0,0,0,1\n0.5,1,2,3,0,0,0,1\n",
                "line 3: field `t`: time goes backwards",
            ),
            (
                "t,x,y,z,qx,qy,qz,qw\ninf,1,2,3,0,0,0,1\n",
                "line 2: field `t`",
            ),
            ("t,x,y,z,qx,qy,qz,qw\n", "track has no samples"),
            ("", "bad header"),
        ];
        for (text, want) in cases {
            let err = CsvTrack::parse(text).expect_err(text).to_string();
            assert!(err.contains(want), "{text:?}: got {err:?}, want {want:?}");
        }
        // Comments, blank lines, CR LF, spaces and quotes are CSV's.
        let t = CsvTrack::parse(
            "# a head\r\nt, x, y, z, qx, qy, qz, qw\r\n\r\n# start\r\n0, 1,\"2\",3, 0, 0, 0, 1\r\n",
        )
        .unwrap();
        assert_eq!(t.rows()[0].position, DVec3::new(1.0, 2.0, 3.0));
        let err = CsvTrack::parse("# a\nt,x,y,z,qx,qy,qz,qw\n\n0,1,2,3,0,0,0\n")
            .unwrap_err()
            .to_string();
        assert_eq!(err, "line 4: expected 8 fields, found 7");
        // NaN in a pose field is replayed, not rejected.
        assert!(CsvTrack::parse("t,x,y,z,qx,qy,qz,qw\n0,NaN,2,3,0,0,0,1\n").is_ok());
        let err = CsvTrack::from_path("/nonexistent/track.csv").expect_err("io");
        assert!(err.to_string().contains("/nonexistent/track.csv"));
    }
}
