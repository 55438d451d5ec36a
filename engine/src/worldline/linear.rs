//! Append-only piecewise-linear worldlines.

use glam::DVec3;

use super::contraction::LorentzMap;
use super::sliding::Braking;
use crate::spacetime::{Event, ProperVelocity, rotation_of_velocity_change};

/// Why a kink cannot be appended to a worldline.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum WorldlineError {
    /// Worldlines only grow forward in board time.
    #[error(
        "cannot change velocity at t = {at} s: the worldline already has a segment from t = {last} s"
    )]
    BeforeLastSegment {
        /// The requested board time.
        at: f64,
        /// Start of the last segment.
        last: f64,
    },
    /// Time or velocity not finite.
    #[error("time or velocity is not a finite number")]
    NotFinite,
    /// A proper velocity beyond what the engine holds (|u| = γ|β| above
    /// [`crate::scene::MAX_U`]): its γ would lose the board clock's
    /// resolution.
    #[error("|u| = γ|β| = {0:e} is beyond what the engine holds: give |u| ≤ 1e12")]
    TooFast(f64),
    /// A worldline or segment received from elsewhere (a CAVE render
    /// node's copy) that no worldline of this engine could be.
    #[error("not a worldline: {0}")]
    Malformed(&'static str),
}

/// One piece of a worldline, of one of three kinds, all along a straight
/// line in closed form:
///
/// * **uniform**: from event `start` on the body moves with constant proper
///   velocity `u`;
/// * **braking**: it starts with proper velocity `u` and slides under
///   constant proper deceleration [`Self::deceleration`] (`μ g`, board-frame
///   sliding friction; see [`crate::worldline::sliding`]): a hyperbola in
///   `(t, s)`, proper speed falling linearly in board time until
///   [`Self::stop_time`], then at rest where it stopped;
/// * **rest**: `u = 0`.
///
/// `u`, [`Self::velocity`], [`Self::gamma`], [`Self::contract`] and
/// [`Self::place`] are the values at the segment's **start**; the `_at`
/// methods give any board time. Before its start a segment extends back
/// uniformly with its start velocity (what the first segment does before
/// `t = 0`).
///
/// Serialised whole, cached fields included, so that a copy (a CAVE render
/// node's) holds the same bits as the original.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Segment {
    /// Where and when this segment begins (board frame).
    pub start: Event,
    /// Proper velocity along the segment.
    pub u: ProperVelocity,
    /// The body's proper time at `start`, seconds.
    pub proper_time: f64,
    /// Orientation of the body's rest frame along this segment, radians
    /// counter-clockwise about the board normal `+z`: the angle by which its
    /// rest-frame axes are turned from those of the pure boost from the
    /// board to `u`. It is the sum of the Thomas–Wigner rotations of every
    /// earlier velocity change ([`crate::spacetime::rotation_of_velocity_change`]);
    /// 0 on the first segment.
    pub orientation: f64,
    /// Board-frame velocity `c u / γ`, m/s (derived from `u`, cached because
    /// every position query needs it).
    velocity: DVec3,
    /// `1 / γ`, the rate of proper time per board time (cached).
    inverse_gamma: f64,
    /// Unit direction of motion (zero at rest), for contraction (cached).
    direction: DVec3,
    /// `γ` (cached).
    gamma: f64,
    /// `(cos, sin)` of `orientation` (cached).
    turn: (f64, f64),
    /// Proper deceleration of the reference point, m/s² (0: uniform or rest).
    deceleration: f64,
    /// Speed of light, m/s.
    c: f64,
}

impl Segment {
    fn new(start: Event, u: ProperVelocity, proper_time: f64, orientation: f64, c: f64) -> Self {
        let gamma = u.gamma();
        let speed = u.0.length();
        Self {
            start,
            u,
            proper_time,
            orientation,
            velocity: u.0 * (c / gamma),
            inverse_gamma: 1.0 / gamma,
            direction: if speed > 0.0 {
                u.0 / speed
            } else {
                DVec3::ZERO
            },
            gamma,
            turn: orientation.sin_cos(),
            deceleration: 0.0,
            c,
        }
    }

    /// Whether this segment is one the engine could have made: finite, with
    /// the cached values its defining ones give (a copy received from
    /// elsewhere is checked so before use).
    #[must_use]
    pub fn is_consistent(&self) -> bool {
        let finite = self.start.t.is_finite()
            && self.start.position.is_finite()
            && self.u.is_finite()
            && self.proper_time.is_finite()
            && self.orientation.is_finite()
            && self.c.is_finite()
            && self.c > 0.0
            && self.deceleration.is_finite()
            && self.deceleration >= 0.0;
        finite
            && Self::braking(
                self.start,
                self.u,
                self.proper_time,
                self.orientation,
                self.c,
                self.deceleration,
            ) == *self
    }

    /// A segment that brakes with proper deceleration `deceleration` (m/s²,
    /// ≥ 0) from its start; a rest segment (`u = 0`) or a zero deceleration
    /// gives a uniform segment.
    fn braking(
        start: Event,
        u: ProperVelocity,
        proper_time: f64,
        orientation: f64,
        c: f64,
        deceleration: f64,
    ) -> Self {
        let mut s = Self::new(start, u, proper_time, orientation, c);
        if u.0 != DVec3::ZERO && deceleration > 0.0 {
            s.deceleration = deceleration;
        }
        s
    }

    /// Proper deceleration of the reference point along this segment, m/s²
    /// (0 for a uniform or rest segment).
    #[inline]
    #[must_use]
    pub fn deceleration(&self) -> f64 {
        self.deceleration
    }

    /// The speed of light its velocities were derived with, m/s.
    #[inline]
    #[must_use]
    pub fn speed_of_light(&self) -> f64 {
        self.c
    }

    /// Whether this is a braking segment (moving, decelerating).
    #[inline]
    #[must_use]
    pub fn is_braking(&self) -> bool {
        self.deceleration > 0.0
    }

    /// Whether this is a rest segment.
    #[inline]
    #[must_use]
    pub fn is_rest(&self) -> bool {
        self.u.0 == DVec3::ZERO
    }

    /// The reference point's braking along this segment in closed form
    /// (times from the segment start; deceleration 0 for uniform motion).
    #[inline]
    #[must_use]
    pub fn braking_law(&self) -> Braking {
        Braking::new(self.u.0.length(), self.deceleration, self.c)
    }

    /// Board time at which a braking segment's reference point comes to
    /// rest, s: `t₀ + c|u|/a`. `None` for uniform and rest segments.
    #[must_use]
    pub fn stop_time(&self) -> Option<f64> {
        self.is_braking()
            .then(|| self.start.t + self.braking_law().stop_time())
    }

    /// Unit direction of motion (zero at rest), board frame.
    #[inline]
    #[must_use]
    pub fn direction(&self) -> DVec3 {
        self.direction
    }

    /// Proper velocity at board time `t` (the start's before the start).
    #[inline]
    #[must_use]
    pub fn u_at(&self, t: f64) -> ProperVelocity {
        let dt = t - self.start.t;
        if self.deceleration == 0.0 || dt <= 0.0 {
            return self.u;
        }
        ProperVelocity(self.direction * self.braking_law().proper_speed_at(dt))
    }

    /// Board-frame velocity at board time `t`, m/s.
    #[inline]
    #[must_use]
    pub fn velocity_at(&self, t: f64) -> DVec3 {
        if self.deceleration == 0.0 {
            return self.velocity;
        }
        self.u_at(t).velocity(self.c)
    }

    /// The uniform segment tangent to this one at board time `t`: same
    /// event, proper velocity, proper time and orientation there (this
    /// segment itself when it is uniform). Its contraction is the body's
    /// instantaneous Lorentz contraction.
    #[must_use]
    pub fn tangent_at(&self, t: f64) -> Segment {
        if self.deceleration == 0.0 {
            return *self;
        }
        Segment::new(
            Event::new(t, self.position_at(t)),
            self.u_at(t),
            self.proper_time_at(t),
            self.orientation,
            self.c,
        )
    }

    /// Where the point of the body at rest-frame offset `r` lies from the
    /// reference point at board time `t`: [`Self::place`] on a uniform
    /// segment; on a braking one the Born-rigid body's offset
    /// ([`Braking::contracted_offset_at`]: `r∥/γ` without friction, `r∥` at
    /// rest), falling back to the instantaneous Lorentz contraction for a
    /// point beyond the braking's Rindler horizon (`r∥ ≥ c²/a`, which
    /// scene validation refuses).
    #[must_use]
    pub fn place_at(&self, t: f64, r: DVec3) -> DVec3 {
        if self.deceleration == 0.0 {
            return self.place(r);
        }
        self.born_rigid_offset(t, self.rotate(r))
    }

    /// On a braking segment, where the point of the Born-rigid body at
    /// rest-frame offset `r` (already turned by [`Self::rotate`]) lies from
    /// the reference point at board time `t`: across the motion `r⊥`, along
    /// it [`Braking::contracted_offset_at`] (the instantaneous Lorentz
    /// contraction beyond the Rindler horizon). See [`Self::place_at`].
    #[must_use]
    pub fn born_rigid_offset(&self, t: f64, r: DVec3) -> DVec3 {
        let n = self.direction;
        let along = n.dot(r);
        let across = r - n * along;
        let dt = (t - self.start.t).max(0.0);
        let law = self.braking_law();
        let moved = law
            .contracted_offset_at(dt, along)
            .unwrap_or_else(|_| along / law.gamma_at(dt));
        across + n * moved
    }

    /// Lorentz factor along the segment.
    #[inline]
    #[must_use]
    pub fn gamma(&self) -> f64 {
        self.gamma
    }

    /// A rest-frame offset contracted along this segment's motion, as
    /// [`crate::worldline::contract`] does, with the direction and `1/γ`
    /// cached: `r⊥ + n (n·r) / γ`.
    #[inline]
    #[must_use]
    pub fn contract(&self, r: DVec3) -> DVec3 {
        self.lorentz_map().apply(r)
    }

    /// This segment's Lorentz contraction as a map (direction and `1/γ`
    /// cached): [`Self::contract`] is its [`LorentzMap::apply`].
    #[inline]
    #[must_use]
    pub fn lorentz_map(&self) -> LorentzMap {
        LorentzMap::from_parts(self.direction, self.inverse_gamma)
    }

    /// `(sin, cos)` of [`Self::orientation`] (cached): what [`Self::rotate`]
    /// multiplies by, for kernels that turn many offsets at once.
    #[inline]
    #[must_use]
    pub fn turn(&self) -> (f64, f64) {
        self.turn
    }

    /// A rest-frame offset (axes of the body's mesh) turned by this
    /// segment's [`Self::orientation`] about `+z`: the same offset in the
    /// axes of the pure boost from the board.
    #[inline]
    #[must_use]
    pub fn rotate(&self, r: DVec3) -> DVec3 {
        let (s, c) = self.turn;
        DVec3::new(c * r.x - s * r.y, s * r.x + c * r.y, r.z)
    }

    /// Where a point of the body at rest-frame offset `r` lies from the
    /// reference point on the board: turned by the orientation, then
    /// contracted (`contract(rotate(r))`). For a shape that turning leaves
    /// alone (a disc) this is [`Self::contract`].
    #[inline]
    #[must_use]
    pub fn place(&self, r: DVec3) -> DVec3 {
        self.contract(self.rotate(r))
    }

    /// Board-frame velocity, m/s.
    #[inline]
    #[must_use]
    pub fn velocity(&self) -> DVec3 {
        self.velocity
    }

    /// Position at board time `t`, extrapolated along this segment. The time
    /// is taken relative to the segment start before it multiplies anything.
    #[inline]
    #[must_use]
    pub fn position_at(&self, t: f64) -> DVec3 {
        let dt = t - self.start.t;
        if self.deceleration == 0.0 || dt <= 0.0 {
            return self.start.position + self.velocity * dt;
        }
        self.start.position + self.direction * self.braking_law().distance_at(dt)
    }

    /// Proper time at board time `t`: `τ₀ + (t − t₀)/γ` (time dilation) on
    /// a uniform segment, `τ₀ + (c/a)(asinh u₀ − asinh u)` on a braking one
    /// ([`Braking::proper_time_at`]).
    #[inline]
    #[must_use]
    pub fn proper_time_at(&self, t: f64) -> f64 {
        let dt = t - self.start.t;
        if self.deceleration == 0.0 || dt <= 0.0 {
            return self.proper_time + dt * self.inverse_gamma;
        }
        self.proper_time + self.braking_law().proper_time_at(dt)
    }
}

/// The state of a body at one board time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyState {
    /// Board-frame position, m.
    pub position: DVec3,
    /// Proper velocity.
    pub u: ProperVelocity,
    /// Proper time, s.
    pub proper_time: f64,
    /// Rest-frame orientation (accumulated Wigner rotation), radians
    /// counter-clockwise about `+z`; see [`Segment::orientation`].
    pub orientation: f64,
}

/// The history of one body's reference point (a puck's centre on the board,
/// an observer's eye): straight segments joined at kinks where its velocity
/// changed (collisions, cue strokes, a tracker sample); for an observer put
/// somewhere ([`Self::relocate`]) or a puck re-contracted against a cushion
/// as a kick lands ([`Self::shift_last`], a jump of at most `R (1 − 1/γ)`),
/// a jump there instead.
///
/// * **Append-only**: segments are only added at or after the last start;
///   the past is never rewritten, so every view of it (replay, several
///   observers, light-delayed images) stays consistent.
/// * **Queries in O(log S)** by binary search over segment starts.
/// * **Before the first event** the first segment extends back to
///   `t = −∞`: a body keeps its initial state for all earlier times, which is
///   what an observer looking into the scene's past (light delay at t = 0)
///   must see. Proper time is then negative. [`Worldline::rest_before_start`]
///   instead has the body rest at its start until then (struck at the
///   start).
/// * **At a kink** the later segment applies (right-continuous velocity).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Worldline {
    segments: Vec<Segment>,
    c: f64,
    /// Proper deceleration of every moving segment begun from now on, m/s²
    /// (sliding friction `μ g`; 0 on a frictionless table).
    deceleration: f64,
}

impl Worldline {
    /// A worldline through `start` with proper velocity `u`, proper time 0 at
    /// `start`, for a speed of light `c` in m/s.
    #[must_use]
    pub fn new(start: Event, u: ProperVelocity, c: f64) -> Self {
        Self {
            segments: vec![Segment::new(start, u, 0.0, 0.0, c)],
            c,
            deceleration: 0.0,
        }
    }

    /// A worldline through `start` with proper velocity `u` that slides
    /// under sliding friction: every moving segment, the first included,
    /// brakes with proper deceleration `deceleration` (`μ g`, m/s², ≥ 0; 0 is
    /// [`Self::new`]).
    #[must_use]
    pub fn braking(start: Event, u: ProperVelocity, c: f64, deceleration: f64) -> Self {
        let deceleration = if deceleration.is_finite() {
            deceleration.max(0.0)
        } else {
            0.0
        };
        Self {
            segments: vec![Segment::braking(start, u, 0.0, 0.0, c, deceleration)],
            c,
            deceleration,
        }
    }

    /// The proper deceleration its moving segments get, m/s².
    #[must_use]
    pub fn deceleration(&self) -> f64 {
        self.deceleration
    }

    /// The speed of light the segments' velocities were derived with, m/s.
    #[must_use]
    pub fn speed_of_light(&self) -> f64 {
        self.c
    }

    /// All segments, oldest first (never empty).
    #[must_use]
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// The segment in force at board time `t`: O(log S).
    #[must_use]
    pub fn segment_at(&self, t: f64) -> &Segment {
        &self.segments[self.segment_index_at(t)]
    }

    /// Index of the segment in force at board time `t`.
    #[must_use]
    pub fn segment_index_at(&self, t: f64) -> usize {
        self.segments
            .partition_point(|s| s.start.t <= t)
            .saturating_sub(1)
    }

    /// The newest segment.
    #[must_use]
    pub fn last(&self) -> &Segment {
        // `new` creates one segment and nothing removes the first.
        &self.segments[self.segments.len() - 1]
    }

    /// Position at board time `t`, m.
    #[must_use]
    pub fn position_at(&self, t: f64) -> DVec3 {
        self.segment_at(t).position_at(t)
    }

    /// Proper velocity `u = γβ` (dimensionless, board frame) at board time
    /// `t` (the later segment's at a kink).
    #[must_use]
    pub fn proper_velocity_at(&self, t: f64) -> ProperVelocity {
        self.segment_at(t).u_at(t)
    }

    /// Proper time at board time `t`, s.
    #[must_use]
    pub fn proper_time_at(&self, t: f64) -> f64 {
        self.segment_at(t).proper_time_at(t)
    }

    /// Position, velocity and proper time at board time `t`.
    #[must_use]
    pub fn state_at(&self, t: f64) -> BodyState {
        let s = self.segment_at(t);
        BodyState {
            position: s.position_at(t),
            u: s.u_at(t),
            proper_time: s.proper_time_at(t),
            orientation: s.orientation,
        }
    }

    /// The event of this worldline at board time `t`.
    #[must_use]
    pub fn event_at(&self, t: f64) -> Event {
        Event::new(t, self.position_at(t))
    }

    /// Has the body rest at its first segment's start position before that
    /// segment begins, as if struck there and then, instead of extending
    /// its first motion back to `t = −∞`: a rest segment is put first,
    /// starting at the same event (at the start itself the moving segment
    /// applies, velocities being right-continuous). Proper time runs at
    /// the board rate before the start (negative there). Nothing changes
    /// when the first segment is already at rest (it extends back as a
    /// rest), so calling it twice is harmless.
    pub fn rest_before_start(&mut self) {
        let first = self.segments[0];
        if first.u.0 == DVec3::ZERO {
            return;
        }
        let rest = Segment::new(
            first.start,
            ProperVelocity::ZERO,
            first.proper_time,
            first.orientation,
            self.c,
        );
        self.segments.insert(0, rest);
    }

    /// Changes the proper velocity to `u` from board time `t` on (a kink).
    ///
    /// `t` must not precede the last segment's start. A kink at exactly the
    /// last start replaces that segment's velocity (two impulses at one
    /// instant add up), keeping the worldline a function of time. On a
    /// braking worldline ([`Self::braking`]) a moving new segment brakes too;
    /// the Wigner rotation is that of the change from the velocity the body
    /// has at `t`.
    pub fn push(&mut self, t: f64, u: ProperVelocity) -> Result<(), WorldlineError> {
        if !(t.is_finite() && u.is_finite()) {
            return Err(WorldlineError::NotFinite);
        }
        let last = *self.last();
        if t < last.start.t {
            return Err(WorldlineError::BeforeLastSegment {
                at: t,
                last: last.start.t,
            });
        }
        // Torque-free: the new rest frame is the old one boosted within
        // itself; two changes at one instant compose in turn.
        let orientation = last.orientation + rotation_of_velocity_change(last.u_at(t), u);
        let a = self.deceleration;
        if t == last.start.t {
            let i = self.segments.len() - 1;
            self.segments[i] =
                Segment::braking(last.start, u, last.proper_time, orientation, self.c, a);
        } else {
            let start = Event::new(t, last.position_at(t));
            self.segments.push(Segment::braking(
                start,
                u,
                last.proper_time_at(t),
                orientation,
                self.c,
                a,
            ));
        }
        Ok(())
    }

    /// Puts the body at `position` at board time `t`, moving with proper
    /// velocity `u` from then on: a jump, not a kink (the worldline is not
    /// continuous there). Only for an observer the player or a tracker puts
    /// somewhere (the free eye orbited or reset, a tracked head's pose),
    /// never for a puck (whose only jump is [`Self::shift_last`]'s). Proper time runs on across the jump. As with
    /// [`Self::push`], `t` must not precede the last segment's start, and
    /// a jump at exactly that start replaces the last segment.
    pub fn relocate(
        &mut self,
        t: f64,
        position: DVec3,
        u: ProperVelocity,
    ) -> Result<(), WorldlineError> {
        if !(t.is_finite() && u.is_finite() && position.is_finite()) {
            return Err(WorldlineError::NotFinite);
        }
        let last = *self.last();
        if t < last.start.t {
            return Err(WorldlineError::BeforeLastSegment {
                at: t,
                last: last.start.t,
            });
        }
        let orientation = last.orientation + rotation_of_velocity_change(last.u_at(t), u);
        let segment = Segment::new(
            Event::new(t, position),
            u,
            last.proper_time_at(t),
            orientation,
            self.c,
        );
        if t == last.start.t {
            let i = self.segments.len() - 1;
            self.segments[i] = segment;
        } else {
            self.segments.push(segment);
        }
        Ok(())
    }

    /// Moves the last segment, start and all, by `offset` (m, board
    /// frame): a jump of the reference point at that segment's start, as
    /// [`Self::relocate`] makes, keeping the segment's motion (braking
    /// included) and proper time. For a puck only when a kick has just
    /// begun the segment and its new contraction would reach into a
    /// cushion: the body then re-contracts about the rim point the cushion
    /// holds rather than about its centre, a jump of at most `R (1 − 1/γ)`,
    /// the size by which every rim point already jumps when a kick
    /// re-contracts a body at one board time (`physics::billiard`).
    pub fn shift_last(&mut self, offset: DVec3) {
        if !offset.is_finite() {
            return;
        }
        let i = self.segments.len() - 1;
        self.segments[i].start.position += offset;
    }

    /// Ends a braking last segment with a rest segment at its stop time (the
    /// motion is unchanged: a braking segment rests after its stop; the rest
    /// segment makes that explicit). Returns the stop time, or `None` if the
    /// last segment is not braking.
    pub fn come_to_rest(&mut self) -> Option<f64> {
        let t = self.last().stop_time()?;
        self.push(t, ProperVelocity::ZERO).ok()?;
        Some(t)
    }

    /// Keeps only the current (last) segment. For long headless runs that
    /// need neither replay nor a light-delayed view of the past; queries
    /// before the kept segment then extrapolate it backwards.
    pub fn forget_history(&mut self) {
        if self.segments.len() > 1 {
            self.segments.drain(..self.segments.len() - 1);
        }
    }

    /// Forgets the segments that ended at or before board time `t` (a
    /// bounded history): the segment in force at `t` becomes the first, and
    /// queries before it extrapolate it backwards.
    pub fn forget_before(&mut self, t: f64) {
        let keep_from = self.segment_index_at(t);
        if keep_from > 0 {
            self.segments.drain(..keep_from);
        }
    }

    /// Appends `segment`, a copy of a segment of another worldline of the
    /// same body (a CAVE render node copies the master's pucks' new
    /// segments this way, bit for bit). Fails on a non-finite start, or
    /// one before the last segment's.
    pub fn append(&mut self, segment: Segment) -> Result<(), WorldlineError> {
        let t = segment.start.t;
        if !(t.is_finite() && segment.start.position.is_finite() && segment.u.is_finite()) {
            return Err(WorldlineError::NotFinite);
        }
        if !segment.is_consistent() || segment.c != self.c {
            return Err(WorldlineError::Malformed(
                "a segment whose values do not agree",
            ));
        }
        let last = self.last().start.t;
        if t <= last {
            return Err(WorldlineError::BeforeLastSegment { at: t, last });
        }
        self.segments.push(segment);
        Ok(())
    }

    /// Checks a worldline received from elsewhere (a CAVE render node's
    /// copy): at least one segment, each consistent
    /// ([`Segment::is_consistent`]) and of the worldline's `c`, their
    /// starts increasing.
    pub fn check(&self) -> Result<(), WorldlineError> {
        if self.segments.is_empty() {
            return Err(WorldlineError::Malformed("no segment"));
        }
        if !(self.c.is_finite() && self.c > 0.0 && self.deceleration.is_finite()) {
            return Err(WorldlineError::Malformed(
                "a speed of light or deceleration out of range",
            ));
        }
        if !self
            .segments
            .iter()
            .all(|s| s.is_consistent() && s.c == self.c)
        {
            return Err(WorldlineError::Malformed(
                "a segment whose values do not agree",
            ));
        }
        if !self
            .segments
            .windows(2)
            .all(|w| w[0].start.t < w[1].start.t)
        {
            return Err(WorldlineError::Malformed("segments out of order"));
        }
        Ok(())
    }

    /// Forgets every kink after board time `t` (for "what if" replays from a
    /// past moment). The segment in force at `t` is kept.
    pub fn truncate_after(&mut self, t: f64) {
        let keep = self.segment_index_at(t) + 1;
        self.segments.truncate(keep);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_received_worldline_or_segment_that_could_not_be_is_refused() {
        let mut w = Worldline::new(Event::new(0.0, DVec3::ZERO), ProperVelocity::ZERO, 1.0);
        w.push(1.0, ProperVelocity(DVec3::new(0.5, 0.0, 0.0)))
            .unwrap();
        assert_eq!(w.check(), Ok(()));
        let mut copy = w.clone();
        copy.truncate_after(0.5);
        // A segment with a cached value that its velocity does not give.
        let mut json = serde_json::to_value(w.last()).unwrap();
        json["gamma"] = serde_json::json!(3.0);
        let forged: Segment = serde_json::from_value(json).unwrap();
        assert!(!forged.is_consistent());
        assert!(matches!(
            copy.append(forged),
            Err(WorldlineError::Malformed(_))
        ));
        assert_eq!(copy.append(*w.last()), Ok(()));
        assert_eq!(copy, w);
        // A worldline with no segment, or with segments out of order.
        let mut json = serde_json::to_value(&w).unwrap();
        let segments = json["segments"].clone();
        json["segments"] = serde_json::json!([]);
        let empty: Worldline = serde_json::from_value(json.clone()).unwrap();
        assert_eq!(empty.check(), Err(WorldlineError::Malformed("no segment")));
        json["segments"] = serde_json::json!([segments[1], segments[0]]);
        let swapped: Worldline = serde_json::from_value(json).unwrap();
        assert_eq!(
            swapped.check(),
            Err(WorldlineError::Malformed("segments out of order"))
        );
    }

    fn line() -> Worldline {
        // c = 2 m/s, β = 0.6 along x: v = 1.2 m/s, γ = 1.25.
        let u = ProperVelocity::try_from_beta(DVec3::new(0.6, 0.0, 0.0)).unwrap();
        Worldline::new(Event::new(0.0, DVec3::new(1.0, 0.5, 0.0)), u, 2.0)
    }

    #[test]
    fn a_relocated_worldline_jumps_and_keeps_its_past_and_proper_time() {
        let mut w = line();
        let (before, tau) = (w.position_at(1.0), w.proper_time_at(2.0));
        let to = DVec3::new(-3.0, 2.0, 1.0);
        w.relocate(2.0, to, ProperVelocity::ZERO).unwrap();
        assert_eq!(w.position_at(1.0), before);
        assert_eq!(w.position_at(2.0), to);
        assert_eq!(w.position_at(5.0), to);
        assert!((w.proper_time_at(2.0) - tau).abs() < 1e-15);
        assert!((w.proper_time_at(3.0) - tau - 1.0).abs() < 1e-12);
        assert!(w.relocate(1.0, to, ProperVelocity::ZERO).is_err());
        assert!(w.relocate(3.0, DVec3::NAN, ProperVelocity::ZERO).is_err());
    }

    #[test]
    fn uniform_motion_and_time_dilation() {
        let w = line();
        let s = w.state_at(2.0);
        assert!((s.position - DVec3::new(3.4, 0.5, 0.0)).length() < 1e-14);
        assert!((s.proper_time - 1.6).abs() < 1e-14); // 2 s / γ
    }

    #[test]
    fn before_first_event_the_initial_state_extends_back() {
        let w = line();
        let s = w.state_at(-1.0);
        assert!((s.position.x - (1.0 - 1.2)).abs() < 1e-14);
        assert!((s.proper_time + 0.8).abs() < 1e-14);
    }

    #[test]
    fn struck_at_the_start_it_rests_before() {
        let mut w = line();
        w.rest_before_start();
        w.rest_before_start();
        assert_eq!(w.segments().len(), 2);
        let s = w.state_at(-1.0);
        assert_eq!(s.position, DVec3::new(1.0, 0.5, 0.0));
        assert_eq!(s.u, ProperVelocity::ZERO);
        assert!((s.proper_time + 1.0).abs() < 1e-14);
        // From the start on, the motion: at the start itself and after.
        assert!(w.proper_velocity_at(0.0).0.x > 0.7);
        assert!((w.state_at(2.0).position.x - 3.4).abs() < 1e-14);
        assert!((w.proper_time_at(2.0) - 1.6).abs() < 1e-14);
        // A kink at the start replaces the motion, not the rest.
        w.push(0.0, ProperVelocity::ZERO).unwrap();
        assert_eq!(w.position_at(5.0), DVec3::new(1.0, 0.5, 0.0));
    }

    #[test]
    fn kinks_are_continuous_in_position_and_proper_time() {
        let mut w = line();
        w.push(1.0, ProperVelocity::ZERO).unwrap();
        w.push(3.0, ProperVelocity(DVec3::new(0.0, 1.0, 0.0)))
            .unwrap();
        assert_eq!(w.segments().len(), 3);
        // At rest from 1 to 3 s: proper time runs at board rate.
        assert!((w.proper_time_at(3.0) - (0.8 + 2.0)).abs() < 1e-14);
        assert!((w.position_at(2.0) - DVec3::new(2.2, 0.5, 0.0)).length() < 1e-14);
        // After the second kink: β = 1/√2, v = √2 m/s along y.
        let p = w.position_at(4.0);
        assert!((p.y - (0.5 + 2f64.sqrt())).abs() < 1e-14);
        // Right-continuous velocity at a kink.
        assert_eq!(w.proper_velocity_at(1.0), ProperVelocity::ZERO);
        assert!(w.push(2.0, ProperVelocity::ZERO).is_err());
        assert!(w.push(5.0, ProperVelocity(DVec3::NAN)).is_err());
    }

    #[test]
    fn same_instant_kink_replaces_velocity() {
        let mut w = line();
        w.push(1.0, ProperVelocity::ZERO).unwrap();
        w.push(1.0, ProperVelocity(DVec3::X)).unwrap();
        assert_eq!(w.segments().len(), 2);
        assert_eq!(w.proper_velocity_at(1.5), ProperVelocity(DVec3::X));
    }

    #[test]
    fn many_segments_binary_search() {
        let mut w = Worldline::new(Event::default(), ProperVelocity::ZERO, 1.0);
        for i in 1..10_000 {
            let u = ProperVelocity(DVec3::X * if i % 2 == 0 { 0.0 } else { 1.0 });
            w.push(i as f64, u).unwrap();
        }
        // 5 000 moving seconds at β = 1/√2.
        let x = w.position_at(10_000.0).x;
        assert!((x - 5000.0 / 2f64.sqrt()).abs() < 1e-8);
        assert_eq!(w.segment_index_at(4321.5), 4321);
        w.truncate_after(100.5);
        assert_eq!(w.segments().len(), 101);
    }
}
