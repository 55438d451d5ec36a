//! The event loop: run freely to the earliest predicted event, resolve it,
//! re-predict what it changed (the paper's §3.3.2.1 "anticipation").
//!
//! Pucks are held internally in the order of their names, so the outcome
//! (ties between simultaneous events included) does not depend on the order
//! in which a scene lists them; every public index is the caller's own.
//!
//! This file holds the types (the billiard, its pucks, kicks, pending
//! events, records); the one `impl Billiard` is split by concern, as
//! rapier splits its `physics_pipeline`:
//!
//! * `build`: building and the switches set before running;
//! * `state`: reading the state;
//! * `run`: the loop (take the earliest event, hand it on);
//! * `anticipate`: each puck's next event (the pair policy and the cheap
//!   bounds it schedules are the pure functions of `predict::pair` and
//!   `predict::bounds`);
//! * `contact`: resolving cushion and pair contacts;
//! * `simultaneous`: contacts on one puck at one board time, together;
//! * `kicks`: velocity changes still ahead, and impulses from outside;
//! * `zeno`: Zeno sequences (inelastic collapse);
//! * `history`: the history horizon and a puck's versions;
//! * `driven`: a billiard whose worldlines are written from outside;
//! * `prefetch`: cache hints.

use glam::{DVec2, DVec3};
use smallvec::SmallVec;

use super::broadphase::BroadPhase;
use super::calendar::{Calendar, Key, Rank};
use super::overlap;
use super::predict::puck_puck::PairContact;
use super::predict::{Cushion, bounds, braking, pair, puck_cushion, puck_puck};
use super::resolve::{self, Body};
use crate::scene::Scene;
use crate::spacetime::{Event, ProperVelocity, rotation_of_velocity_change};
use crate::worldline::Worldline;

mod anticipate;
mod build;
mod contact;
mod driven;
mod history;
mod kicks;
mod prefetch;
mod run;
mod simultaneous;
mod state;
mod zeno;

use prefetch::{prefetch, prefetch_all};

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
    /// Rest-frame orientation after the change (accumulated Thomas–Wigner
    /// rotation), radians counter-clockwise about `+z`; see
    /// [`crate::worldline::Segment::orientation`].
    pub orientation_after: f64,
    /// True while the velocity change has not yet happened (its board time
    /// is still ahead): the values are the scheduled ones.
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
    /// more when a Zeno sequence ends (see [`CollisionKind`]) or when
    /// contacts on one puck at one board time are resolved together (see
    /// `simultaneous`).
    pub pucks: Vec<PuckOutcome>,
    /// The most the two pucks may overlap in the board frame because of
    /// this contact, m (0 for a cushion and for a Zeno cluster's merge, whose
    /// kicks come from no new approach): what rigid bodies cannot avoid in
    /// relativity, see [`overlap_bound`](crate::physics::overlap::bound);
    /// for contacts resolved together, the largest of their pairs'.
    pub overlap_bound: f64,
    /// Several contacts at one board time resolved together
    /// ([`crate::physics::resolve::simultaneous`]): `pucks` holds every
    /// puck of the group, `pairs` the contacts among them (`contact` is
    /// the point of the first).
    pub simultaneous: bool,
    /// For contacts resolved together, each pair in contact, as indices
    /// into `pucks`; empty otherwise (a pair contact is `pucks[0]` with
    /// `pucks[1]`).
    pub pairs: Vec<[usize; 2]>,
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
    /// Kicks whose new contraction would have put the puck's board shape
    /// into a cushion: it re-contracted about the rim point the cushion
    /// holds instead (`Billiard::hold_off_cushions`).
    pub cushion_holds: u64,
    /// Groups of contacts at one board time resolved together
    /// (`resolve::simultaneous`); each contact is also counted in
    /// `pair_contacts`.
    pub simultaneous_contacts: u64,
}

impl Stats {
    /// Contacts of either kind.
    #[must_use]
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
    /// Whether its pair is settled once both have taken their kicks
    /// (`Puck::kicked_by`): a pair contact's outcome separates the two in
    /// the pair frame; one of several contacts resolved together need not
    /// (`simultaneous`), so such a pair is predicted again as any other.
    settles: bool,
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
    /// The last kick that landed: (contact count, version it left, its
    /// partner in the contact). Two pucks whose last kicks are of one
    /// contact, one the other's partner, and unchanged since, have
    /// collided and nothing has touched either since: a *settled* pair
    /// (`Billiard::settled`). Their motion is the collision's outcome,
    /// which separates them in the pair frame: they are predicted again
    /// only on the board, once apart there (their board shapes, contracted
    /// differently, can slide into each other later).
    kicked_by: Option<(u64, u32, u32)>,
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

    /// Whether this puck's and `other`'s rest discs (one of them braking
    /// at `deceleration`, m/s²; `c` m/s), grown so that their touch bounds
    /// a contact's earlier kick ([`bounds::kick_growth`]: a kick can come
    /// before its contact on the cloth), are shown apart from board time
    /// `now` to `limit` (s) from these records alone
    /// ([`bounds::braking_apart_until`], no braking law): the first test of
    /// a braking pair, before [`bounds::braking_kick`]. `false` says
    /// nothing.
    #[inline]
    fn braking_apart_until(
        &self,
        other: &Hot,
        deceleration: f64,
        c: f64,
        now: f64,
        limit: f64,
    ) -> bool {
        let beta = self.v.length().max(other.v.length()) / c;
        let decelerations =
            deceleration * (f64::from(u8::from(self.braking)) + f64::from(u8::from(other.braking)));
        let grown = bounds::kick_growth(beta, self.radius.max(other.radius), c, decelerations);
        let (mut start_a, mut start_b) = (self.start(), other.start());
        start_a.radius += grown;
        start_b.radius += grown;
        bounds::braking_apart_until(&start_a, &start_b, deceleration, now, limit)
    }

    /// What [`bounds::braking_apart_until`] reads of it.
    #[inline]
    fn start(&self) -> bounds::SegmentStart {
        bounds::SegmentStart {
            t0: self.t0,
            x0: self.x0,
            v: self.v,
            radius: self.radius,
            braking: self.braking,
        }
    }
}

/// Width of a broad-phase shell's margin, in mean rest radii: a puck's AABB
/// is its rest disc about the shell's centre grown by this, and moves when
/// the centre has gone that far. Measured best among 0.5 to 3 radii
/// (BENCHMARKS.md): smaller moves shells more often, larger gives each puck
/// more partners to bound.
const SHELL_MARGIN: f64 = 1.5;

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
    /// The board time the running `step_until` goes to (s; events due
    /// together with one being handled are taken only up to it).
    until: f64,
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
    /// The largest proper deceleration of any puck's braking segments,
    /// m/s² (0 without friction): the braking pairs' first bound
    /// ([`bounds::braking_apart_until`]) uses it.
    deceleration: f64,
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
