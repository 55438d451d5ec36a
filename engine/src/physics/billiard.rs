//! The event loop: run freely to the earliest predicted event, resolve it,
//! re-predict what it changed (the paper's §3.3.2.1 "anticipation").

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use super::broadphase::BroadPhase;
use super::calendar::{Calendar, Entry, Slot};
use super::predict::{Cushion, puck_cushion, puck_puck};
use super::resolve::{self, Body};
use crate::scene::Scene;
use crate::spacetime::{Event, ProperVelocity};
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
    /// True while the velocity change has not yet happened (light from the
    /// contact has not reached the centre): the values are the scheduled ones.
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
    /// Velocity changes that landed before light reached the centre,
    /// because the puck met something else first.
    pub early_kicks: u64,
}

impl Stats {
    /// Contacts of either kind.
    pub fn contacts(&self) -> u64 {
        self.pair_contacts + self.cushion_contacts
    }
}

/// A velocity change on its way: light from a contact travelling to a
/// puck's centre. It is an impulse: if the puck changed meanwhile, the
/// momentum and mass it carries are added to the puck's new state.
#[derive(Clone, Copy, Debug)]
struct Kick {
    puck: u32,
    partner: u32,
    t: f64,
    before: Body,
    after: Body,
    version_at_contact: u32,
    record: Option<usize>,
    slot: usize,
    generation: u32,
}

#[derive(Clone, Debug)]
struct Puck {
    name: String,
    radius: f64,
    mass: f64,
    worldline: Worldline,
    version: u32,
    pending: Vec<usize>,
}

/// Consecutive contacts of one pair closer together than this (in units of
/// the time light takes to cross the table) count towards a Zeno sequence.
const ZENO_GAP: f64 = 1e-9;
/// A pair that meets this many times in such quick succession is merged
/// (its next collision is perfectly inelastic).
const ZENO_COUNT: u32 = 64;

/// The relativistic billiard's physics: pucks, their worldlines, and the
/// calendar of what happens next.
pub struct Billiard {
    c: f64,
    table: DVec2,
    restitution: f64,
    cushion_restitution: f64,
    pucks: Vec<Puck>,
    time: f64,
    calendar: Calendar,
    kicks: Vec<Option<Kick>>,
    free_kicks: Vec<usize>,
    kick_generation: u32,
    broad: BroadPhase,
    window_end: f64,
    collisions: Vec<Collision>,
    record: bool,
    keep_history: bool,
    warnings: Vec<String>,
    stats: Stats,
    zeno: HashMap<(u32, u32), (f64, u32)>,
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
        let pucks = pucks
            .into_iter()
            .map(|p| Puck {
                worldline: Worldline::new(Event::new(0.0, p.position.extend(0.0)), p.u, c),
                name: p.name,
                radius: p.radius,
                mass: p.mass,
                version: 0,
                pending: Vec::new(),
            })
            .collect();
        let mut billiard = Self {
            c,
            table,
            restitution,
            cushion_restitution,
            pucks,
            time: 0.0,
            calendar: Calendar::default(),
            kicks: Vec::new(),
            free_kicks: Vec::new(),
            kick_generation: 0,
            broad: BroadPhase::new(n, mean_radius),
            window_end: 0.0,
            collisions: Vec::new(),
            record: true,
            keep_history: true,
            warnings: Vec::new(),
            stats: Stats::default(),
            zeno: HashMap::new(),
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

    /// Whether worldlines keep their whole history (on by default). Off,
    /// each keeps only its current segment: for long headless runs that
    /// need no replay and no light-delayed view of the past.
    pub fn set_keep_history(&mut self, on: bool) {
        self.keep_history = on;
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

    /// Puck `i`'s name.
    pub fn name(&self, i: usize) -> &str {
        &self.pucks[i].name
    }

    /// Index of the puck called `name`.
    pub fn index_of(&self, name: &str) -> Option<usize> {
        self.pucks.iter().position(|p| p.name == name)
    }

    /// Puck `i`'s rest radius, m.
    pub fn radius(&self, i: usize) -> f64 {
        self.pucks[i].radius
    }

    /// Puck `i`'s current rest mass, kg (grows in inelastic collisions).
    pub fn mass(&self, i: usize) -> f64 {
        self.pucks[i].mass
    }

    /// Puck `i`'s worldline (its centre), complete up to [`Self::time`].
    pub fn worldline(&self, i: usize) -> &Worldline {
        &self.pucks[i].worldline
    }

    /// Every collision so far whose contact is at or before [`Self::time`],
    /// in the order resolved (contact time order). A puck–puck collision's
    /// outcomes stay `pending` until light from the contact reaches each
    /// centre.
    pub fn collisions(&self) -> &[Collision] {
        &self.collisions
    }

    /// Messages about degraded behaviour (Zeno sequences merged, …).
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// Total 4-momentum of the pucks at [`Self::time`], including what is
    /// in transit: a puck–puck collision's transfer that light has not yet
    /// carried to a centre. Exactly conserved by puck–puck collisions;
    /// cushions change it (they are external).
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
        if t.is_nan() || t <= self.time {
            return;
        }
        while let Some(entry) = self.calendar.peek().copied() {
            if entry.t > t {
                break;
            }
            self.calendar.pop();
            self.handle(entry);
        }
        self.time = t;
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
        let t = t.max(self.time);
        self.advance_to(t);
        self.flush_pending(i);
        let puck = &mut self.pucks[i];
        let u = ProperVelocity(puck.worldline.last().u.0 + du);
        puck.worldline
            .push(t.max(puck.worldline.last().start.t), u)?;
        self.changed(i);
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
                {
                    self.stats.stale += 1;
                    return;
                }
                if self.pending_with(ia, ib) {
                    // A duplicate of a contact already resolved (the pair left
                    // and re-entered the broad phase): light is still on its way.
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

    /// A puck about to meet something while light from an earlier contact
    /// is still crossing it takes that news now: its pending velocity
    /// changes land at the current time, so every collision starts from
    /// the puck's complete state and 4-momentum stays exactly conserved.
    /// Returns whether anything landed (the puck then has new predictions).
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
            kx.total_cmp(&ky)
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
                puck: i,
                t: t_kink,
                position,
                u_before: before,
                u_after: after,
                mass_before: puck.mass,
                mass_after: puck.mass,
                pending: false,
            };
            self.collisions.push(Collision {
                kind: CollisionKind::Cushion(cushion),
                t: t_kink,
                contact,
                pucks: vec![outcome],
            });
        }
        self.changed(i);
    }

    fn pair_contact(&mut self, a: usize, b: usize, predicted_at: f64) {
        let Some(hit) = puck_puck::predict(self.mover(a), self.mover(b), self.c, predicted_at)
        else {
            return;
        };
        self.time = self.time.max(hit.contact.t);
        self.stats.pair_contacts += 1;
        let body = |p: &Puck| Body {
            mass: p.mass,
            u: p.worldline.last().u,
        };
        let before = [body(&self.pucks[a]), body(&self.pucks[b])];
        let restitution = self.zeno_restitution(a, b, hit.contact.t);
        let after = resolve::puck_puck(
            before[0],
            before[1],
            hit.normal,
            hit.pair_frame,
            restitution,
        );

        let record = self.record.then(|| {
            let pucks = [a, b]
                .iter()
                .enumerate()
                .map(|(k, &i)| PuckOutcome {
                    puck: i,
                    t: hit.kicks[k].t,
                    position: hit.kicks[k].position,
                    u_before: before[k].u,
                    u_after: after[k].u,
                    mass_before: before[k].mass,
                    mass_after: after[k].mass,
                    pending: true,
                })
                .collect();
            self.collisions.push(Collision {
                kind: CollisionKind::PuckPuck,
                t: hit.contact.t,
                contact: hit.contact.position,
                pucks,
            });
            self.collisions.len() - 1
        });
        for (k, (&i, &j)) in [a, b].iter().zip([b, a].iter()).enumerate() {
            let kick = Kick {
                puck: i as u32,
                partner: j as u32,
                t: hit.kicks[k].t.max(self.time),
                before: before[k],
                after: after[k],
                version_at_contact: self.pucks[i].version,
                record,
                slot: k,
                generation: 0,
            };
            let kick = Kick {
                generation: {
                    self.kick_generation = self.kick_generation.wrapping_add(1);
                    self.kick_generation
                },
                ..kick
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
            self.calendar.push(Entry {
                t: kick.t,
                slot: Slot::Kick(id),
                versions: [kick.generation, 0],
                predicted_at: kick.t,
            });
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
            // The puck was struck again before light from this contact had
            // crossed it: add this contact's 4-momentum transfer to its
            // present 4-momentum. Energy and momentum stay exactly
            // conserved; the difference from a rigid body's outcome shows
            // as a change of rest mass (internal energy of a body that, in
            // relativity, cannot be rigid).
            self.stats.overlapping_kicks += 1;
            let p = now.momentum() + (kick.after.momentum() - kick.before.momentum());
            let mass = p.invariant_mass();
            if mass > 1e-3 * now.mass && p.energy > 0.0 {
                Body {
                    mass,
                    u: ProperVelocity(p.momentum / mass),
                }
            } else {
                // Not a timelike 4-momentum any more: keep the mass, add
                // the 3-momentum.
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
        if let Some(r) = kick.record {
            let position = puck.worldline.position_at(t);
            self.collisions[r].pucks[kick.slot] = PuckOutcome {
                puck: i,
                t,
                position,
                u_before: now.u,
                u_after: next.u,
                mass_before: now.mass,
                mass_after: next.mass,
                pending: false,
            };
        }
        self.changed(i);
    }

    /// Restitution for this contact of the pair: the scene's, unless the pair
    /// is in a Zeno sequence (inelastic collapse), which is then ended by
    /// one perfectly inelastic collision, and a warning says so.
    fn zeno_restitution(&mut self, a: usize, b: usize, t: f64) -> f64 {
        let gap = ZENO_GAP * self.table.length() / self.c;
        let entry = self
            .zeno
            .entry((a as u32, b as u32))
            .or_insert((f64::NEG_INFINITY, 0));
        if t - entry.0 < gap {
            entry.1 += 1;
        } else {
            entry.1 = 0;
        }
        entry.0 = t;
        if entry.1 >= ZENO_COUNT {
            entry.1 = 0;
            self.stats.zeno_merges += 1;
            self.warnings.push(format!(
                "t = {t} s: pucks \"{}\" and \"{}\" met {ZENO_COUNT} times within {gap:.3e} s \
                 (inelastic collapse); this collision is made perfectly inelastic so they move together",
                self.pucks[a].name, self.pucks[b].name
            ));
            0.0
        } else {
            self.restitution
        }
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

    /// Puck `i`'s worldline changed: it gets a new version (its old
    /// predictions go stale), a new swept AABB, and new predictions.
    fn changed(&mut self, i: usize) {
        let puck = &mut self.pucks[i];
        puck.version = puck.version.wrapping_add(1);
        if !self.keep_history {
            puck.worldline.forget_history();
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
            return; // light from their last contact is still on its way
        }
        self.stats.predictions += 1;
        if let Some(hit) = puck_puck::predict(self.mover(a), self.mover(b), self.c, self.time)
            && hit.contact.t <= self.window_end
        {
            self.calendar.push(Entry {
                t: hit.contact.t,
                slot: Slot::Pair(a as u32, b as u32),
                versions: [self.pucks[a].version, self.pucks[b].version],
                predicted_at: self.time,
            });
        }
    }

    /// Everywhere puck `i` can be between board times `t0` and `t1` on its
    /// current segment, as an AABB (clipped to the table: a puck meets a
    /// cushion before its centre can leave it).
    fn swept(&self, i: usize, t0: f64, t1: f64) -> (DVec2, DVec2) {
        let puck = &self.pucks[i];
        let s = puck.worldline.last();
        let (p0, p1) = (s.position_at(t0).truncate(), s.position_at(t1).truncate());
        let r = DVec2::splat(puck.radius);
        let lo = DVec2::ZERO - r;
        let hi = self.table + r;
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
        self.calendar.push(Entry {
            t: self.window_end,
            slot: Slot::Horizon,
            versions: [0, 0],
            predicted_at: t,
        });
    }

    /// Length of a look-ahead window: the time a typical (RMS-speed) puck
    /// takes to move one radius. Swept AABBs then stay small, and windows
    /// are not too many; measured best among 0.25 to 8 radii (BENCHMARKS.md).
    fn horizon(&self) -> f64 {
        let crossing = self.table.length() / self.c;
        let n = self.pucks.len().max(1) as f64;
        let mean_sq: f64 = self
            .pucks
            .iter()
            .map(|p| p.worldline.last().velocity().length_squared())
            .sum::<f64>()
            / n;
        let mean_radius = self.pucks.iter().map(|p| p.radius).sum::<f64>() / n;
        if mean_sq > 0.0 {
            (1.0 * mean_radius / mean_sq.sqrt()).clamp(1e-9 * crossing, 10.0 * crossing)
        } else {
            10.0 * crossing
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
