//! Game-side tracker state machine: turns an untrusted stream of
//! [`TrackerSample`]s into the head pose to render with, and a status line.
//!
//! Why a state machine: the CAVE image is computed from the head pose every
//! frame, so a single NaN, a teleport from a reordered packet or a velocity
//! spike after a tracker restart is immediately visible (or nauseating). The
//! [`Follower`] therefore
//!
//! * **always holds the last good pose** and never returns a non-finite one;
//! * checks ordering first: duplicates and out-of-order sequence numbers are
//!   dropped, but a *publisher restart* (sequence back to a small number with
//!   time moving on, a large backwards jump, or any ordering break after a
//!   silence longer than `stale_after`) is accepted and resets the filter;
//! * then checks content: `valid = 0`, NaN/inf, and quaternions whose norm is
//!   off by more than a tolerance are rejected; nearly-unit quaternions are
//!   renormalised and kept on the same hemisphere as the previous one;
//! * filters the position with a [`OneEuroFilter`] driven by the publisher's
//!   timestamps (receive times are batched per frame and useless as dt);
//! * reports [`TrackerStatus`] from *local* receive times: Live, then Stale
//!   after `stale_after` (default 100 ms) without a good sample, then Lost
//!   after `lost_after` (default 1 s). A dead publisher simply ages into
//!   Stale and Lost.
//!
//! All time is passed in by the caller (`now: Instant`) so the logic is
//! deterministic in tests and uses one clock per frame in the game.

use crate::filter::{OneEuroFilter, OneEuroParams};
use crate::sample::TrackerSample;
use glam::{DQuat, DVec3};
use std::fmt;
use std::time::{Duration, Instant};

/// Tuning of the [`Follower`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FollowerConfig {
    /// No good sample for longer than this: status Stale.
    pub stale_after: Duration,
    /// No good sample for longer than this: status Lost.
    pub lost_after: Duration,
    /// Quaternions with `| |q| - 1 | <= tolerance` are renormalised, others
    /// rejected (a far-off norm means a corrupt or mis-ordered packet).
    /// A negative or non-finite value means the default (0.05).
    pub quat_norm_tolerance: f64,
    /// A backwards sequence jump to a value `<=` this, with the publisher's
    /// timestamp moving forward, is a publisher restart.
    pub restart_max_sequence: u64,
    /// A backwards sequence jump at least this large is a restart whatever
    /// the timestamps say (the new publisher may have a new clock base).
    pub restart_min_backstep: u64,
    /// A sample with a newer sequence but a timestamp older than the last
    /// in-order one by more than this is a leftover from a previous publisher
    /// and is dropped.
    pub max_time_regression: Duration,
    /// If consecutive good samples are further apart than this (publisher
    /// time), the filter restarts instead of smoothing across the gap.
    pub filter_reset_gap: Duration,
    /// One-Euro filter parameters for the position.
    pub filter: OneEuroParams,
}

impl Default for FollowerConfig {
    fn default() -> Self {
        Self {
            stale_after: Duration::from_millis(100),
            lost_after: Duration::from_secs(1),
            quat_norm_tolerance: 0.05,
            restart_max_sequence: 16,
            restart_min_backstep: 1000,
            max_time_regression: Duration::from_millis(50),
            filter_reset_gap: Duration::from_millis(250),
            filter: OneEuroParams::default(),
        }
    }
}

pub use crate::report::MAX_TRACKED_COORDINATE;

/// Why a sample's content was rejected.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RejectReason {
    /// `valid = 0`: the tracker had no fix.
    NoFix,
    /// Position has NaN or infinite components.
    NonFinitePosition,
    /// Position further than [`MAX_TRACKED_COORDINATE`] from the tracker's
    /// origin on some axis: no room is that big (a corrupt sample).
    PositionOutOfRange,
    /// Orientation has NaN or infinite components.
    NonFiniteOrientation,
    /// Orientation norm too far from 1 to renormalise.
    BadQuaternion {
        /// The norm received.
        norm: f64,
    },
}

impl fmt::Display for RejectReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RejectReason::NoFix => write!(f, "no fix"),
            RejectReason::NonFinitePosition => write!(f, "non-finite position"),
            RejectReason::PositionOutOfRange => write!(
                f,
                "position beyond ±{MAX_TRACKED_COORDINATE} m of the tracker's origin"
            ),
            RejectReason::NonFiniteOrientation => write!(f, "non-finite orientation"),
            RejectReason::BadQuaternion { norm } => {
                write!(f, "orientation not a unit quaternion (|q| = {norm:.3})")
            }
        }
    }
}

/// Why a sample was dropped before its content was looked at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DropReason {
    /// Same sequence and timestamp as the last in-order sample.
    Duplicate,
    /// Older sequence than the last in-order sample, not a restart.
    OutOfOrder,
    /// Newer sequence but much older timestamp: leftover of an old publisher.
    TimeRegressed,
}

/// What [`Follower::push`] did with a sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Verdict {
    /// Became the new pose.
    Accepted,
    /// In order, but its content is unusable.
    Rejected(RejectReason),
    /// Ignored because of its ordering.
    Dropped(DropReason),
}

/// Tracker health, for the game logic and the on-screen status line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TrackerStatus {
    /// No good sample received yet.
    Waiting,
    /// A good sample arrived within `stale_after`.
    Live,
    /// No good sample for more than `stale_after` (pose held).
    Stale,
    /// No good sample for more than `lost_after` (pose held).
    Lost,
    /// Samples keep arriving but are all rejected (pose held).
    Rejecting {
        /// Reason of the latest rejection.
        reason: RejectReason,
    },
}

impl fmt::Display for TrackerStatus {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TrackerStatus::Waiting => write!(f, "tracker: waiting for first sample"),
            TrackerStatus::Live => write!(f, "tracker: live"),
            TrackerStatus::Stale => write!(f, "tracker: stale, holding last pose"),
            TrackerStatus::Lost => write!(f, "tracker: LOST, holding last pose"),
            TrackerStatus::Rejecting { reason } => {
                write!(
                    f,
                    "tracker: rejecting samples ({reason}), holding last pose"
                )
            }
        }
    }
}

/// The pose to render with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeadPose {
    /// Filtered position (metres, tracker space).
    pub position: DVec3,
    /// Unit orientation (renormalised, hemisphere-continuous).
    pub orientation: DQuat,
    /// Unfiltered position of the last good sample.
    pub raw_position: DVec3,
    /// Publisher timestamp of the last good sample (Unix ns).
    pub timestamp_ns: u64,
    /// Sequence number of the last good sample.
    pub sequence: u64,
}

/// Everything the game needs for one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FollowerOutput {
    /// Health.
    pub status: TrackerStatus,
    /// Last good pose; `None` only before the first good sample.
    pub pose: Option<HeadPose>,
    /// Filtered velocity (m/s) while Live, zero otherwise so that nothing
    /// extrapolates a pose the tracker no longer confirms.
    pub velocity: DVec3,
    /// Time since the last good sample was received.
    pub age: Option<Duration>,
}

impl FollowerOutput {
    /// One-line status for the HUD, with the pose age when it matters.
    #[must_use]
    pub fn status_line(&self) -> String {
        match (self.status, self.age) {
            (TrackerStatus::Live, _) | (_, None) => self.status.to_string(),
            (s, Some(age)) => format!("{s} ({:.2} s old)", age.as_secs_f64()),
        }
    }
}

/// Counters for diagnostics.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FollowerStats {
    /// Samples that became the pose.
    pub accepted: u64,
    /// Accepted samples whose quaternion was renormalised.
    pub renormalised: u64,
    /// Rejected: no fix.
    pub no_fix: u64,
    /// Rejected: NaN/inf.
    pub non_finite: u64,
    /// Rejected: quaternion norm.
    pub bad_quaternion: u64,
    /// Dropped: duplicate.
    pub duplicates: u64,
    /// Dropped: out of order.
    pub out_of_order: u64,
    /// Dropped: timestamp regressed.
    pub time_regressed: u64,
    /// Publisher restarts detected.
    pub restarts: u64,
}

#[derive(Debug, Clone, Copy)]
struct InOrder {
    sequence: u64,
    timestamp_ns: u64,
    received: Instant,
}

#[derive(Debug, Clone, Copy)]
struct Good {
    pose: HeadPose,
    velocity: DVec3,
    received: Instant,
}

/// The tracker-following state machine (see the module docs).
#[derive(Debug, Clone)]
pub struct Follower {
    config: FollowerConfig,
    filter: OneEuroFilter,
    last_in_order: Option<InOrder>,
    last_good: Option<Good>,
    last_reject: Option<(RejectReason, Instant)>,
    stats: FollowerStats,
}

impl Default for Follower {
    fn default() -> Self {
        Self::new(FollowerConfig::default())
    }
}

fn ns_to_secs(ns: i128) -> f64 {
    ns as f64 * 1e-9
}

impl Follower {
    /// A follower in state Waiting.
    #[must_use]
    pub fn new(config: FollowerConfig) -> Self {
        Self {
            filter: OneEuroFilter::new(config.filter),
            config,
            last_in_order: None,
            last_good: None,
            last_reject: None,
            stats: FollowerStats::default(),
        }
    }

    /// The configuration.
    #[must_use]
    pub fn config(&self) -> &FollowerConfig {
        &self.config
    }

    /// Diagnostic counters.
    #[must_use]
    pub fn stats(&self) -> &FollowerStats {
        &self.stats
    }

    /// Feeds every sample of a drained batch, all received at `now`.
    pub fn extend<'a>(
        &mut self,
        samples: impl IntoIterator<Item = &'a TrackerSample>,
        now: Instant,
    ) {
        for s in samples {
            self.push(s, now);
        }
    }

    /// Classifies the sample's ordering; `Ok(restart)` if it is to be
    /// processed.
    fn check_order(&self, s: &TrackerSample, now: Instant) -> Result<bool, DropReason> {
        let Some(last) = self.last_in_order else {
            return Ok(false);
        };
        let c = &self.config;
        // After a silence any ordering break is a new stream: nothing from
        // the old one can still be "just reordered" that late.
        let after_gap = now.saturating_duration_since(last.received) > c.stale_after;
        let dt_ns = i128::from(s.timestamp_ns) - i128::from(last.timestamp_ns);
        if s.sequence > last.sequence {
            let regress = i128::try_from(c.max_time_regression.as_nanos()).unwrap_or(i128::MAX);
            if dt_ns < -regress {
                return if after_gap {
                    Ok(true)
                } else {
                    Err(DropReason::TimeRegressed)
                };
            }
            return Ok(false);
        }
        let backstep = last.sequence - s.sequence;
        if backstep == 0 && dt_ns == 0 {
            return Err(DropReason::Duplicate);
        }
        let small_restart = s.sequence <= c.restart_max_sequence && dt_ns > 0;
        if backstep >= c.restart_min_backstep || small_restart || after_gap {
            return Ok(true);
        }
        Err(if backstep == 0 {
            DropReason::Duplicate
        } else {
            DropReason::OutOfOrder
        })
    }

    /// Content checks; returns the usable (position, unit orientation).
    fn check_content(&mut self, s: &TrackerSample) -> Result<(DVec3, DQuat), RejectReason> {
        if !s.has_fix() {
            return Err(RejectReason::NoFix);
        }
        let p = s.position_vec();
        if !p.is_finite() {
            return Err(RejectReason::NonFinitePosition);
        }
        if p.abs().max_element() > MAX_TRACKED_COORDINATE {
            return Err(RejectReason::PositionOutOfRange);
        }
        let q = s.orientation_quat();
        if !q.is_finite() {
            return Err(RejectReason::NonFiniteOrientation);
        }
        let norm = q.length();
        let tol = match self.config.quat_norm_tolerance {
            t if t.is_finite() && t >= 0.0 => t,
            _ => FollowerConfig::default().quat_norm_tolerance,
        };
        let err = (norm - 1.0).abs();
        if err.is_nan() || err > tol || norm == 0.0 {
            return Err(RejectReason::BadQuaternion { norm });
        }
        if (norm - 1.0).abs() > 1e-9 {
            self.stats.renormalised += 1;
        }
        let mut q = q / norm;
        // q and -q are the same rotation; keep the sign continuous so
        // anything interpolating orientations takes the short way.
        if let Some(g) = &self.last_good
            && q.dot(g.pose.orientation) < 0.0
        {
            q = -q;
        }
        Ok((p, q))
    }

    /// Processes one sample received at `now`.
    pub fn push(&mut self, s: &TrackerSample, now: Instant) -> Verdict {
        let restart = match self.check_order(s, now) {
            Ok(r) => r,
            Err(reason) => {
                match reason {
                    DropReason::Duplicate => self.stats.duplicates += 1,
                    DropReason::OutOfOrder => self.stats.out_of_order += 1,
                    DropReason::TimeRegressed => self.stats.time_regressed += 1,
                }
                return Verdict::Dropped(reason);
            }
        };
        if restart {
            self.stats.restarts += 1;
            self.filter.reset();
        }
        self.last_in_order = Some(InOrder {
            sequence: s.sequence,
            timestamp_ns: s.timestamp_ns,
            received: now,
        });

        let (position, orientation) = match self.check_content(s) {
            Ok(v) => v,
            Err(reason) => {
                match reason {
                    RejectReason::NoFix => self.stats.no_fix += 1,
                    RejectReason::NonFinitePosition
                    | RejectReason::PositionOutOfRange
                    | RejectReason::NonFiniteOrientation => self.stats.non_finite += 1,
                    RejectReason::BadQuaternion { .. } => self.stats.bad_quaternion += 1,
                }
                self.last_reject = Some((reason, now));
                return Verdict::Rejected(reason);
            }
        };

        // Filter step from publisher time; reset across gaps, restarts and
        // unusable timestamps rather than smoothing over them.
        let dt = match &self.last_good {
            Some(g) => ns_to_secs(i128::from(s.timestamp_ns) - i128::from(g.pose.timestamp_ns)),
            None => 0.0,
        };
        if !(dt > 0.0 && dt <= self.config.filter_reset_gap.as_secs_f64()) {
            self.filter.reset();
        }
        let (filtered, velocity) = match self.filter.update(position, dt) {
            Some(o) => (o.position, o.velocity),
            None => (position, DVec3::ZERO),
        };
        self.last_good = Some(Good {
            pose: HeadPose {
                position: filtered,
                orientation,
                raw_position: position,
                timestamp_ns: s.timestamp_ns,
                sequence: s.sequence,
            },
            velocity,
            received: now,
        });
        self.stats.accepted += 1;
        Verdict::Accepted
    }

    /// Status at `now`.
    #[must_use]
    pub fn status(&self, now: Instant) -> TrackerStatus {
        let c = &self.config;
        let recent_reject = self
            .last_reject
            .filter(|(_, at)| now.saturating_duration_since(*at) <= c.stale_after);
        let Some(good) = &self.last_good else {
            return match recent_reject {
                Some((reason, _)) => TrackerStatus::Rejecting { reason },
                None => TrackerStatus::Waiting,
            };
        };
        let age = now.saturating_duration_since(good.received);
        if age <= c.stale_after {
            return TrackerStatus::Live;
        }
        if let Some((reason, at)) = recent_reject
            && at >= good.received
        {
            return TrackerStatus::Rejecting { reason };
        }
        if age <= c.lost_after {
            TrackerStatus::Stale
        } else {
            TrackerStatus::Lost
        }
    }

    /// Pose, velocity and status at `now`.
    #[must_use]
    pub fn output(&self, now: Instant) -> FollowerOutput {
        let status = self.status(now);
        let velocity = match (&self.last_good, status) {
            (Some(g), TrackerStatus::Live) => g.velocity,
            _ => DVec3::ZERO,
        };
        FollowerOutput {
            status,
            pose: self.last_good.map(|g| g.pose),
            velocity,
            age: self
                .last_good
                .map(|g| now.saturating_duration_since(g.received)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: u64 = 1_000_000;
    const T0: u64 = 1_700_000_000_000_000_000;

    fn good(seq: u64, t_ms: u64, x: f64) -> TrackerSample {
        TrackerSample::new(
            T0 + t_ms * MS,
            seq,
            DVec3::new(x, 1.7, 0.0),
            DQuat::IDENTITY,
            true,
        )
    }

    fn at(base: Instant, ms: u64) -> Instant {
        base + Duration::from_millis(ms)
    }

    fn live_follower() -> (Follower, Instant) {
        let base = Instant::now();
        let mut f = Follower::default();
        for i in 0..10 {
            assert_eq!(f.push(&good(i, i, 0.0), at(base, i)), Verdict::Accepted);
        }
        (f, base)
    }

    #[test]
    fn waiting_then_live() {
        let base = Instant::now();
        let mut f = Follower::default();
        let o = f.output(base);
        assert_eq!(o.status, TrackerStatus::Waiting);
        assert!(o.pose.is_none() && o.age.is_none());
        assert_eq!(o.status_line(), "tracker: waiting for first sample");
        f.push(&good(0, 0, 1.0), base);
        let o = f.output(base);
        assert_eq!(o.status, TrackerStatus::Live);
        assert_eq!(o.pose.map(|p| p.position.x), Some(1.0));
    }

    #[test]
    fn stale_then_lost_holding_pose() {
        let (f, base) = live_follower();
        let pose = f.output(at(base, 9)).pose;
        assert_eq!(f.status(at(base, 100)), TrackerStatus::Live);
        let stale = f.output(at(base, 150));
        assert_eq!(stale.status, TrackerStatus::Stale);
        assert_eq!(stale.pose, pose);
        assert_eq!(stale.velocity, DVec3::ZERO);
        assert!(
            stale.status_line().contains("stale"),
            "{}",
            stale.status_line()
        );
        assert!(
            stale.status_line().contains("0.14 s old"),
            "{}",
            stale.status_line()
        );
        let lost = f.output(at(base, 1100));
        assert_eq!(lost.status, TrackerStatus::Lost);
        assert_eq!(lost.pose, pose);
        // A clock going backwards does not panic.
        assert_eq!(f.status(base), TrackerStatus::Live);
    }

    #[test]
    fn invalid_content_is_rejected_and_pose_held() {
        let (mut f, base) = live_follower();
        let held = f.output(at(base, 9)).pose;
        let mut nan = good(10, 10, 5.0);
        nan.position[1] = f64::NAN;
        assert_eq!(
            f.push(&nan, at(base, 10)),
            Verdict::Rejected(RejectReason::NonFinitePosition)
        );
        let mut inf_q = good(11, 11, 5.0);
        inf_q.orientation[3] = f64::INFINITY;
        assert_eq!(
            f.push(&inf_q, at(base, 11)),
            Verdict::Rejected(RejectReason::NonFiniteOrientation)
        );
        let mut nofix = good(12, 12, 5.0);
        nofix.valid = 0;
        assert_eq!(
            f.push(&nofix, at(base, 12)),
            Verdict::Rejected(RejectReason::NoFix)
        );
        let mut far = good(13, 13, 5.0);
        far.orientation = [0.0, 0.0, 0.0, 1.5];
        assert!(matches!(
            f.push(&far, at(base, 13)),
            Verdict::Rejected(RejectReason::BadQuaternion { norm }) if (norm - 1.5).abs() < 1e-12
        ));
        let o = f.output(at(base, 14));
        assert_eq!(o.pose, held);
        // Still within stale_after of the last good sample: Live.
        assert_eq!(o.status, TrackerStatus::Live);
        // Keep rejecting past stale_after: Rejecting with the last reason.
        for i in 14..40 {
            f.push(
                &{
                    let mut s = good(i, i * 10, 5.0);
                    s.valid = 0;
                    s
                },
                at(base, i * 10),
            );
        }
        let st = f.status(at(base, 400));
        assert_eq!(
            st,
            TrackerStatus::Rejecting {
                reason: RejectReason::NoFix
            }
        );
        assert_eq!(
            st.to_string(),
            "tracker: rejecting samples (no fix), holding last pose"
        );
        assert_eq!(f.output(at(base, 400)).pose, held);
        let stats = *f.stats();
        assert_eq!((stats.non_finite, stats.bad_quaternion), (2, 1));
        assert_eq!(stats.no_fix, 1 + 26);
    }

    #[test]
    fn rejecting_before_any_good_sample() {
        let base = Instant::now();
        let mut f = Follower::default();
        let mut s = good(0, 0, 0.0);
        s.valid = 0;
        f.push(&s, base);
        assert_eq!(
            f.status(base),
            TrackerStatus::Rejecting {
                reason: RejectReason::NoFix
            }
        );
        assert_eq!(f.status(at(base, 500)), TrackerStatus::Waiting);
    }

    #[test]
    fn near_unit_quaternion_is_renormalised_and_hemisphere_kept() {
        let (mut f, base) = live_follower();
        let q = DQuat::from_rotation_y(0.2);
        let mut s = good(10, 10, 0.0);
        // Slightly long and on the other hemisphere.
        s.orientation = (-(q * 1.02)).to_array();
        assert_eq!(f.push(&s, at(base, 10)), Verdict::Accepted);
        let got = f.output(at(base, 10)).pose.expect("pose").orientation;
        assert!((got.length() - 1.0).abs() < 1e-12);
        assert!(
            got.dot(DQuat::IDENTITY) > 0.0,
            "sign flipped to stay continuous"
        );
        assert!(got.angle_between(q) < 1e-9);
        assert_eq!(f.stats().renormalised, 1);
    }

    #[test]
    fn duplicates_and_reordered_samples_are_dropped() {
        let (mut f, base) = live_follower();
        assert_eq!(
            f.push(&good(9, 9, 0.0), at(base, 10)),
            Verdict::Dropped(DropReason::Duplicate)
        );
        // A swapped pair: 11 then 10.
        assert_eq!(f.push(&good(11, 11, 0.0), at(base, 11)), Verdict::Accepted);
        assert_eq!(
            f.push(&good(10, 10, 9.0), at(base, 11)),
            Verdict::Dropped(DropReason::OutOfOrder)
        );
        // A swap at the very start is not mistaken for a restart.
        let mut g = Follower::default();
        g.push(&good(1, 1, 0.0), base);
        assert_eq!(
            g.push(&good(0, 0, 0.0), base),
            Verdict::Dropped(DropReason::OutOfOrder)
        );
        assert_eq!(g.stats().restarts, 0);
        assert_eq!(f.stats().duplicates, 1);
        assert_eq!(f.stats().out_of_order, 1);
    }

    #[test]
    fn restart_with_small_sequence_is_accepted() {
        let base = Instant::now();
        let mut f = Follower::default();
        for i in 0..500 {
            f.push(&good(i, i, 0.0), at(base, i));
        }
        // Immediate restart (no gap), seq back to 0, time moving on.
        assert_eq!(f.push(&good(0, 600, 2.0), at(base, 500)), Verdict::Accepted);
        assert_eq!(f.stats().restarts, 1);
        let o = f.output(at(base, 500));
        assert_eq!(o.status, TrackerStatus::Live);
        // Filter was reset: no smoothing from the old stream, no velocity spike.
        assert_eq!(o.pose.map(|p| p.position.x), Some(2.0));
        assert_eq!(o.velocity, DVec3::ZERO);
        assert_eq!(f.push(&good(1, 601, 2.0), at(base, 501)), Verdict::Accepted);
    }

    #[test]
    fn restart_with_new_clock_base_and_large_backstep() {
        let base = Instant::now();
        let mut f = Follower::default();
        for i in 0..2000 {
            f.push(&good(i, 10_000 + i, 0.0), at(base, i / 10));
        }
        // New publisher with a clock far behind and sequence 50.
        let s = good(50, 0, 1.0);
        assert_eq!(f.push(&s, at(base, 200)), Verdict::Accepted);
        assert_eq!(f.stats().restarts, 1);
    }

    #[test]
    fn any_ordering_break_after_a_gap_is_a_restart() {
        let base = Instant::now();
        let mut f = Follower::default();
        for i in 0..300 {
            f.push(&good(i, i, 0.0), at(base, i));
        }
        // After 2 s of silence a publisher starting at 200 (not small, not a
        // large backstep) is accepted.
        assert_eq!(
            f.push(&good(200, 2300, 1.0), at(base, 2300)),
            Verdict::Accepted
        );
        assert_eq!(f.stats().restarts, 1);
        assert_eq!(f.status(at(base, 2300)), TrackerStatus::Live);
    }

    #[test]
    fn leftovers_of_old_publisher_are_dropped() {
        let base = Instant::now();
        let mut f = Follower::default();
        for i in 0..10 {
            f.push(&good(i, 1000 + i, 0.0), at(base, i));
        }
        // Restart: seq 0, later time.
        f.push(&good(0, 2000, 1.0), at(base, 10));
        // A late sample of the old stream (seq 10 > 0, but 1 s older).
        assert_eq!(
            f.push(&good(10, 1010, 0.0), at(base, 10)),
            Verdict::Dropped(DropReason::TimeRegressed)
        );
        assert_eq!(f.output(at(base, 10)).pose.map(|p| p.position.x), Some(1.0));
    }

    #[test]
    fn velocity_is_estimated_and_filtered() {
        let base = Instant::now();
        let mut f = Follower::default();
        // 0.5 m/s along x at 1 kHz with 0.1 mm noise.
        let mut rng = crate::motion::Prng::new(5);
        for i in 0..3000u64 {
            let x = 0.5 * i as f64 * 1e-3 + rng.gaussian() * 1e-4;
            f.push(&good(i, i, x), at(base, i));
        }
        let o = f.output(at(base, 2999));
        assert!((o.velocity.x - 0.5).abs() < 0.05, "{:?}", o.velocity);
        assert!(o.velocity.y.abs() < 0.05 && o.velocity.z.abs() < 0.05);
    }

    /// A hostile or crashed peer: samples of random bits (any bit pattern
    /// is a valid `TrackerSample`) never panic the follower, and what it
    /// outputs stays finite and in range.
    #[test]
    fn random_bytes_never_crash_and_never_leak_out() {
        let base = Instant::now();
        let mut f = Follower::default();
        let mut rng = crate::motion::Prng::new(0x9e37_79b9_7f4a_7c15);
        let mut next = move || rng.next_u64();
        for k in 0..20_000u64 {
            let mut s = TrackerSample {
                timestamp_ns: next(),
                sequence: next(),
                position: [0; 3].map(|_| f64::from_bits(next())),
                orientation: [0; 4].map(|_| f64::from_bits(next())),
                valid: next() as u8,
                _pad: [0; 7],
            };
            // Every third one plausible, so some are accepted.
            if k % 3 == 0 {
                s.position = [0; 3].map(|_| (next() % 4000) as f64 / 1000.0 - 2.0);
                s.orientation = [0.0, 0.0, 0.0, 1.0];
            }
            let _ = f.push(&s, at(base, k));
            let o = f.output(at(base, k));
            if let Some(p) = o.pose {
                assert!(p.position.is_finite() && p.orientation.is_finite());
                assert!(p.position.abs().max_element() <= MAX_TRACKED_COORDINATE);
            }
            assert!(o.velocity.is_finite(), "{:?}", o.velocity);
        }
    }

    #[test]
    fn broken_timestamps_do_not_freeze_the_pose() {
        let base = Instant::now();
        let mut f = Follower::default();
        for i in 0..5u64 {
            let mut s = good(i, 0, i as f64);
            s.timestamp_ns = 0;
            assert_eq!(f.push(&s, at(base, i)), Verdict::Accepted);
        }
        assert_eq!(f.output(at(base, 5)).pose.map(|p| p.position.x), Some(4.0));
    }

    #[test]
    fn fault_injected_stream_end_to_end() {
        use crate::motion::{Faults, MotionConfig, MotionGenerator, Path, PoseSource};
        let cfg = MotionConfig {
            source: PoseSource::Path(Path::by_name("circle").expect("circle")),
            noise_std_m: 0.0005,
            rate_hz: 500.0,
            faults: Faults {
                nan_every: Some(17),
                reorder_every: Some(23),
                stall: Some((1.0, 0.3)),
                dropouts: vec![(2.0, 0.05)],
            },
            ..MotionConfig::default()
        };
        let mut g = MotionGenerator::new(cfg);
        let mut f = Follower::default();
        let base = Instant::now();
        let mut saw_stale = false;
        for k in 0..1500u64 {
            // Receive time = simulation time (2 ms per tick).
            let now = at(base, 2 * k);
            let batch = g.tick(T0 + 2 * k * MS);
            f.extend(batch.iter(), now);
            let o = f.output(now);
            if let Some(p) = o.pose {
                assert!(p.position.is_finite() && p.orientation.is_finite());
                assert!(((p.position - DVec3::new(0.0, 1.7, 0.0)).length() - 0.5).abs() < 0.02);
            }
            saw_stale |= o.status == TrackerStatus::Stale;
        }
        assert!(saw_stale, "the 300 ms stall must show as Stale");
        let s = *f.stats();
        assert!(s.non_finite > 50 && s.out_of_order > 30, "{s:?}");
        assert_eq!(s.restarts, 0, "{s:?}");
        assert!(s.no_fix >= 20, "{s:?}");
        assert_eq!(f.status(at(base, 3000)), TrackerStatus::Live);
    }
}
