//! The event loop: run freely to the earliest predicted event, resolve it,
//! re-predict what it changed (the paper's §3.3.2.1 "anticipation").
//!
//! Pucks are held internally in the order of their names, so the outcome
//! (ties between simultaneous events included) does not depend on the order
//! in which a scene lists them; every public index is the caller's own.

use glam::{DVec2, DVec3};

use super::broadphase::BroadPhase;
use super::calendar::{Calendar, Entry, Slot};
use super::overlap;
use super::predict::puck_puck::PairContact;
use super::predict::{Cushion, puck_cushion, puck_puck};
use super::resolve::{self, Body};
use crate::scene::Scene;
use crate::spacetime::{Event, ProperVelocity, rotation_of_velocity_change};
use crate::worldline::Worldline;

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
    /// Two pucks.
    PuckPuck,
    /// A puck and a cushion.
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
    /// One outcome per puck involved (two for puck–puck, one for a cushion).
    pub pucks: Vec<PuckOutcome>,
    /// The most the two pucks may overlap in the board frame because of
    /// this contact, m (0 for a cushion): what rigid bodies cannot avoid in
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
    /// Calendar entries dropped as stale.
    pub stale: u64,
    /// Closed-form predictions made.
    pub predictions: u64,
    /// Look-ahead windows started.
    pub windows: u64,
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
    generation: u32,
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
    pending: Vec<usize>,
    /// The last kick that landed: (contact count, version it left).
    kicked_by: Option<(u64, u32)>,
    /// A pair that has collided and that nothing else has touched since:
    /// (partner, own version, partner's version). Their motion is the
    /// collision's outcome, which separates, so they are not predicted
    /// again until one of them changes.
    settled: Option<(u32, u32, u32)>,
    /// Board time of this puck's last pair contact and how many came in
    /// quick succession (Zeno detection, O(1) per puck).
    quick: (f64, u32),
}

/// Consecutive contacts of one puck closer together than this (in units of
/// the time light takes to cross the table) count towards a Zeno sequence.
const ZENO_GAP: f64 = 1e-9;
/// A puck that meets others this many times in such quick succession ends
/// the sequence: its next collision is perfectly inelastic.
const ZENO_COUNT: u32 = 64;

/// The relativistic billiard's physics: pucks, their worldlines, and the
/// calendar of what happens next.
pub struct Billiard {
    c: f64,
    table: DVec2,
    restitution: f64,
    cushion_restitution: f64,
    /// In name order; `internal[i]` is the caller's puck `i`.
    pucks: Vec<Puck>,
    internal: Vec<u32>,
    time: f64,
    calendar: Calendar,
    kicks: Vec<Option<Kick>>,
    free_kicks: Vec<usize>,
    kick_generation: u32,
    contacts_made: u64,
    broad: BroadPhase,
    window_end: f64,
    /// Kept collision records; `collisions[0]` has global index
    /// `collisions_dropped`.
    collisions: Vec<Collision>,
    collisions_dropped: u64,
    record: bool,
    history: Option<f64>,
    forgotten_before: Option<f64>,
    warnings: Vec<String>,
    stats: Stats,
    scratch: Vec<(u32, u32)>,
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
                pending: Vec::new(),
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
            calendar: Calendar::default(),
            kicks: Vec::new(),
            free_kicks: Vec::new(),
            kick_generation: 0,
            contacts_made: 0,
            broad: BroadPhase::new(n, mean_radius),
            window_end: 0.0,
            collisions: Vec::new(),
            collisions_dropped: 0,
            record: true,
            history: None,
            forgotten_before: None,
            warnings: Vec::new(),
            stats: Stats::default(),
            scratch: Vec::new(),
        };
        billiard.start_window(0.0);
        billiard
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
            sum + crate::spacetime::FourMomentum::of_body(p.mass, p.worldline.last().u)
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
        let mut done = 0usize;
        while let Some(entry) = self.calendar.peek().copied() {
            if entry.t > t {
                break;
            }
            if done >= max_events {
                return false;
            }
            self.calendar.pop();
            self.handle(entry);
            done += 1;
        }
        self.time = t;
        true
    }

    /// Adds a momentum impulse to puck `i` at board time `t` (≥ the current
    /// time; earlier means now): its proper velocity grows by `du` (an
    /// impulse `J` on a puck of mass `m` is `du = J / (m c)`). A push of any
    /// size leaves it below `c`. Fails on a non-finite `du`.
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
        self.advance_to(t);
        self.flush_pending(i);
        let puck = &mut self.pucks[i];
        let u = ProperVelocity(puck.worldline.last().u.0 + du);
        puck.worldline
            .push(t.max(puck.worldline.last().start.t), u)?;
        self.bump(i);
        // The look-ahead window was sized for the old speeds.
        self.start_window(self.time);
        Ok(())
    }

    fn handle(&mut self, entry: Entry) {
        match entry.slot {
            Slot::Kick(k) => {
                if self.kicks[k].is_some_and(|kick| kick.generation == entry.versions[0]) {
                    self.time = self.time.max(entry.t);
                    self.land_kick(k);
                }
            }
            Slot::Cushion(i, cushion) => {
                let i = i as usize;
                if self.pucks[i].version != entry.versions[0] {
                    self.stats.stale += 1;
                    return;
                }
                self.time = self.time.max(entry.t);
                if self.flush_pending(i) {
                    return; // re-predicted with the news the puck carried
                }
                self.cushion_contact(i, cushion, entry.t);
            }
            Slot::Pair(a, b) => {
                let (ia, ib) = (a as usize, b as usize);
                if self.pucks[ia].version != entry.versions[0]
                    || self.pucks[ib].version != entry.versions[1]
                    || self.pending_with(ia, ib)
                {
                    self.stats.stale += 1;
                    return;
                }
                self.time = self.time.max(entry.t);
                let flushed_a = self.flush_pending(ia);
                let flushed_b = self.flush_pending(ib);
                if flushed_a || flushed_b {
                    return; // re-predicted with the news they carried
                }
                self.pair_contact(ia, ib, entry.predicted_at);
            }
            Slot::Horizon => self.start_window(entry.t),
        }
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
        let before = puck.worldline.last().u;
        let after = resolve::puck_cushion(before, cushion.outward(), self.cushion_restitution);
        let t_kink = t.max(puck.worldline.last().start.t);
        if puck.worldline.push(t_kink, after).is_err() {
            return;
        }
        self.stats.cushion_contacts += 1;
        if self.record {
            let position = puck.worldline.position_at(t_kink);
            let contact = position + puck_cushion::support_offset(puck.radius, before, cushion);
            let outcome = PuckOutcome {
                puck: puck.external as usize,
                t: t_kink,
                position,
                u_before: before,
                u_after: after,
                mass_before: puck.mass,
                mass_after: puck.mass,
                orientation_after: puck.worldline.last().orientation,
                pending: false,
            };
            self.collisions.push(Collision {
                kind: CollisionKind::Cushion(cushion),
                t: t_kink,
                contact,
                pucks: vec![outcome],
                overlap_bound: 0.0,
            });
        }
        self.bump(i);
    }

    fn pair_contact(&mut self, a: usize, b: usize, predicted_at: f64) {
        let Some(hit) = self.contact_of(a, b, predicted_at) else {
            return;
        };
        self.stats.pair_contacts += 1;
        self.contacts_made += 1;
        let contact_id = self.contacts_made;
        let body = |p: &Puck| Body {
            mass: p.mass,
            u: p.worldline.last().u,
        };
        let before = [body(&self.pucks[a]), body(&self.pucks[b])];
        let restitution = self.zeno_restitution(a, b, hit.contact.t);
        let after = if hit.on_board {
            resolve::puck_puck_board(before[0], before[1], hit.normal, restitution)
        } else {
            resolve::puck_puck(
                before[0],
                before[1],
                hit.normal,
                hit.pair_frame,
                restitution,
            )
        };
        // Kick times: never before now (a contact found already
        // overlapping is resolved at once).
        let times = [hit.kicks[0].t.max(self.time), hit.kicks[1].t.max(self.time)];
        let overlap_bound = {
            let first = if times[0] <= times[1] { 0 } else { 1 };
            let second = 1 - first;
            let closing = after[first].u.velocity(self.c) - before[second].u.velocity(self.c);
            let (ra, rb) = (self.pucks[a].radius, self.pucks[b].radius);
            let early = overlap::depth(
                self.pucks[a].worldline.last(),
                ra,
                self.pucks[b].worldline.last(),
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
            self.kick_generation = self.kick_generation.wrapping_add(1);
            let kick = Kick {
                puck: i as u32,
                partner: j as u32,
                t: times[k],
                before: before[k],
                after: after[k],
                version_at_contact: self.pucks[i].version,
                record,
                slot: k,
                generation: self.kick_generation,
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
        // The kicks that are due land now, earliest first; a later one is
        // put on the calendar.
        let order = if times[0] <= times[1] { [0, 1] } else { [1, 0] };
        for k in order {
            let id = ids[k];
            if times[k] <= self.time {
                self.land_kick(id);
            } else {
                self.calendar.push(Entry {
                    t: times[k],
                    slot: Slot::Kick(id),
                    versions: [self.kicks[id].map_or(0, |kick| kick.generation), 0],
                    predicted_at: times[k],
                });
            }
        }
    }

    fn land_kick(&mut self, id: usize) {
        let Some(kick) = self.kicks[id].take() else {
            return;
        };
        self.free_kicks.push(id);
        let i = kick.puck as usize;
        let puck = &mut self.pucks[i];
        puck.pending.retain(|&k| k != id);
        let now = Body {
            mass: puck.mass,
            u: puck.worldline.last().u,
        };
        let next = if puck.version == kick.version_at_contact {
            kick.after
        } else {
            // The puck was changed again before this kick's board time: add
            // this contact's 4-momentum transfer to its present 4-momentum.
            // Energy and momentum stay exactly conserved; the difference
            // from a rigid body's outcome shows as a change of rest mass.
            self.stats.overlapping_kicks += 1;
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
        // At its scheduled time, or now if it lands early (flushed).
        let t = kick.t.min(self.time).max(puck.worldline.last().start.t);
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

    /// Restitution for this contact: the scene's, unless one of the pucks
    /// is in a Zeno sequence (inelastic collapse: contacts closer and closer
    /// in time), which is then ended by one perfectly inelastic collision.
    /// The first time, a warning says so.
    fn zeno_restitution(&mut self, a: usize, b: usize, t: f64) -> f64 {
        let gap = ZENO_GAP * self.table.length() / self.c;
        let mut streak = 0;
        for i in [a, b] {
            let quick = &mut self.pucks[i].quick;
            quick.1 = if t - quick.0 < gap { quick.1 + 1 } else { 0 };
            quick.0 = t;
            streak = streak.max(quick.1);
        }
        if streak < ZENO_COUNT {
            return self.restitution;
        }
        self.pucks[a].quick.1 = 0;
        self.pucks[b].quick.1 = 0;
        self.stats.zeno_merges += 1;
        if self.stats.zeno_merges == 1 {
            self.warnings.push(format!(
                "t = {t} s: pucks \"{}\" and \"{}\" met others {ZENO_COUNT} times within {gap:.3e} s \
                 (inelastic collapse); such a collision is made perfectly inelastic so they move \
                 together (said once; every one is counted)",
                self.pucks[a].name, self.pucks[b].name
            ));
        }
        0.0
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
    fn contact_of(&self, a: usize, b: usize, now: f64) -> Option<PairContact> {
        let (pa, pb) = (&self.pucks[a], &self.pucks[b]);
        let (sa, sb) = (pa.worldline.last(), pb.worldline.last());
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
        if let Some((depth, m)) = overlap::penetration(sa, pa.radius, sb, pb.radius, now) {
            return (m.dot(v_rel) < -still).then(|| on_board(now, m, depth));
        }
        if let Some(hit) = puck_puck::predict(self.mover(a), self.mover(b), self.c, now) {
            return Some(hit);
        }
        // Apart now, and the pair frame sees nothing ahead: will the board
        // shapes meet? Only while the centres are within reach.
        let reach = pa.radius + pb.radius;
        let d0 = sb.position_at(now) - sa.position_at(now);
        let vv = v_rel.length_squared();
        if vv == 0.0 {
            return None;
        }
        // |d0 + v τ|² = reach²: the later root is when the centres leave reach.
        let (p, q) = (d0.dot(v_rel), d0.length_squared() - reach * reach);
        let disc = p * p - vv * q;
        if disc < 0.0 {
            return None;
        }
        let leave = (-p + disc.sqrt()) / vv;
        if leave <= 0.0 {
            return None;
        }
        let end = (now + leave).min(self.window_end);
        // A separating axis along which they do not close: never.
        let (g, m) = overlap::gap(sa, pa.radius, sb, pb.radius, d0);
        if g <= 0.0 && m.dot(v_rel) >= 0.0 {
            return None;
        }
        let t = overlap::first_touch(sa, pa.radius, sb, pb.radius, now, end)?.max(now);
        let (_, normal) = overlap::gap(sa, pa.radius, sb, pb.radius, d0 + v_rel * (t - now));
        Some(on_board(t, normal, 0.0))
    }

    /// Puck `i`'s worldline changed: it gets a new version (its old
    /// predictions go stale), its history is trimmed to the horizon, and it
    /// gets a new swept AABB and new predictions.
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
        self.predict_cushions(i);
        let (mins, maxs) = self.swept(i, self.time, self.window_end);
        self.broad.set_swept(i, mins, maxs);
        self.scratch.clear();
        self.broad.flush(&mut self.scratch);
        for k in 0..self.broad.partners(i).len() {
            let j = self.broad.partners(i)[k] as usize;
            self.predict_pair(i.min(j), i.max(j));
        }
        self.compact();
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

    fn predict_cushions(&mut self, i: usize) {
        let puck = &self.pucks[i];
        for cushion in Cushion::ALL {
            self.stats.predictions += 1;
            if let Some(hit) = puck_cushion::predict(
                puck.worldline.last(),
                puck.radius,
                self.table,
                cushion,
                self.time,
            ) && hit.t <= self.window_end
            {
                self.calendar.push(Entry {
                    t: hit.t,
                    slot: Slot::Cushion(i as u32, cushion),
                    versions: [puck.version, 0],
                    predicted_at: self.time,
                });
            }
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

    fn predict_pair(&mut self, a: usize, b: usize) {
        if self.pending_with(a, b) {
            return; // the second kick of their last contact is still ahead
        }
        let (pa, pb) = (&self.pucks[a], &self.pucks[b]);
        if pa.settled == Some((b as u32, pa.version, pb.version)) {
            return; // they collided and nothing has touched them since
        }
        self.stats.predictions += 1;
        if let Some(hit) = self.contact_of(a, b, self.time) {
            // Processed at the earliest of the two kicks (the contact lies
            // between them in board time).
            let t = hit.kicks[0]
                .t
                .min(hit.kicks[1].t)
                .min(hit.contact.t)
                .max(self.time);
            if t <= self.window_end {
                self.calendar.push(Entry {
                    t,
                    slot: Slot::Pair(a as u32, b as u32),
                    versions: [self.pucks[a].version, self.pucks[b].version],
                    predicted_at: self.time,
                });
            }
        }
    }

    /// Everywhere puck `i` can be between board times `t0` and `t1` on its
    /// current segment, as an AABB (clipped to the table: a puck meets a
    /// cushion before its centre can leave it).
    fn swept(&self, i: usize, t0: f64, t1: f64) -> (DVec2, DVec2) {
        let puck = &self.pucks[i];
        let s = puck.worldline.last();
        let r = DVec2::splat(puck.radius);
        let lo = DVec2::ZERO - r;
        let hi = self.table + r;
        let p0 = s.position_at(t0).truncate();
        let p1 = if t1.is_finite() {
            s.position_at(t1).truncate()
        } else {
            // An endless window: a moving puck can be anywhere ahead.
            let v = s.velocity().truncate();
            let ahead = |v: f64, lo: f64, hi: f64, p: f64| {
                if v > 0.0 {
                    hi
                } else if v < 0.0 {
                    lo
                } else {
                    p
                }
            };
            DVec2::new(ahead(v.x, lo.x, hi.x, p0.x), ahead(v.y, lo.y, hi.y, p0.y))
        };
        (
            (p0.min(p1) - r).clamp(lo, hi),
            (p0.max(p1) + r).clamp(lo, hi),
        )
    }

    /// Starts a new look-ahead window at board time `t`: every swept AABB
    /// anew, and every prediction. Only events inside the window are put on
    /// the calendar, which keeps it short; the next window predicts again.
    fn start_window(&mut self, t: f64) {
        self.stats.windows += 1;
        self.time = self.time.max(t);
        let horizon = self.horizon();
        self.window_end = t + horizon;
        for i in 0..self.pucks.len() {
            let (mins, maxs) = self.swept(i, t, self.window_end);
            self.broad.set_swept(i, mins, maxs);
        }
        let mut added = std::mem::take(&mut self.scratch);
        added.clear();
        self.broad.flush(&mut added);
        self.scratch = added;
        for i in 0..self.pucks.len() {
            self.predict_cushions(i);
            for k in 0..self.broad.partners(i).len() {
                let j = self.broad.partners(i)[k] as usize;
                if j > i {
                    self.predict_pair(i, j);
                }
            }
        }
        if self.window_end.is_finite() {
            self.calendar.push(Entry {
                t: self.window_end,
                slot: Slot::Horizon,
                versions: [0, 0],
                predicted_at: t,
            });
        }
    }

    /// Length of a look-ahead window: the time a typical (RMS-speed) puck
    /// takes to move one radius. Swept AABBs then stay small, and windows
    /// are not too many; measured best among 0.25 to 8 radii (BENCHMARKS.md).
    /// With nothing moving, the window is endless: an idle table costs
    /// nothing however long it is watched, whatever `c` is.
    fn horizon(&self) -> f64 {
        let n = self.pucks.len().max(1) as f64;
        let mean_sq: f64 = self
            .pucks
            .iter()
            .map(|p| p.worldline.last().velocity().length_squared())
            .sum::<f64>()
            / n;
        let mean_radius = self.pucks.iter().map(|p| p.radius).sum::<f64>() / n;
        if mean_sq > 0.0 {
            (mean_radius / mean_sq.sqrt()).max(1e-9 * self.table.length() / self.c)
        } else {
            f64::INFINITY
        }
    }

    /// Drops stale entries once they outnumber live ones.
    fn compact(&mut self) {
        let live_bound = 16 * self.pucks.len() + 1024;
        if self.calendar.len() <= 4 * live_bound {
            return;
        }
        let pucks = &self.pucks;
        let kicks = &self.kicks;
        self.calendar.retain(|e| match e.slot {
            Slot::Horizon => true,
            Slot::Kick(k) => kicks[k].is_some_and(|kick| kick.generation == e.versions[0]),
            Slot::Cushion(i, _) => pucks[i as usize].version == e.versions[0],
            Slot::Pair(a, b) => {
                pucks[a as usize].version == e.versions[0]
                    && pucks[b as usize].version == e.versions[1]
            }
        });
    }
}
