//! The event loop: run freely to the earliest predicted event, resolve it,
//! re-predict what it changed (the paper's §3.3.2.1 "anticipation").
//!
//! Pucks are held internally in the order of their names, so the outcome
//! (ties between simultaneous events included) does not depend on the order
//! in which a scene lists them; every public index is the caller's own.

use glam::{DVec2, DVec3};
use smallvec::SmallVec;

use super::broadphase::BroadPhase;
use super::calendar::{Calendar, Key, Rank};
use super::overlap;
use super::predict::puck_puck::PairContact;
use super::predict::{Cushion, braking, puck_cushion, puck_puck};
use super::resolve::{self, Body};
use crate::scene::Scene;
use crate::spacetime::{Event, ProperVelocity, rotation_of_velocity_change};
use crate::worldline::{Segment, Worldline};

/// A puck as the physics starts it, at board time 0.
#[derive(Clone, Debug, PartialEq)]
pub struct PuckInit {
    /// Name, for reports.
    pub name: String,
    /// Centre at t = 0, m.
    pub position: DVec2,
    /// Proper velocity at t = 0.
    pub u: ProperVelocity,
    /// Rest radius, m.
    pub radius: f64,
    /// Rest mass, kg.
    pub mass: f64,
}

impl From<&crate::scene::PuckSpec> for PuckInit {
    fn from(p: &crate::scene::PuckSpec) -> Self {
        Self {
            name: p.name.clone(),
            position: p.position,
            u: p.u,
            radius: p.radius,
            mass: p.mass,
        }
    }
}

/// What a collision did to one puck, at its own velocity-change event.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PuckOutcome {
    /// Index of the puck.
    pub puck: usize,
    /// Board time of this puck's velocity change, s.
    pub t: f64,
    /// The puck's centre then, m.
    pub position: DVec3,
    /// Proper velocity just before.
    pub u_before: ProperVelocity,
    /// Proper velocity just after.
    pub u_after: ProperVelocity,
    /// Rest mass before, kg.
    pub mass_before: f64,
    /// Rest mass after (larger after an inelastic puck–puck collision), kg.
    pub mass_after: f64,
    /// True while the velocity change has not yet happened (its board time
    /// is still ahead): the values are the scheduled ones.
    /// Rest-frame orientation after the change (accumulated Thomas–Wigner
    /// rotation), radians counter-clockwise about `+z`; see
    /// [`crate::worldline::Segment::orientation`].
    pub orientation_after: f64,
    pub pending: bool,
}

/// Which kind of collision.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CollisionKind {
    /// Two pucks (three or more when a Zeno sequence among them ends: they
    /// move together, see `Billiard::stats().zeno_merges`).
    PuckPuck,
    /// A puck and a cushion (with the pucks pressing it into the cushion
    /// when a Zeno sequence there ends: they stop moving into it).
    Cushion(Cushion),
}

/// One collision: the contact event and each puck's outcome.
#[derive(Clone, Debug, PartialEq)]
pub struct Collision {
    /// Puck–puck or which cushion.
    pub kind: CollisionKind,
    /// Board time of the contact, s.
    pub t: f64,
    /// Contact point, m.
    pub contact: DVec3,
    /// One outcome per puck involved: two for puck–puck, one for a cushion;
    /// more when a Zeno sequence ends (see [`CollisionKind`]).
    pub pucks: Vec<PuckOutcome>,
    /// The most the two pucks may overlap in the board frame because of
    /// this contact, m (0 for a cushion and for a Zeno cluster's merge, whose
    /// kicks come from no new approach): what rigid bodies cannot avoid in
    /// relativity, see [`overlap_bound`](crate::physics::overlap::bound).
    pub overlap_bound: f64,
}

/// Counters of what the event loop did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Puck–puck contacts resolved.
    pub pair_contacts: u64,
    /// Puck–cushion contacts resolved.
    pub cushion_contacts: u64,
    /// Velocity changes applied.
    pub kicks: u64,
    /// Calendar entries found stale (a partner changed since the
    /// prediction): the puck was predicted again instead.
    pub stale: u64,
    /// Exact pair predictions made (pair frame, and the board where it
    /// decides).
    pub predictions: u64,
    /// Candidate pairs dismissed by the cheap lower bound on their contact
    /// time (rest discs on the board) without an exact prediction.
    pub pruned: u64,
    /// Times a puck left its broad-phase shell (its AABB moved).
    pub shell_moves: u64,
    /// Collisions resolved as perfectly inelastic to end a Zeno sequence.
    pub zeno_merges: u64,
    /// Velocity changes that reached a puck already changed since their
    /// contact (none is expected: pending changes land first, see
    /// `early_kicks`).
    pub overlapping_kicks: u64,
    /// Velocity changes that landed before their scheduled board time,
    /// because the puck met something else first.
    pub early_kicks: u64,
    /// Collision records and worldline segments dropped because they were
    /// older than the history horizon.
    pub forgotten_collisions: u64,
}

impl Stats {
    /// Contacts of either kind.
    pub fn contacts(&self) -> u64 {
        self.pair_contacts + self.cushion_contacts
    }
}

/// A velocity change still ahead: the second kick of a puck–puck contact,
/// at the event on the puck's centre simultaneous with the contact in the
/// pair frame. It is an impulse: if the puck changed meanwhile, the
/// 4-momentum it carries is added to the puck's new state.
#[derive(Clone, Copy, Debug)]
struct Kick {
    puck: u32,
    partner: u32,
    t: f64,
    before: Body,
    after: Body,
    version_at_contact: u32,
    /// Global index of the collision record to complete, if recorded.
    record: Option<u64>,
    slot: usize,
    /// Which contact it belongs to (a running count of pair contacts).
    contact: u64,
}

#[derive(Clone, Debug)]
struct Puck {
    name: String,
    /// Index in the caller's order.
    external: u32,
    radius: f64,
    mass: f64,
    worldline: Worldline,
    version: u32,
    /// Its kicks still ahead (indices into the kick table; rarely more
    /// than two, kept in the record so reading them chases no pointer).
    pending: SmallVec<[usize; 2]>,
    /// The last kick that landed: (contact count, version it left).
    kicked_by: Option<(u64, u32)>,
    /// A pair that has collided and that nothing else has touched since:
    /// (partner, own version, partner's version). Their motion is the
    /// collision's outcome, which separates them in the pair frame: they
    /// are predicted again only on the board, once apart there (their board
    /// shapes, contracted differently, can slide into each other later).
    settled: Option<(u32, u32, u32)>,
    /// Board time of this puck's last contact (pair or cushion) and how
    /// many came in quick succession (Zeno detection, O(1) per puck).
    quick: (f64, u32),
}

/// Consecutive contacts of one puck closer together than this (in units of
/// the time light takes to cross the table) count towards a Zeno sequence.
const ZENO_GAP: f64 = 1e-9;
/// A puck that meets others or a cushion this many times in such quick
/// succession is in a Zeno sequence (inelastic collapse): its collisions
/// with pucks are then perfectly inelastic, and a cushion stops the cluster
/// pressing into it.
const ZENO_COUNT: u32 = 64;

/// What a puck's one pending event is about.
#[derive(Clone, Copy, Debug)]
enum What {
    /// A pending velocity change (index into the kick table).
    Kick(usize),
    /// The puck meets a cushion.
    Cushion(Cushion),
    /// Pucks `a` < `b` meet (one of them is this puck); `partner_version` is
    /// the other's version when predicted.
    Pair {
        a: u32,
        b: u32,
        partner_version: u32,
    },
    /// The puck's centre leaves its broad-phase shell.
    Shell,
    /// The puck's braking segment ends: it comes to rest (sliding friction).
    Stop,
}

/// A puck's pending event: what, and when it was predicted (board time,
/// s). For a pair the winning prediction is kept apart, in
/// `Billiard::hits`, so that it is not computed again when it happens: this
/// small record is what every event reads, the large one only a pair
/// contact.
#[derive(Clone, Copy, Debug)]
struct Next {
    what: What,
    predicted_at: f64,
}

/// What scanning a puck's partners reads of each, packed in one cache line
/// (64 bytes, aligned): its current segment's start (board time s, centre
/// m), board velocity (m/s) and rest radius (m) for the cheap lower bound,
/// and the board time its centre leaves its shell (s), which limits the
/// pair's contacts that count.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct Hot {
    t0: f64,
    x0: DVec2,
    v: DVec2,
    radius: f64,
    /// When the centre leaves its broad-phase shell (infinite if never):
    /// set by `Billiard::predict`, which works it out first.
    exit: f64,
    /// On a braking segment: the uniform bound does not apply.
    braking: bool,
}

impl Default for Hot {
    fn default() -> Self {
        Self {
            t0: 0.0,
            x0: DVec2::ZERO,
            v: DVec2::ZERO,
            radius: 0.0,
            exit: f64::INFINITY,
            braking: false,
        }
    }
}

impl Hot {
    /// Puck's motion now, with shell exit `exit` (s).
    fn of(puck: &Puck, exit: f64) -> Self {
        let s = puck.worldline.last();
        Self {
            t0: s.start.t,
            x0: s.start.position.truncate(),
            v: s.velocity().truncate(),
            radius: puck.radius,
            exit,
            braking: s.is_braking(),
        }
    }

    #[inline]
    fn position_at(&self, t: f64) -> DVec2 {
        self.x0 + self.v * (t - self.t0)
    }
}

/// Width of a broad-phase shell's margin, in mean rest radii: a puck's AABB
/// is its rest disc about the shell's centre grown by this, and moves when
/// the centre has gone that far. Measured best among 0.5 to 3 radii
/// (BENCHMARKS.md): smaller moves shells more often, larger gives each puck
/// more partners to bound.
const SHELL_MARGIN: f64 = 1.5;

/// Proper speed of the pair frame on the board above which a pair-frame
/// contact is checked against the board's first touch (see `contact_of`).
const BOARD_FIRST_U: f64 = 3.0;

/// The relativistic billiard's physics: pucks, their worldlines, and the
/// calendar of what happens next.
#[derive(Clone)]
pub struct Billiard {
    c: f64,
    table: DVec2,
    restitution: f64,
    cushion_restitution: f64,
    /// In name order; `internal[i]` is the caller's puck `i`.
    pucks: Vec<Puck>,
    internal: Vec<u32>,
    time: f64,
    /// One entry per puck: its earliest event.
    calendar: Calendar,
    /// What each puck's entry is about.
    next: Vec<Next>,
    /// For a puck whose entry is a pair contact, the prediction that won
    /// (other entries leave theirs unread).
    hits: Vec<Option<PairContact>>,
    kicks: Vec<Option<Kick>>,
    free_kicks: Vec<usize>,
    contacts_made: u64,
    broad: BroadPhase,
    /// Each puck's shell centre, m (when the centre leaves it is in `hot`).
    shells: Vec<DVec2>,
    /// Shell margin, m.
    margin: f64,
    /// Each puck's current motion, for the cheap bound.
    hot: Vec<Hot>,
    /// Scratch of `predict`: the candidates whose bound (board time, s) can
    /// beat the earliest event, with their index.
    bounded: Vec<(f64, u32)>,
    /// The slow reference path (tests): every pair a candidate, no cheap
    /// bound, each contact computed again when it happens.
    reference: bool,
    /// Driven from outside (a CAVE render node): no events, the worldlines
    /// are written by [`Self::replace_worldline`] and [`Self::extend_worldline`].
    driven: bool,
    /// Kept collision records; `collisions[0]` has global index
    /// `collisions_dropped`.
    collisions: Vec<Collision>,
    collisions_dropped: u64,
    record: bool,
    history: Option<f64>,
    forgotten_before: Option<f64>,
    warnings: Vec<String>,
    /// Whether a Zeno sequence has been reported (once, whichever kind
    /// came first; every one is counted in the stats).
    zeno_said: bool,
    stats: Stats,
}

// ## Building

impl Billiard {
    /// A billiard on a table of `table` metres with speed of light `c`,
    /// restitutions for puck–puck and puck–cushion collisions, and pucks at
    /// board time 0. The caller guarantees what scene validation checks
    /// (finite numbers, pucks on the table and apart).
    pub fn new(
        c: f64,
        table: DVec2,
        restitution: f64,
        cushion_restitution: f64,
        pucks: Vec<PuckInit>,
    ) -> Self {
        let mean_radius = if pucks.is_empty() {
            0.03
        } else {
            pucks.iter().map(|p| p.radius).sum::<f64>() / pucks.len() as f64
        };
        let n = pucks.len();
        let mut pucks: Vec<Puck> = pucks
            .into_iter()
            .enumerate()
            .map(|(k, p)| Puck {
                worldline: Worldline::new(Event::new(0.0, p.position.extend(0.0)), p.u, c),
                name: p.name,
                external: k as u32,
                radius: p.radius,
                mass: p.mass,
                version: 0,
                pending: SmallVec::new(),
                kicked_by: None,
                settled: None,
                quick: (f64::NEG_INFINITY, 0),
            })
            .collect();
        // Canonical order: by name, then (for equal names) by the caller's
        // order. Every tie between simultaneous events is broken in it.
        pucks.sort_by(|a, b| a.name.cmp(&b.name).then(a.external.cmp(&b.external)));
        let mut internal = vec![0u32; n];
        for (i, p) in pucks.iter().enumerate() {
            internal[p.external as usize] = i as u32;
        }
        let mut billiard = Self {
            c,
            table,
            restitution,
            cushion_restitution,
            pucks,
            internal,
            time: 0.0,
            calendar: Calendar::new(n),
            next: vec![
                Next {
                    what: What::Shell,
                    predicted_at: 0.0,
                };
                n
            ],
            hits: vec![None; n],
            kicks: Vec::new(),
            free_kicks: Vec::new(),
            contacts_made: 0,
            broad: BroadPhase::new(&[], &[]),
            shells: vec![DVec2::ZERO; n],
            hot: vec![Hot::default(); n],
            bounded: Vec::new(),
            margin: SHELL_MARGIN * mean_radius,
            reference: false,
            driven: false,
            collisions: Vec::new(),
            collisions_dropped: 0,
            record: true,
            history: None,
            forgotten_before: None,
            warnings: Vec::new(),
            zeno_said: false,
            stats: Stats::default(),
        };
        billiard.start();
        billiard
    }

    /// Every shell about its puck's centre and every puck predicted, at the
    /// current time.
    fn start(&mut self) {
        for i in 0..self.pucks.len() {
            self.shells[i] = self.pucks[i]
                .worldline
                .last()
                .position_at(self.time)
                .truncate();
        }
        self.hot = self
            .pucks
            .iter()
            .map(|p| Hot::of(p, f64::INFINITY))
            .collect();
        let half: Vec<f64> = self.pucks.iter().map(|p| p.radius + self.margin).collect();
        self.broad = BroadPhase::new(&self.shells, &half);
        for i in 0..self.pucks.len() {
            self.hot[i].exit = self.shell_exit(i);
        }
        for i in 0..self.pucks.len() {
            self.predict(i);
        }
    }

    /// Switches to the slow reference path, kept for tests: every pair of
    /// pucks is a candidate (no broad phase), no cheap bound prunes any, and
    /// each pair contact is predicted again when it happens instead of kept.
    /// The physics is the same; a test checks that the fast loop gives the
    /// same contacts. Call before running.
    pub fn set_reference_loop(&mut self, on: bool) {
        self.reference = on;
        self.start();
    }

    /// Puts sliding friction on the table: every moving puck brakes with
    /// proper deceleration `deceleration` (`μ g`, m/s², board frame; 0 is
    /// frictionless), from its state at board time 0 (see
    /// `predict::braking`). Call before running; a non-finite or negative
    /// value is taken as 0.
    pub fn set_sliding_friction(&mut self, deceleration: f64) {
        for puck in &mut self.pucks {
            // A puck resting until struck at its start (`before_start =
            // "rest"`) has that rest segment first, at the same start: the
            // braking begins with the stroke, and the rest is kept.
            let segments = puck.worldline.segments();
            let rests_first = segments.len() > 1
                && segments[0].start.t == segments[1].start.t
                && segments[0].u == ProperVelocity::ZERO;
            let stroke = segments[usize::from(rests_first)];
            puck.worldline = Worldline::braking(stroke.start, stroke.u, self.c, deceleration);
            if rests_first {
                puck.worldline.rest_before_start();
            }
        }
        self.start();
    }

    /// The billiard of a validated scene.
    pub fn from_scene(scene: &Scene) -> Self {
        let pucks = scene.pucks.iter().map(PuckInit::from).collect();
        let mut billiard = Self::new(
            scene.c,
            scene.table.size,
            scene.restitution,
            scene.table.cushion_restitution,
            pucks,
        );
        if scene.table.deceleration() > 0.0 {
            billiard.set_sliding_friction(scene.table.deceleration());
        }
        // `before_start = "rest"`: each puck rests until struck at t = 0.
        if scene.before_start == crate::scene::BeforeStart::Rest {
            for puck in &mut billiard.pucks {
                puck.worldline.rest_before_start();
            }
        }
        billiard
    }

    /// Whether to keep a log of collisions (on by default; long benchmark
    /// runs turn it off).
    pub fn set_recording(&mut self, on: bool) {
        self.record = on;
    }

    /// Whether worldlines keep their whole history (on by default). Off is
    /// `set_history(Some(0.0))`: each keeps only its current segment.
    pub fn set_keep_history(&mut self, on: bool) {
        self.set_history(if on { None } else { Some(0.0) });
    }

    /// How far back, in seconds of board time, the worldlines and the
    /// collision records reach (`None`, the default: the whole run). With a
    /// horizon `h`, worldline segments that ended before `time − h` are
    /// forgotten as the pucks change, and collision records whose contact is
    /// before `time − h` are dropped at the start of the next
    /// [`Self::step_until`] or [`Self::advance_to`] (so what one call
    /// produced can always be read after it). Memory then stays O(N) plus
    /// what happens within `h`. Queries before the horizon extrapolate the
    /// oldest kept segment: [`Self::forgotten_before`] says from when.
    pub fn set_history(&mut self, horizon: Option<f64>) {
        self.history = horizon.map(|h| if h.is_nan() { 0.0 } else { h.max(0.0) });
    }

    /// The history horizon, s (`None`: everything is kept).
    pub fn history(&self) -> Option<f64> {
        self.history
    }
}

// ## Reading the state

impl Billiard {
    /// Speed of light, m/s.
    pub fn c(&self) -> f64 {
        self.c
    }

    /// Table size, m.
    pub fn table(&self) -> DVec2 {
        self.table
    }

    /// Board time up to which every event has been processed, s.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Number of pucks.
    pub fn len(&self) -> usize {
        self.pucks.len()
    }

    /// Whether there are no pucks.
    pub fn is_empty(&self) -> bool {
        self.pucks.is_empty()
    }

    fn puck(&self, i: usize) -> &Puck {
        &self.pucks[self.internal[i] as usize]
    }

    /// Puck `i`'s name.
    pub fn name(&self, i: usize) -> &str {
        &self.puck(i).name
    }

    /// Index of the puck called `name`.
    pub fn index_of(&self, name: &str) -> Option<usize> {
        let k = self.pucks.partition_point(|p| p.name.as_str() < name);
        self.pucks
            .get(k)
            .filter(|p| p.name == name)
            .map(|p| p.external as usize)
    }

    /// Puck `i`'s rest radius, m.
    pub fn radius(&self, i: usize) -> f64 {
        self.puck(i).radius
    }

    /// Puck `i`'s current rest mass, kg (grows in inelastic collisions).
    pub fn mass(&self, i: usize) -> f64 {
        self.puck(i).mass
    }

    /// Puck `i`'s worldline (its centre), complete up to [`Self::time`]
    /// (and back to [`Self::forgotten_before`], if history is bounded).
    pub fn worldline(&self, i: usize) -> &Worldline {
        &self.puck(i).worldline
    }

    /// The kept collision records, in the order processed (that of each
    /// collision's first velocity change, which for a puck–puck contact can
    /// come slightly before the contact itself). A puck–puck collision's second velocity change stays
    /// `pending` until its board time. With a history horizon the oldest
    /// records are dropped: the first one kept has global index
    /// [`Self::collisions_forgotten`].
    pub fn collisions(&self) -> &[Collision] {
        &self.collisions
    }

    /// How many collision records have been dropped (the global index of
    /// `collisions()[0]`).
    pub fn collisions_forgotten(&self) -> u64 {
        self.collisions_dropped
    }

    /// How many collisions have been recorded in all (kept or dropped).
    pub fn collision_count(&self) -> u64 {
        self.collisions_dropped + self.collisions.len() as u64
    }

    /// The kept records from global index `from` on (those before it and
    /// any dropped ones are skipped).
    pub fn collisions_from(&self, from: u64) -> &[Collision] {
        let k = from.saturating_sub(self.collisions_dropped) as usize;
        &self.collisions[k.min(self.collisions.len())..]
    }

    /// Board time before which history has been forgotten (worldline
    /// segments and collision records), if any has.
    pub fn forgotten_before(&self) -> Option<f64> {
        self.forgotten_before
    }

    /// Messages about degraded behaviour (a Zeno sequence ended, …): each
    /// kind is said once; [`Self::stats`] counts every occurrence.
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// Total 4-momentum of the pucks at [`Self::time`], including what is
    /// in transit: the part of a puck–puck collision's transfer whose
    /// second kick is still ahead. Exactly conserved by puck–puck
    /// collisions; cushions change it (they are external).
    pub fn total_momentum(&self) -> crate::spacetime::FourMomentum {
        let bodies = self.pucks.iter().fold(Default::default(), |sum, p| {
            sum + crate::spacetime::FourMomentum::of_body(
                p.mass,
                p.worldline.last().u_at(self.time),
            )
        });
        self.kicks.iter().flatten().fold(bodies, |sum, k| {
            sum + (k.after.momentum() - k.before.momentum())
        })
    }

    /// Counters.
    pub fn stats(&self) -> Stats {
        self.stats
    }
}

// ## Running

impl Billiard {
    /// Processes every event up to board time `t` (the pucks then move
    /// freely to `t`). Going backwards does nothing: the past is kept in the
    /// worldlines, for replay.
    pub fn advance_to(&mut self, t: f64) {
        while !self.step_until(t, usize::MAX) {}
    }

    /// Processes at most `max_events` calendar entries at or before board
    /// time `t`. Returns `true` when every event up to `t` is done (the
    /// billiard's time is then `t`), `false` if it stopped early (call
    /// again): a long run in bounded steps, so a caller can stream the
    /// records, show progress or stop.
    pub fn step_until(&mut self, t: f64, max_events: usize) -> bool {
        self.trim_records();
        if t.is_nan() || t <= self.time {
            return true;
        }
        if self.driven {
            self.time = t;
            return true;
        }
        let mut done = 0usize;
        while let Some((key, i)) = self.calendar.peek() {
            if key.t > t {
                break;
            }
            if done >= max_events {
                return false;
            }
            self.handle(i as usize, key.t);
            done += 1;
        }
        self.time = t;
        true
    }

    /// Adds a momentum impulse to puck `i` at board time `t` (≥ the current
    /// time; earlier means now): its proper velocity grows by `du` (an
    /// impulse `J` on a puck of mass `m` is `du = J / (m c)`). A push of any
    /// size leaves it below `c`. Fails on a non-finite `du`, and on one
    /// that would take |u| = γ|β| beyond [`crate::scene::MAX_U`]: the
    /// puck keeps its velocity, and nothing changes unless it takes a
    /// collision's kick still pending first, to find that out.
    pub fn apply_impulse(
        &mut self,
        i: usize,
        t: f64,
        du: DVec3,
    ) -> Result<(), crate::worldline::WorldlineError> {
        if !du.is_finite() || !t.is_finite() {
            return Err(crate::worldline::WorldlineError::NotFinite);
        }
        let i = self.internal[i] as usize;
        let t = t.max(self.time);
        // Too large for the velocity the puck has now: refused before
        // anything moves (the check below, after the run to `t` and the
        // puck's pending kicks, catches the rest).
        let ahead = (self.pucks[i].worldline.last().u_at(t).0 + du).length();
        if ahead > crate::scene::MAX_U {
            return Err(crate::worldline::WorldlineError::TooFast(ahead));
        }
        self.advance_to(t);
        self.flush_pending(i);
        let puck = &mut self.pucks[i];
        let u = ProperVelocity(puck.worldline.last().u_at(t).0 + du);
        if u.0.length() > crate::scene::MAX_U {
            return Err(crate::worldline::WorldlineError::TooFast(u.0.length()));
        }
        puck.worldline
            .push(t.max(puck.worldline.last().start.t), u)?;
        self.bump(i);
        Ok(())
    }

    /// Stops predicting anything: from now on the worldlines are written from
    /// outside, by [`Self::replace_worldline`] and [`Self::extend_worldline`],
    /// and running ahead only moves the board time. A CAVE render node
    /// drives its copy of the master's billiard this way, so that every wall
    /// sees the master's worldlines bit for bit. Pending kicks are dropped.
    pub fn drive_from_outside(&mut self) {
        self.driven = true;
        for i in 0..self.pucks.len() {
            self.calendar.remove(i as u32);
        }
        self.kicks.clear();
        self.free_kicks.clear();
    }

    /// Whether the worldlines are written from outside
    /// ([`Self::drive_from_outside`]).
    pub fn is_driven(&self) -> bool {
        self.driven
    }

    /// Puts `worldline` in place of puck `i`'s (a copy of another billiard's
    /// puck), trimmed to the history horizon. Only for a billiard driven
    /// from outside: otherwise it is re-predicted as after an impulse.
    pub fn replace_worldline(&mut self, i: usize, worldline: Worldline) {
        let k = self.internal[i] as usize;
        self.pucks[k].worldline = worldline;
        self.written(k);
    }

    /// Appends `segments` (copies of another billiard's puck `i`'s newest
    /// segments, in time order) to puck `i`'s worldline, trimmed to the
    /// history horizon. Fails, leaving what was appended before the bad
    /// one, on a segment that is not finite or does not start after the
    /// last one.
    pub fn extend_worldline(
        &mut self,
        i: usize,
        segments: &[crate::worldline::Segment],
    ) -> Result<(), crate::worldline::WorldlineError> {
        let k = self.internal[i] as usize;
        let mut result = Ok(());
        for s in segments {
            result = self.pucks[k].worldline.append(*s);
            if result.is_err() {
                break;
            }
        }
        self.written(k);
        result
    }

    /// Puck `k` (internal index) was written from outside.
    fn written(&mut self, k: usize) {
        if self.driven {
            let puck = &mut self.pucks[k];
            puck.version = puck.version.wrapping_add(1);
            if let Some(h) = self.history {
                let cutoff = self.time - h;
                if puck.worldline.segments().len() > 1
                    && puck.worldline.segments()[1].start.t <= cutoff
                {
                    puck.worldline.forget_before(cutoff);
                }
            }
        } else {
            self.bump(k);
        }
    }

    /// Handles puck `i`'s pending event, due at board time `t`.
    fn handle(&mut self, i: usize, t: f64) {
        let next = self.next[i];
        self.calendar.remove(i as u32);
        self.fetch_upcoming(false);
        self.time = self.time.max(t);
        let version = self.pucks[i].version;
        match next.what {
            What::Kick(k) => {
                if self.kicks[k].is_some_and(|kick| kick.puck as usize == i) {
                    self.land_kick(k);
                }
            }
            What::Cushion(cushion) => {
                // A pending kick lands first: re-predicted with its news.
                if !self.flush_pending(i) {
                    self.cushion_contact(i, cushion, t);
                }
            }
            What::Pair {
                a,
                b,
                partner_version,
            } => {
                let (a, b) = (a as usize, b as usize);
                let j = if a == i { b } else { a };
                if self.pucks[j].version != partner_version || self.pending_with(a, b) {
                    self.stats.stale += 1;
                } else {
                    let flushed_a = self.flush_pending(a);
                    let flushed_b = self.flush_pending(b);
                    // Else re-predicted with the news they carried.
                    if !(flushed_a || flushed_b) {
                        self.pair_contact(a, b, self.hits[i], next.predicted_at);
                    }
                }
            }
            What::Shell => self.move_shell(i),
            What::Stop => {
                // The motion is unchanged (a braking segment rests after its
                // stop): no new version, predictions made stay valid.
                self.pucks[i].worldline.come_to_rest();
                self.hot[i] = Hot::of(&self.pucks[i], self.hot[i].exit);
            }
        }
        // Unchanged (a stale entry, a shell move): predicted again; changed
        // pucks were predicted as they changed.
        if self.pucks[i].version == version {
            self.predict(i);
        }
        self.fetch_upcoming(true);
    }

    /// Asks for the records the next event will read first (its puck's
    /// pending event, record, motion and partner list), scattered over
    /// memory at large N, so that fetching them overlaps the handling of
    /// this one (a hint: nothing changes if the next event turns out to be
    /// another). With `deep`, also what those records point to (the
    /// newest segment, the partner list if it spilled to the heap): read
    /// once the records themselves have arrived.
    fn fetch_upcoming(&self, deep: bool) {
        if self.reference {
            return;
        }
        let Some(j) = self.calendar.upcoming() else {
            return;
        };
        let j = j as usize;
        let puck = &self.pucks[j];
        if deep {
            prefetch(puck.worldline.last());
            prefetch(self.broad.partners(j));
        } else {
            prefetch(&self.next[j]);
            prefetch_all(puck);
            prefetch(&self.hot[j]);
            prefetch(self.broad.partners_record(j));
        }
    }

    /// Puck `i` left its shell: a new shell about its centre now, and the
    /// candidate pairs that brings (it is then predicted again).
    fn move_shell(&mut self, i: usize) {
        self.stats.shell_moves += 1;
        self.shells[i] = self.pucks[i]
            .worldline
            .last()
            .position_at(self.time)
            .truncate();
        self.broad
            .set_shell(i, self.shells[i], self.pucks[i].radius + self.margin);
    }

    /// A puck about to meet something while the second kick of an earlier
    /// contact is still ahead of it takes that kick now, so every collision
    /// starts from the puck's complete state and 4-momentum stays exactly
    /// conserved. Returns whether anything landed (the puck then has new
    /// predictions).
    fn flush_pending(&mut self, i: usize) -> bool {
        if self.pucks[i].pending.is_empty() {
            return false;
        }
        let mut ids = std::mem::take(&mut self.pucks[i].pending);
        ids.sort_by(|&x, &y| {
            let (kx, ky) = (
                self.kicks[x].map_or(0.0, |k| k.t),
                self.kicks[y].map_or(0.0, |k| k.t),
            );
            kx.total_cmp(&ky).then(x.cmp(&y))
        });
        self.pucks[i].pending = ids.clone();
        for id in ids {
            self.stats.early_kicks += 1;
            self.land_kick(id);
        }
        true
    }

    fn cushion_contact(&mut self, i: usize, cushion: Cushion, t: f64) {
        self.time = self.time.max(t);
        let puck = &mut self.pucks[i];
        let t_kink = t.max(puck.worldline.last().start.t);
        let before = puck.worldline.last().u_at(t_kink);
        let outward = cushion.outward();
        let zeno = self.quick_streak(i, t_kink) >= ZENO_COUNT;
        // In a Zeno sequence against this cushion (pucks pressed into it by
        // others moving with them): the cluster stops moving into the
        // cushion, the limit of the sequence.
        let cluster = if zeno {
            self.pressed_cluster(i, before, t_kink)
        } else {
            vec![i]
        };
        let after = if zeno {
            ProperVelocity(before.0 - outward * before.0.dot(outward))
        } else {
            resolve::puck_cushion(before, outward, self.cushion_restitution)
        };
        let mut outcomes = Vec::with_capacity(cluster.len());
        for &k in &cluster {
            let puck = &mut self.pucks[k];
            if puck.worldline.push(t_kink, after).is_err() {
                continue;
            }
            outcomes.push(PuckOutcome {
                puck: puck.external as usize,
                t: t_kink,
                position: puck.worldline.position_at(t_kink),
                u_before: before,
                u_after: after,
                mass_before: puck.mass,
                mass_after: puck.mass,
                orientation_after: puck.worldline.last().orientation,
                pending: false,
            });
        }
        if outcomes.is_empty() {
            return;
        }
        self.stats.cushion_contacts += 1;
        if zeno {
            self.stats.zeno_merges += 1;
            if !self.zeno_said {
                self.zeno_said = true;
                self.warnings.push(format!(
                    "t = {t_kink} s: puck \"{}\" was pressed into cushion {} {ZENO_COUNT} times within {:.3e} s \
                     (inelastic collapse); it and the {} puck(s) pressing it with one velocity \
                     stop moving into the cushion (said once; every one is counted)",
                    self.pucks[i].name,
                    cushion.name(),
                    ZENO_GAP * self.table.length() / self.c,
                    cluster.len() - 1
                ));
            }
        }
        if self.record {
            let radius = self.pucks[i].radius;
            let contact =
                outcomes[0].position + puck_cushion::support_offset(radius, before, cushion);
            self.collisions.push(Collision {
                kind: CollisionKind::Cushion(cushion),
                t: t_kink,
                contact,
                pucks: outcomes,
                overlap_bound: 0.0,
            });
        }
        for k in cluster {
            self.bump(k);
        }
    }

    /// The pucks that can touch puck `m` now: its broad-phase partners
    /// (every puck, on the reference path), in index order, so a cluster
    /// grows in the same order either way.
    fn neighbours(&self, m: usize) -> Vec<usize> {
        if self.reference {
            return (0..self.pucks.len()).filter(|&j| j != m).collect();
        }
        let mut near: Vec<usize> = self.broad.partners(m).iter().map(|&j| j as usize).collect();
        near.sort_unstable();
        near
    }

    /// The pucks pressed into a cushion together with puck `i`: `i` and
    /// every puck reached from it through touching pucks (centres at most
    /// the sum of radii apart at board time `t`, m) that move with the same
    /// proper velocity `u` and have no kick pending.
    fn pressed_cluster(&self, i: usize, u: ProperVelocity, t: f64) -> Vec<usize> {
        let same = |w: ProperVelocity| (w.0 - u.0).length() <= 1e-12 * u.0.length();
        self.touching_cluster(vec![i], t, |p| {
            p.pending.is_empty() && same(p.worldline.last().u_at(t))
        })
    }

    /// `seeds` and every puck reached from them through touching pucks
    /// (centres at most the sum of radii apart at board time `t`, m) that
    /// `joins` accepts, in the order reached.
    fn touching_cluster(
        &self,
        mut cluster: Vec<usize>,
        t: f64,
        joins: impl Fn(&Puck) -> bool,
    ) -> Vec<usize> {
        let centre = |k: usize| self.pucks[k].worldline.last().position_at(t);
        let mut k = 0;
        while k < cluster.len() {
            let (m, xm) = (cluster[k], centre(cluster[k]));
            for j in self.neighbours(m) {
                let p = &self.pucks[j];
                if cluster.contains(&j) || !joins(p) {
                    continue;
                }
                let reach = (p.radius + self.pucks[m].radius) * (1.0 + 1e-9);
                if (centre(j) - xm).length() <= reach {
                    cluster.push(j);
                }
            }
            k += 1;
        }
        cluster
    }

    /// Resolves the contact of pucks `a` < `b` predicted at board time
    /// `predicted_at` (s) as `kept`: that prediction, or (the reference path)
    /// one computed again from the same state, bit for bit.
    fn pair_contact(&mut self, a: usize, b: usize, kept: Option<PairContact>, predicted_at: f64) {
        let hit = if self.reference {
            self.contact_of(a, b, predicted_at, self.settled(a, b))
        } else {
            kept
        };
        let Some(hit) = hit else {
            return;
        };
        self.stats.pair_contacts += 1;
        self.contacts_made += 1;
        let contact_id = self.contacts_made;
        // Kick times: never before now (a contact found already
        // overlapping is resolved at once).
        let times = [hit.kicks[0].t.max(self.time), hit.kicks[1].t.max(self.time)];
        // Each puck's state at its own kick (it may be braking meanwhile).
        let body = |p: &Puck, t: f64| Body {
            mass: p.mass,
            u: p.worldline.last().u_at(t),
        };
        let before = [
            body(&self.pucks[a], times[0]),
            body(&self.pucks[b], times[1]),
        ];
        // Counted at the board time it is processed (its first kick), as a
        // cushion contact is: a contact's own time can lie later (between
        // the kicks), and a sequence alternating with a cushion would then
        // never look quick.
        let zeno = self.in_zeno_sequence(a, b, self.time);
        if zeno && self.merge_zeno_cluster(a, b, hit.contact.position) {
            return;
        }
        let restitution = if zeno { 0.0 } else { self.restitution };
        let after = if hit.on_board {
            self.board_push(a, b, before, hit.normal, restitution)
        } else {
            resolve::puck_puck(
                before[0],
                before[1],
                hit.normal,
                hit.pair_frame,
                restitution,
            )
        };
        // The overlap bound is reported only in the collision record: with
        // recording off (long runs) its board-frame depth test, a full
        // overlap scan, is skipped.
        let overlap_bound = if !self.record {
            0.0
        } else {
            let first = if times[0] <= times[1] { 0 } else { 1 };
            let second = 1 - first;
            let closing = after[first].u.velocity(self.c) - before[second].u.velocity(self.c);
            let (ra, rb) = (self.pucks[a].radius, self.pucks[b].radius);
            let early = overlap::depth(
                &self.pucks[a].worldline.last().tangent_at(times[first]),
                ra,
                &self.pucks[b].worldline.last().tangent_at(times[first]),
                rb,
                times[first],
            );
            overlap::bound(
                [ra, rb],
                hit.gamma_pair,
                (times[second] - times[first]) * closing.length(),
                early,
            )
        };

        let record = self.record.then(|| {
            let pucks = [a, b]
                .iter()
                .enumerate()
                .map(|(k, &i)| PuckOutcome {
                    puck: self.pucks[i].external as usize,
                    t: times[k],
                    position: hit.kicks[k].position,
                    u_before: before[k].u,
                    u_after: after[k].u,
                    mass_before: before[k].mass,
                    mass_after: after[k].mass,
                    // As scheduled; set again when the kick is taken.
                    orientation_after: self.pucks[i].worldline.last().orientation
                        + rotation_of_velocity_change(before[k].u, after[k].u),
                    pending: true,
                })
                .collect();
            self.collisions.push(Collision {
                kind: CollisionKind::PuckPuck,
                t: hit.contact.t.max(self.time),
                contact: hit.contact.position,
                pucks,
                overlap_bound,
            });
            self.collision_count() - 1
        });
        let mut ids = [0usize; 2];
        for (k, (&i, &j)) in [a, b].iter().zip([b, a].iter()).enumerate() {
            let kick = Kick {
                puck: i as u32,
                partner: j as u32,
                t: times[k],
                before: before[k],
                after: after[k],
                version_at_contact: self.pucks[i].version,
                record,
                slot: k,
                contact: contact_id,
            };
            let id = match self.free_kicks.pop() {
                Some(id) => {
                    self.kicks[id] = Some(kick);
                    id
                }
                None => {
                    self.kicks.push(Some(kick));
                    self.kicks.len() - 1
                }
            };
            self.pucks[i].pending.push(id);
            ids[k] = id;
        }
        // The kicks that are due land now, earliest first; a later one
        // becomes its puck's pending event if it is the earliest.
        let order = if times[0] <= times[1] { [0, 1] } else { [1, 0] };
        for k in order {
            let id = ids[k];
            if times[k] <= self.time {
                self.land_kick(id);
            } else {
                self.offer_kick([a, b][k], id, times[k]);
            }
        }
    }

    /// A kick of puck `i` at board time `t` has been scheduled and nothing
    /// else about the puck changed: it becomes the puck's pending event if
    /// it comes first.
    fn offer_kick(&mut self, i: usize, id: usize, t: f64) {
        let key = Key {
            t,
            rank: Rank::kick(i as u32),
        };
        if self.calendar.key(i as u32).is_none_or(|k| key.before(&k)) {
            self.next[i] = Next {
                what: What::Kick(id),
                predicted_at: self.time,
            };
            self.calendar.set(i as u32, key);
        }
    }

    /// The outcome of a contact found on the board (pucks `a`, `b` touching
    /// or overlapping there now, closing along `normal`), both kicks now.
    ///
    /// Restitution 0: the pair moves together ([`resolve::together`]), the
    /// outcome a pair-frame contact with restitution 0 has too (all the
    /// kinetic energy of the relative motion becomes heat, whatever the
    /// normal). Both then have one velocity and one contraction, so their
    /// board shapes translate together: the overlap the kick leaves
    /// (within the contact's bound: each shape grows by at most
    /// `R (1 − 1/γ)`) never deepens and they never meet again until
    /// something else changes one of them. An impulse along the normal
    /// alone would leave them sliding past each other; at γ ≳ 10³ the
    /// reshaped shapes could then slide back into each other (the seed-15
    /// case of `collision_integrity`).
    ///
    /// Otherwise an impulse along the board's penetration direction
    /// ([`resolve::puck_puck_board`]);
    /// that kick changes both pucks' contraction at once, so the new shapes
    /// can still overlap and close along a new penetration direction: the
    /// push is repeated along it, at the same instant, until they open (at
    /// most 16 times), elastically: the first push kept the fraction
    /// `restitution` of the CM kinetic energy, the contact's whole loss.
    /// Each push conserves 4-momentum exactly, and the whole is one contact.
    fn board_push(
        &self,
        a: usize,
        b: usize,
        before: [Body; 2],
        normal: DVec3,
        restitution: f64,
    ) -> [Body; 2] {
        if restitution <= 0.0 {
            return resolve::together(before[0], before[1]);
        }
        let mut after = resolve::puck_puck_board(before[0], before[1], normal, restitution);
        let t = self.time;
        let (ra, rb) = (self.pucks[a].radius, self.pucks[b].radius);
        let xa = Event::new(t, self.pucks[a].worldline.last().position_at(t));
        let xb = Event::new(t, self.pucks[b].worldline.last().position_at(t));
        for _ in 0..16 {
            let wa = Worldline::new(xa, after[0].u, self.c);
            let wb = Worldline::new(xb, after[1].u, self.c);
            let (sa, sb) = (wa.last(), wb.last());
            let v_rel = sb.velocity() - sa.velocity();
            let still = 1e-12 * (sa.velocity().length() + sb.velocity().length());
            let m = match overlap::penetration(sa, ra, sb, rb, t) {
                // Still overlapping: closing along the new direction?
                Some((_, m)) if m.dot(v_rel) < -still => m,
                Some(_) => break,
                // Apart: would sliding bring them together again?
                None => match self.touch_again(xa, ra, after[0].u, xb, rb, after[1].u) {
                    Some(m) if m.dot(v_rel) < -still => m,
                    _ => break,
                },
            };
            // The first push took the contact's heat: the repeats, the same
            // contact, are elastic, so the CM kinetic energy kept is `e`
            // (each at `e` kept `e²`, `e³`, …: issue 30).
            after = resolve::puck_puck_board(after[0], after[1], m, 1.0);
        }
        after
    }

    /// Whether two pucks leaving the board events `xa`, `xb` (m, s) with
    /// proper velocities `ua`, `ub` will overlap on the board again while
    /// their centres are within reach: the direction (from `a` towards `b`)
    /// along which they then meet, if they do.
    fn touch_again(
        &self,
        xa: Event,
        ra: f64,
        ua: ProperVelocity,
        xb: Event,
        rb: f64,
        ub: ProperVelocity,
    ) -> Option<DVec3> {
        let (wa, wb) = (
            Worldline::new(xa, ua, self.c),
            Worldline::new(xb, ub, self.c),
        );
        let (sa, sb) = (wa.last(), wb.last());
        let d0 = xb.position - xa.position;
        let v = sb.velocity() - sa.velocity();
        let vv = v.length_squared();
        let reach = ra + rb;
        let (p, q) = (d0.dot(v), d0.length_squared() - reach * reach);
        let disc = p * p - vv * q;
        if vv == 0.0 || disc < 0.0 {
            return None;
        }
        let leave = (-p + disc.sqrt()) / vv;
        if leave <= 0.0 {
            return None;
        }
        let t0 = xa.t;
        let t = overlap::first_touch(sa, ra, sb, rb, t0, t0 + leave)?;
        let d = sb.position_at(t) - sa.position_at(t);
        Some(overlap::gap(sa, ra, sb, rb, d).1)
    }

    fn land_kick(&mut self, id: usize) {
        let Some(kick) = self.kicks[id].take() else {
            return;
        };
        self.free_kicks.push(id);
        let i = kick.puck as usize;
        let puck = &mut self.pucks[i];
        puck.pending.retain(|k| *k != id);
        // At its scheduled time, or now if it lands early (flushed).
        let t = kick.t.min(self.time).max(puck.worldline.last().start.t);
        let now = Body {
            mass: puck.mass,
            u: puck.worldline.last().u_at(t),
        };
        // Unchanged since the contact and (on a braking segment) landing at
        // its own time: the scheduled outcome. A braking puck whose kick
        // lands early (flushed) has not yet slowed to the state the outcome
        // was worked from: it takes the contact's transfer as below.
        let as_scheduled = now.u == kick.before.u;
        let next = if puck.version == kick.version_at_contact && as_scheduled {
            kick.after
        } else {
            // The puck was changed again before this kick's board time: add
            // this contact's 4-momentum transfer to its present 4-momentum.
            // Energy and momentum stay exactly conserved; the difference
            // from a rigid body's outcome shows as a change of rest mass.
            if puck.version != kick.version_at_contact {
                self.stats.overlapping_kicks += 1;
            }
            let p = now.momentum() + (kick.after.momentum() - kick.before.momentum());
            let mass = p.invariant_mass();
            if mass > 1e-3 * now.mass && p.energy > 0.0 {
                Body {
                    mass,
                    u: ProperVelocity(p.momentum / mass),
                }
            } else {
                Body {
                    mass: now.mass,
                    u: ProperVelocity(p.momentum / now.mass),
                }
            }
        };
        if puck.worldline.push(t, next.u).is_err() {
            return;
        }
        puck.mass = next.mass;
        self.stats.kicks += 1;
        if let Some(r) = kick.record
            && let Some(k) = r.checked_sub(self.collisions_dropped)
            && let Some(record) = self.collisions.get_mut(k as usize)
        {
            record.pucks[kick.slot] = PuckOutcome {
                puck: puck.external as usize,
                t,
                position: puck.worldline.position_at(t),
                u_before: now.u,
                u_after: next.u,
                mass_before: now.mass,
                mass_after: next.mass,
                orientation_after: puck.worldline.last().orientation,
                pending: false,
            };
        }
        // The version this change leaves; if the partner has taken its own
        // kick of this contact and nothing else since, the pair is settled.
        let version = self.pucks[i].version.wrapping_add(1);
        self.pucks[i].kicked_by = Some((kick.contact, version));
        let j = kick.partner as usize;
        let partner_done = !self.pucks[j]
            .pending
            .iter()
            .any(|&k| self.kicks[k].is_some_and(|other| other.contact == kick.contact));
        if partner_done && self.pucks[j].kicked_by == Some((kick.contact, self.pucks[j].version)) {
            self.pucks[i].settled = Some((j as u32, version, self.pucks[j].version));
            self.pucks[j].settled = Some((i as u32, self.pucks[j].version, version));
        }
        self.bump(i);
    }

    /// Whether this contact of `a` and `b` at board time `t` is part of a
    /// Zeno sequence (inelastic collapse: contacts closer and closer in
    /// time); it is then perfectly inelastic. The first time, a warning says
    /// so.
    fn in_zeno_sequence(&mut self, a: usize, b: usize, t: f64) -> bool {
        let streak = self.quick_streak(a, t).max(self.quick_streak(b, t));
        if streak < ZENO_COUNT {
            return false;
        }
        // Not reset: every contact of the sequence from here on is
        // inelastic, until a pause longer than the Zeno gap (a sequence
        // against a cushion ends there, see `cushion_contact`).
        self.stats.zeno_merges += 1;
        if !self.zeno_said {
            self.zeno_said = true;
            self.warnings.push(format!(
                "t = {t} s: pucks \"{}\" and \"{}\" met others {ZENO_COUNT} times within {:.3e} s \
                 (inelastic collapse); such a collision is made perfectly inelastic so they move \
                 together (said once; every one is counted)",
                self.pucks[a].name,
                self.pucks[b].name,
                ZENO_GAP * self.table.length() / self.c
            ));
        }
        true
    }

    /// Ends a Zeno sequence of three or more pucks at once (a light puck
    /// crushed between two heavy ones converging: pairwise inelastic
    /// contacts only approach the end, for ever): the cluster of touching
    /// pucks in the sequence (each had a contact within the Zeno gap),
    /// reached from `a` and `b`, moves together ([`resolve::together_all`])
    /// now, at this board time (the limit of the sequence, whatever the
    /// pair frames' kick times), after any kick still ahead of a member has
    /// landed. One collision record holds every puck of the cluster.
    /// Returns `false` (nothing done) if the cluster is just the pair.
    fn merge_zeno_cluster(&mut self, a: usize, b: usize, contact: DVec3) -> bool {
        let t = self.time;
        let gap = ZENO_GAP * self.table.length() / self.c;
        let cluster = self.touching_cluster(vec![a, b], t, |p| t - p.quick.0 < gap);
        if cluster.len() < 3 {
            return false;
        }
        // Kicks still ahead of a member (the far end of an earlier contact)
        // land now, so the merge starts from each one's complete state.
        for &i in &cluster {
            self.flush_pending(i);
        }
        let before: Vec<Body> = cluster
            .iter()
            .map(|&i| Body {
                mass: self.pucks[i].mass,
                u: self.pucks[i].worldline.last().u_at(t),
            })
            .collect();
        let after = resolve::together_all(&before);
        self.stats.pair_contacts += 1;
        self.contacts_made += 1;
        let mut outcomes = Vec::with_capacity(cluster.len());
        for (k, &i) in cluster.iter().enumerate() {
            let puck = &mut self.pucks[i];
            if puck.worldline.push(t, after[k].u).is_err() {
                continue;
            }
            puck.mass = after[k].mass;
            self.stats.kicks += 1;
            outcomes.push(PuckOutcome {
                puck: puck.external as usize,
                t,
                position: puck.worldline.position_at(t),
                u_before: before[k].u,
                u_after: after[k].u,
                mass_before: before[k].mass,
                mass_after: after[k].mass,
                orientation_after: puck.worldline.last().orientation,
                pending: false,
            });
        }
        if self.record {
            self.collisions.push(Collision {
                kind: CollisionKind::PuckPuck,
                t,
                contact,
                pucks: outcomes,
                overlap_bound: 0.0,
            });
        }
        for i in cluster {
            self.bump(i);
        }
        true
    }

    /// Counts a contact of puck `i` at board time `t` (s) towards its Zeno
    /// sequence: returns how many contacts in a row came within the Zeno gap
    /// of the one before.
    fn quick_streak(&mut self, i: usize, t: f64) -> u32 {
        let gap = ZENO_GAP * self.table.length() / self.c;
        let quick = &mut self.pucks[i].quick;
        quick.1 = if t - quick.0 < gap { quick.1 + 1 } else { 0 };
        quick.0 = t;
        quick.1
    }
}

// ## Prediction bookkeeping

impl Billiard {
    fn mover(&self, i: usize) -> puck_puck::Mover<'_> {
        puck_puck::Mover {
            segment: self.pucks[i].worldline.last(),
            radius: self.pucks[i].radius,
        }
    }

    /// Whether pucks `a` and `b` have collided and nothing has changed
    /// either since.
    fn settled(&self, a: usize, b: usize) -> bool {
        let (pa, pb) = (&self.pucks[a], &self.pucks[b]);
        pa.settled == Some((b as u32, pa.version, pb.version))
    }

    /// The next contact of pucks `a` and `b` from board time `now` on.
    ///
    /// Normally the closed-form prediction ([`puck_puck::predict`]), in the
    /// pair frame. But the board slice is not the pair frame's, and a kick
    /// (from a cushion or a third puck) changes a puck's contraction at once
    /// and begins a new segment whose backward extension the pair-frame
    /// solve cannot tell from the real past. So the board picture decides
    /// where the pair-frame one is silent:
    ///
    /// * pucks overlapping on the board and closing (the penetration depth
    ///   grows) are pushed apart at once: a contact at `now`, normal along
    ///   the penetration direction, both kicks at `now` (the board is the
    ///   frame in which that overlap is defined); if they are opening, the
    ///   depth shrinks to nothing with no event (it is concave in time);
    /// * pucks apart on the board for which the pair frame finds no contact
    ///   ahead, but whose board shapes will meet (a concave gap function
    ///   crossing zero, [`overlap::first_touch`]), meet then, the same way.
    ///
    /// `board_only`: a settled pair (see `Puck::settled`): the pair frame is
    /// not asked (its contact is the one just resolved), only the board, and
    /// while the contact's own overlap lasts nothing is predicted.
    ///
    /// Both board searches (an overlap scan per time tried)
    /// are skipped for a pair that [`overlap::apart_throughout`] proves
    /// apart on the board for as long as their rest discs overlap: they
    /// would find nothing.
    fn contact_of(&self, a: usize, b: usize, now: f64, board_only: bool) -> Option<PairContact> {
        let (pa, pb) = (&self.pucks[a], &self.pucks[b]);
        let (sa, sb) = (pa.worldline.last(), pb.worldline.last());
        if sa.is_braking() || sb.is_braking() {
            return braking::pair(self.mover(a), self.mover(b), self.c, now);
        }
        let on_board = |t: f64, m: DVec3, depth: f64| PairContact {
            contact: Event::new(
                t,
                sa.position_at(t) + m * (pa.radius * sa.contract(m).length() - 0.5 * depth),
            ),
            kicks: [
                Event::new(t, sa.position_at(t)),
                Event::new(t, sb.position_at(t)),
            ],
            normal: m,
            pair_frame: ProperVelocity::ZERO,
            gamma_pair: sa.gamma().max(sb.gamma()),
            on_board: true,
        };
        let v_rel = sb.velocity() - sa.velocity();
        // A closing speed below this is rounding (relative to the speeds).
        let still = 1e-12 * (sa.velocity().length() + sb.velocity().length());
        let d0 = sb.position_at(now) - sa.position_at(now);
        // How long the centres stay within reach of each other (rest discs
        // overlapping), if they are or come so; before and after, the board
        // shapes, inside their rest discs, are apart.
        let leave = leaves_reach(d0, v_rel, pa.radius + pb.radius);
        // Proved apart on the board over that whole window (a cheap
        // one-sided test, made only where a search would follow): the
        // penetration test now and the board's first touch below would find
        // nothing, so neither search is made.
        // (Not on the reference path, which keeps the searches themselves
        // so that the test comparing the two paths checks these proofs.)
        let apart = || {
            !self.reference
                && leave.is_some_and(|leave| {
                    overlap::apart_throughout(sa, pa.radius, sb, pb.radius, now, now + leave)
                })
        };
        let mut proved_apart = None;
        if overlap::penetration_needs_scan(sa, pa.radius, sb, pb.radius, d0) {
            // A settled pair proved still overlapping (a cheap one-sided
            // test): the penetration test would find it so, and nothing is
            // predicted.
            if board_only
                && !self.reference
                && overlap::overlap_certain(sa, pa.radius, sb, pb.radius, now)
            {
                return None;
            }
            let is_apart = *proved_apart.insert(apart());
            if !is_apart
                && let Some((depth, m)) = overlap::penetration(sa, pa.radius, sb, pb.radius, now)
            {
                if board_only {
                    return None; // a settled pair's own overlap: it only opens
                }
                return (m.dot(v_rel) < -still).then(|| on_board(now, m, depth));
            }
        }
        if !board_only
            && let Some(hit) = puck_puck::predict(self.mover(a), self.mover(b), self.c, now)
        {
            // The board shapes can meet well before the pair frame's first
            // kick when the pair frame moves fast on the board (a very fast
            // puck crossing a slower one's path: the pair frame's slice is
            // far from the board's). Then the board decides, at its first
            // touch. Checked only for a pair frame faster than
            // `BOARD_FIRST_U` (proper speed; below it the slices differ by
            // a fraction of a contact and the pair frame keeps the contact)
            // whose unperturbed shapes overlap on the board at that kick.
            let first = hit.kicks[0].t.min(hit.kicks[1].t);
            if first > now
                && hit.pair_frame.0.length_squared() > BOARD_FIRST_U * BOARD_FIRST_U
                && overlap::depth(sa, pa.radius, sb, pb.radius, first) > 0.0
                && let Some(t) = overlap::first_touch(sa, pa.radius, sb, pb.radius, now, first)
                && t < first
            {
                let d = sb.position_at(t) - sa.position_at(t);
                let (_, normal) = overlap::gap(sa, pa.radius, sb, pb.radius, d);
                return Some(on_board(t.max(now), normal, 0.0));
            }
            return Some(hit);
        }
        // Apart now, and the pair frame sees nothing ahead: will the board
        // shapes meet? Only while the centres are within reach.
        let end = now + leave?;
        if proved_apart.unwrap_or_else(apart) {
            return None;
        }
        // A separating axis along which they do not close: never.
        let (g, m) = overlap::gap(sa, pa.radius, sb, pb.radius, d0);
        if g <= 0.0 && m.dot(v_rel) >= 0.0 {
            return None;
        }
        let t = overlap::first_touch(sa, pa.radius, sb, pb.radius, now, end)?.max(now);
        let (_, normal) = overlap::gap(sa, pa.radius, sb, pb.radius, d0 + v_rel * (t - now));
        Some(on_board(t, normal, 0.0))
    }

    /// Puck `i`'s worldline changed: it gets a new version (predictions
    /// made with the old one go stale), its history is trimmed to the
    /// horizon, and it is predicted again.
    fn bump(&mut self, i: usize) {
        let puck = &mut self.pucks[i];
        puck.version = puck.version.wrapping_add(1);
        if let Some(h) = self.history {
            let cutoff = self.time - h;
            if puck.worldline.segments().len() > 1 && puck.worldline.segments()[1].start.t <= cutoff
            {
                puck.worldline.forget_before(cutoff);
                self.forgotten_before =
                    Some(self.forgotten_before.map_or(cutoff, |f| f.max(cutoff)));
            }
        }
        self.hot[i] = Hot::of(&self.pucks[i], self.hot[i].exit);
        self.predict(i);
    }

    /// Applies the history horizon to the collision records now (it is
    /// otherwise applied as each [`Self::step_until`] starts): for a caller
    /// that wants `collisions()` to hold only the horizon after a long call.
    pub fn forget_old_records(&mut self) {
        self.trim_records();
    }

    /// Drops the finished collision records older than the history horizon:
    /// those whose every velocity change is before `time − h`, from the
    /// front (records are in the order their first kick was processed; a
    /// record still pending and all after it stay).
    fn trim_records(&mut self) {
        let Some(h) = self.history else {
            return;
        };
        let cutoff = self.time - h;
        let k = self
            .collisions
            .iter()
            .position(|c| c.pucks.iter().any(|p| p.pending || p.t > cutoff))
            .unwrap_or(self.collisions.len());
        if k > 0 {
            self.collisions.drain(..k);
            self.collisions_dropped += k as u64;
            self.stats.forgotten_collisions += k as u64;
            self.forgotten_before = Some(self.forgotten_before.map_or(cutoff, |f| f.max(cutoff)));
        }
    }

    fn pending_with(&self, a: usize, b: usize) -> bool {
        let waits = |x: usize, y: usize| {
            self.pucks[x]
                .pending
                .iter()
                .any(|&k| self.kicks[k].is_some_and(|kick| kick.partner as usize == y))
        };
        waits(a, b) || waits(b, a)
    }

    /// Puck `i`'s pending event from now on: the earliest of its pending
    /// velocity changes, its cushion contacts, its shell exit and its
    /// contacts with its candidate partners. A pair's exact prediction is
    /// made only if a cheap lower bound on its time ([`disc_touch`]) can
    /// beat the earliest found so far; a pair contact later than either
    /// puck's shell exit is left for the shell move to find (so the outcome
    /// does not depend on which pairs the broad phase reports beyond what
    /// the shells guarantee).
    fn predict(&mut self, i: usize) {
        // The partners' records are scattered over `hot`: ask for them all
        // now, so that fetching them overlaps the work below.
        if !self.reference {
            for &j in self.broad.partners(i) {
                prefetch(&self.hot[j as usize]);
            }
        }
        let now = self.time;
        let mut best = Key::NEVER;
        let mut next = Next {
            what: What::Shell,
            predicted_at: now,
        };
        let mut won = None;
        let puck = &self.pucks[i];
        for &k in &puck.pending {
            if let Some(kick) = self.kicks[k] {
                let key = Key {
                    t: kick.t.max(now),
                    rank: Rank::kick(i as u32),
                };
                if key.before(&best) {
                    best = key;
                    next.what = What::Kick(k);
                }
            }
        }
        let segment = puck.worldline.last();
        // The centre stays in its shell until the shell exit, which is an
        // event of its own, so a cushion the shell's disc (its margin and
        // the rest radius, inside which the contracted puck lies) does not
        // reach cannot be met before it: not worked out. The reach is grown
        // by far more than the rounding of the positions.
        let exit = self.shell_exit(i);
        let shell = self.shells[i];
        let reach = self.margin + puck.radius + 1e-9 * (self.table.x + self.table.y);
        let from_shell = [
            shell.x,
            self.table.x - shell.x,
            shell.y,
            self.table.y - shell.y,
        ];
        for (k, cushion) in Cushion::ALL.into_iter().enumerate() {
            if from_shell[k] > reach && !self.reference {
                continue;
            }
            if let Some(t) = braking::cushion_time(segment, puck.radius, self.table, cushion, now) {
                let key = Key {
                    t,
                    rank: Rank::cushion(i as u32, k as u32),
                };
                if key.before(&best) {
                    best = key;
                    next.what = What::Cushion(cushion);
                }
            }
        }
        self.hot[i].exit = exit;
        let key = Key {
            t: exit,
            rank: Rank::shell(i as u32),
        };
        if key.before(&best) {
            best = key;
            next.what = What::Shell;
        }
        if let Some(stop) = segment.stop_time() {
            let key = Key {
                t: stop.max(now),
                rank: Rank::stop(i as u32),
            };
            if key.before(&best) {
                best = key;
                next.what = What::Stop;
            }
        }
        // The candidates: the broad phase's partners, or (the reference
        // path) every other puck.
        let (partners, everyone) = if self.reference {
            (&[][..], 0..self.pucks.len())
        } else {
            (self.broad.partners(i), 0..0)
        };
        let candidates = partners
            .iter()
            .map(|&j| j as usize)
            .chain(everyone.filter(|&j| j != i));
        // Counted here, added to the stats after the scan.
        let (mut pruned, mut predictions) = (0, 0);
        // First the cheap bound of every candidate: those that can beat the
        // earliest event so far are kept, then solved exactly in the order
        // of their bounds, so that the first exact contacts found prune the
        // rest. The winner is the earliest key whatever the order (a pair
        // pruned can only have a later contact than the one that pruned
        // it), so this order changes how many solves are made, never the
        // outcome.
        let mut bounded = std::mem::take(&mut self.bounded);
        bounded.clear();
        // This puck's side of every bound, worked out once.
        let own = self.hot[i];
        let own_now = own.position_at(now);
        for j in candidates {
            if self.reference {
                bounded.push((f64::NEG_INFINITY, j as u32));
                continue;
            }
            let other = &self.hot[j];
            let limit = best.t.min(other.exit);
            let bound = if own.braking || other.braking {
                let (a, b) = (i.min(j), i.max(j));
                braking_touch(
                    self.pucks[a].worldline.last(),
                    self.pucks[a].radius,
                    self.pucks[b].worldline.last(),
                    self.pucks[b].radius,
                    now,
                )
            } else {
                disc_touch(own_now, own.v, own.radius, other, now)
            };
            match bound {
                Some(t) if t <= limit => {
                    // Its records are read if it is solved: asked for now.
                    prefetch_all(&self.pucks[j]);
                    bounded.push((t, j as u32));
                }
                _ => pruned += 1,
            }
        }
        // Insertion sort (a handful of entries), stable: the reference
        // path's all-equal bounds keep the partners' order.
        for k in 1..bounded.len() {
            let mut m = k;
            while m > 0 && bounded[m - 1].0 > bounded[m].0 {
                bounded.swap(m - 1, m);
                m -= 1;
            }
        }
        for &(bound, j) in &bounded {
            if bound > best.t {
                pruned += 1;
                continue; // and every later one: counted as pruned
            }
            let j = j as usize;
            // Its newest segment is read by the solve: asked for before the
            // checks below.
            prefetch(self.pucks[j].worldline.last());
            let (a, b) = (i.min(j), i.max(j));
            let limit = best.t.min(self.hot[j].exit);
            if self.pending_with(a, b) {
                continue; // the second kick of their last contact is still ahead
            }
            // Collided, and nothing has touched them since: the outcome
            // separates them in the pair frame, so only the board can bring
            // them together again (two shapes contracted differently
            // sliding into each other after they have parted, seed 339 of
            // `collision_integrity`). While the contact's own overlap lasts,
            // or on braking worldlines, nothing is predicted.
            // (That overlap is tested in `contact_of`.)
            let settled = self.settled(a, b);
            if settled && (self.hot[a].braking || self.hot[b].braking) {
                continue;
            }
            predictions += 1;
            let Some(hit) = self.contact_of(a, b, now, settled) else {
                continue;
            };
            // Processed at the earliest of the two kicks (the contact lies
            // between them in board time).
            let t = hit.kicks[0]
                .t
                .min(hit.kicks[1].t)
                .min(hit.contact.t)
                .max(now);
            let key = Key {
                t,
                rank: Rank::pair(a as u32, b as u32),
            };
            if t <= limit && key.before(&best) {
                best = key;
                next.what = What::Pair {
                    a: a as u32,
                    b: b as u32,
                    partner_version: self.pucks[j].version,
                };
                won = Some(hit);
            }
        }
        self.bounded = bounded;
        self.stats.pruned += pruned;
        self.stats.predictions += predictions;
        if matches!(next.what, What::Pair { .. }) {
            self.hits[i] = won;
        }
        self.next[i] = next;
        self.calendar.set(i as u32, best);
    }

    /// The board time at which puck `i`'s centre, on its current segment,
    /// leaves its shell (infinite if it never does).
    fn shell_exit(&self, i: usize) -> f64 {
        let s = self.pucks[i].worldline.last();
        if s.is_braking() {
            return braking::shell_exit(s, self.shells[i], self.margin, self.time);
        }
        let v = s.velocity().truncate();
        let vv = v.length_squared();
        if vv == 0.0 {
            return f64::INFINITY;
        }
        let d = s.position_at(self.time).truncate() - self.shells[i];
        let q = d.length_squared() - self.margin * self.margin;
        if q >= 0.0 {
            return self.time; // already out (rounding)
        }
        // |d + v τ|² = margin²: the positive root, in a form without
        // cancellation (q < 0).
        let p = d.dot(v);
        let root = (p * p - vv * q).sqrt();
        let tau = if p >= 0.0 {
            -q / (p + root)
        } else {
            (root - p) / vv
        };
        self.time + tau
    }
}

/// Asks the processor to bring `value`'s (first) cache line in ahead of
/// its use (a hint: nothing is read, and the results cannot change).
#[inline(always)]
fn prefetch<T: ?Sized>(value: &T) {
    prefetch_line((value as *const T).cast::<u8>());
}

/// [`prefetch`] of every cache line `value` touches (from the 64-byte
/// boundary at or below its start: a record need not be aligned to one).
#[inline(always)]
fn prefetch_all<T>(value: &T) {
    let start = (value as *const T).cast::<u8>();
    let below = start as usize % 64;
    let first = start.wrapping_sub(below);
    for offset in (0..below + std::mem::size_of::<T>()).step_by(64) {
        prefetch_line(first.wrapping_add(offset));
    }
}

/// The cache line of `address` into the cache (any address: never read).
#[inline(always)]
fn prefetch_line(address: *const u8) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        // SAFETY: SSE is part of x86_64's baseline, and a prefetch never
        // faults nor reads memory the program sees (any address is allowed).
        unsafe { _mm_prefetch::<_MM_HINT_T0>(address.cast::<i8>()) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = address;
}

/// How long after now (s) two centres `d0` apart (m, b − a) moving apart
/// at `v` (m/s, b − a) stay within `reach` (m) of each other: the later root
/// of `|d0 + v τ|² = reach²`, if it is positive; `None` if they never are
/// within reach from now on (or do not move relative to each other).
fn leaves_reach(d0: DVec3, v: DVec3, reach: f64) -> Option<f64> {
    let vv = v.length_squared();
    if vv == 0.0 {
        return None;
    }
    let (p, q) = (d0.dot(v), d0.length_squared() - reach * reach);
    let disc = p * p - vv * q;
    if disc < 0.0 {
        return None;
    }
    let leave = (-p + disc.sqrt()) / vv;
    (leave > 0.0).then_some(leave)
}

/// A lower bound on the board time at which pucks on segments `sa` and
/// `sb` (rest radii `ra`, `rb`, m) can touch from `now` on, when either is
/// braking (for two uniform segments [`disc_touch`] is sharper); `None`
/// when they never can. Each centre moves on a straight line, never faster
/// than at `now` (braking only slows it: `|x(t) − x(now)| ≤ |v(now)| (t −
/// now)`), and a braking one no farther than to where it stops. Every
/// Lorentz-contracted (or Born-rigid) body lies inside its rest disc, so
/// the pucks touch only once the two displacements together have closed
/// the gap between the rest discs, `|Δx(now)| − ra − rb`. The gap is
/// shrunk by 1e-9 relative so rounding never makes the bound late.
fn braking_touch(sa: &Segment, ra: f64, sb: &Segment, rb: f64, now: f64) -> Option<f64> {
    let motion = |s: &Segment| {
        let x = s.position_at(now).truncate();
        let speed = s.velocity_at(now).truncate().length();
        let left = s.stop_time().map_or(f64::INFINITY, |stop| {
            (s.position_at(stop.max(now)).truncate() - x).length()
        });
        (x, speed, if s.is_rest() { 0.0 } else { left })
    };
    let (xa, va, la) = motion(sa);
    let (xb, vb, lb) = motion(sb);
    let gap = ((xb - xa).length() - (ra + rb)) * (1.0 - 1e-9) - 1e-12;
    if gap <= 0.0 {
        return Some(now);
    }
    if la + lb < gap {
        return None; // they stop apart
    }
    let closing = va + vb;
    (closing > 0.0).then(|| now + gap / closing)
}

/// A lower bound on when two pucks, moving uniformly as `a` and `b` say,
/// can next have a contact event or a velocity change of it, from board
/// time `now`: the board time at which their rest discs
/// first touch (`now` if they overlap), or `None` if they never do (they
/// miss or recede). Classical and cheap: a quadratic on the board.
///
/// Why it bounds: a contracted puck lies inside its rest disc, so the board
/// shapes cannot meet before the rest discs do; and at the earlier of the
/// two kicks of a pair-frame contact the board distance of the centres is
/// at most `R_a + R_b`. (In the pair frame let the kicks `K_a`, `K_b` be
/// `Δx′` apart, `p = Δx′·n` along the approach; the contact of the similar
/// ellipses gives `|Δx′|² = S² − u′²p²`. The event on the later puck's
/// worldline a proper time `λ` earlier, on the board slice of the first
/// kick, is then at interval `S² − (u′p − λ)² ≤ S²` from it, and board
/// simultaneous events' interval is their board distance squared.) The
/// reach is grown by 1e-9 so rounding never makes the bound late.
///
/// `a` is given by its centre at `now` (m), velocity (m/s) and rest radius
/// (m), worked out once for all its partners. The result is the same to
/// the bit with `a` and `b` exchanged (negating both `d` and `v` is exact),
/// so it does not depend on which of the pair is scanning.
#[inline]
fn disc_touch(a_now: DVec2, a_v: DVec2, a_radius: f64, b: &Hot, now: f64) -> Option<f64> {
    let d = b.position_at(now) - a_now;
    let reach = (a_radius + b.radius) * (1.0 + 1e-9);
    let q = d.length_squared() - reach * reach;
    if q <= 0.0 {
        return Some(now);
    }
    let v = b.v - a_v;
    let p = d.dot(v);
    if p >= 0.0 {
        return None; // receding or parallel
    }
    let vv = v.length_squared();
    let disc = p * p - vv * q;
    if disc < 0.0 {
        return None; // they pass wide
    }
    // The earlier root of |d + v τ|² = reach², without cancellation.
    Some(now + q / (disc.sqrt() - p))
}
