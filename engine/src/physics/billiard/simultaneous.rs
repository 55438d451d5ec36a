//! Contacts on one puck at one board time, resolved together
//! ([`resolve::simultaneous::on_one_puck`]): two mirror-image strikers
//! meeting a puck at once come back mirror images, whatever the order in
//! which the loop takes the two contacts.

use super::*;

/// Two contacts on one puck count as simultaneous when its velocity
/// changes from them are due within this fraction of the time light takes
/// to cross the table (plus the same fraction of the board time, for the
/// rounding of late times) of each other: far below anything a scene can
/// set on purpose, far above the rounding that makes mirror-image contacts
/// differ in their last bits.
const SIMULTANEOUS: f64 = 1e-12;

impl Billiard {
    /// The other contacts due on puck `a` or `b` at the board time its
    /// velocity changes in their contact `hit`: the puck (the centre) and
    /// each other puck whose next contact with the centre changes the
    /// centre's velocity then (within [`SIMULTANEOUS`]), with that
    /// contact. `a` is tried first, then `b`; `None` if neither has one.
    ///
    /// Such a contact need not be any puck's calendar entry (a puck holds
    /// only its earliest event, and a contact waiting for another's kick
    /// was not predicted), so each partner of the centre that could touch
    /// it by then is predicted again: those whose rest discs can meet by
    /// the centre's kick (at the earlier kick of a contact the rest discs
    /// touch, and no kick of it is before now: [`bounds::disc_touch`],
    /// [`bounds::braking_touch`]), in a dense gas rarely any. Only pucks
    /// with no kick pending count.
    ///
    /// Each is predicted from `predicted_at` (s), when `hit` was (or from
    /// the later start of either segment): what a prediction finds depends
    /// on when it is made (two shapes can overlap on the board before
    /// their contact in the pair frame, and a prediction made then pushes
    /// them apart on the board at once), and a mirror image of `hit` would
    /// have been predicted when `hit` was.
    pub(super) fn simultaneous_with(
        &self,
        a: usize,
        b: usize,
        hit: &PairContact,
        predicted_at: f64,
    ) -> Option<(usize, Vec<(usize, PairContact)>)> {
        let now = self.time;
        for (slot, centre) in [a, b].into_iter().enumerate() {
            if !self.pucks[centre].pending.is_empty() {
                continue;
            }
            // Kicks fall never before now (a contact found late is
            // resolved at once).
            let t = hit.kicks[slot].t.max(now);
            let tolerance = SIMULTANEOUS * (t.abs() + self.table.length() / self.c);
            let mut others = Vec::new();
            let everyone = if self.reference {
                0..self.pucks.len()
            } else {
                0..0
            };
            let partners = if self.reference {
                &[][..]
            } else {
                self.broad.partners(centre)
            };
            for j in partners.iter().map(|&j| j as usize).chain(everyone) {
                if j == centre || j == a || j == b || !self.pucks[j].pending.is_empty() {
                    continue;
                }
                let (lo, hi) = (centre.min(j), centre.max(j));
                let (hl, hh) = (self.hot[lo], self.hot[hi]);
                let bound = if hl.braking || hh.braking {
                    let reach =
                        |k: usize| bounds::BrakingReach::of(self.pucks[k].worldline.last(), now);
                    bounds::braking_touch(
                        &reach(lo),
                        self.pucks[lo].radius,
                        &reach(hi),
                        self.pucks[hi].radius,
                        now,
                        t + tolerance,
                    )
                } else {
                    bounds::disc_touch(
                        hl.position_at(now),
                        hl.v,
                        hl.radius,
                        hh.position_at(now),
                        hh.v,
                        hh.radius,
                        now,
                    )
                };
                if bound.is_none_or(|bound| bound > t + tolerance) {
                    continue;
                }
                let settled = self.settled(lo, hi);
                if settled && (hl.braking || hh.braking) {
                    continue;
                }
                let from = predicted_at
                    .max(self.pucks[lo].worldline.last().start.t)
                    .max(self.pucks[hi].worldline.last().start.t);
                let Some(h) = self.contact_of(lo, hi, from, settled, t + tolerance) else {
                    continue;
                };
                let on_centre = if lo == centre { 0 } else { 1 };
                if (h.kicks[on_centre].t.max(now) - t).abs() <= tolerance {
                    others.push((j, h));
                }
            }
            if !others.is_empty() {
                // In index order, whichever list they came from, so that
                // the reference loop resolves them to the same bits.
                others.sort_by_key(|&(j, _)| j);
                return Some((centre, others));
            }
        }
        None
    }

    /// Resolves the contact `hit` of pucks `ab` together with `others`,
    /// the other contacts on `centre` (one of `ab`) due at the same board
    /// time ([`Self::simultaneous_with`]), as one contact numbered
    /// `contact_id`: each striker's velocity changes at its own kick of its
    /// contact, the centre's once, at the earliest of its kicks. One
    /// collision record holds the centre, then the strikers. Returns
    /// `false`, with nothing changed, if the rule has no outcome for them
    /// ([`resolve::simultaneous::on_one_puck`]): the contacts are then
    /// resolved one by one, as any others. Not asked at restitution 0
    /// (`pair_contact` says why).
    pub(super) fn joint_contact(
        &mut self,
        ab: [usize; 2],
        hit: PairContact,
        centre: usize,
        others: Vec<(usize, PairContact)>,
        contact_id: u64,
    ) -> bool {
        let other = if ab[0] == centre { ab[1] } else { ab[0] };
        let mut contacts = vec![(other, hit)];
        contacts.extend(others);
        // Which of a contact's two kicks is the centre's, which the striker's.
        let slots = |striker: usize| if centre < striker { (0, 1) } else { (1, 0) };
        let now = self.time;
        let centre_t = contacts
            .iter()
            .map(|&(s, h)| h.kicks[slots(s).0].t)
            .fold(f64::INFINITY, f64::min)
            .max(now);
        let body = |i: usize, t: f64| Body {
            mass: self.pucks[i].mass,
            u: self.pucks[i].worldline.last().u_at(t),
        };
        let centre_before = body(centre, centre_t);
        let times: Vec<f64> = contacts
            .iter()
            .map(|&(s, h)| h.kicks[slots(s).1].t.max(now))
            .collect();
        let strikers: Vec<Body> = contacts
            .iter()
            .zip(&times)
            .map(|(&(s, _), &t)| body(s, t))
            .collect();
        let alone: Vec<[Body; 2]> = contacts
            .iter()
            .zip(&strikers)
            .map(|(&(s, h), &striker)| {
                let pair = if centre < s {
                    [centre_before, striker]
                } else {
                    [striker, centre_before]
                };
                let (lo, hi) = (centre.min(s), centre.max(s));
                let out = if h.on_board {
                    self.board_push(lo, hi, pair, h.normal, self.restitution)
                } else {
                    resolve::puck_puck(pair[0], pair[1], h.normal, h.pair_frame, self.restitution)
                };
                if centre < s { [out[1], out[0]] } else { out }
            })
            .collect();
        let Some((centre_after, after)) =
            resolve::simultaneous::on_one_puck(centre_before, &strikers, &alone)
        else {
            return false;
        };
        self.stats.pair_contacts += contacts.len() as u64 - 1;
        self.stats.simultaneous_contacts += 1;
        for &(s, _) in &contacts[1..] {
            self.quick_streak(s, now);
        }
        let record = self.record.then(|| {
            let overlap_bound = contacts
                .iter()
                .enumerate()
                .map(|(k, &(s, h))| {
                    let (c_slot, s_slot) = slots(s);
                    let mut t = [0.0; 2];
                    let (mut b, mut a) = ([centre_before; 2], [centre_after; 2]);
                    t[c_slot] = centre_t;
                    t[s_slot] = times[k];
                    b[s_slot] = strikers[k];
                    a[s_slot] = after[k];
                    let pair = if c_slot == 0 {
                        [centre, s]
                    } else {
                        [s, centre]
                    };
                    self.overlap_bound_of(pair, t, b, a, h.gamma_pair)
                })
                .fold(0.0, f64::max);
            let outcome = |i: usize, t: f64, before: Body, after: Body| PuckOutcome {
                puck: self.pucks[i].external as usize,
                t,
                // The centre at its own kick (as scheduled).
                position: self.pucks[i].worldline.last().position_at(t),
                u_before: before.u,
                u_after: after.u,
                mass_before: before.mass,
                mass_after: after.mass,
                // As scheduled; set again when the kick is taken.
                orientation_after: self.pucks[i].worldline.last().orientation
                    + rotation_of_velocity_change(before.u, after.u),
                pending: true,
            };
            let mut pucks = vec![outcome(centre, centre_t, centre_before, centre_after)];
            for (k, &(s, _)) in contacts.iter().enumerate() {
                pucks.push(outcome(s, times[k], strikers[k], after[k]));
            }
            self.collisions.push(Collision {
                kind: CollisionKind::PuckPuck,
                t: hit.contact.t.max(now),
                contact: hit.contact.position,
                pucks,
                overlap_bound,
                simultaneous: true,
            });
            self.collision_count() - 1
        });
        // The kicks: the centre's (slot 0 of the record), then each
        // striker's.
        let first_striker = contacts[0].0;
        let mut kicks = vec![(
            centre,
            Kick {
                puck: centre as u32,
                partner: first_striker as u32,
                t: centre_t,
                before: centre_before,
                after: centre_after,
                version_at_contact: self.pucks[centre].version,
                record,
                slot: 0,
                contact: contact_id,
                settles: false,
            },
        )];
        for (k, &(s, _)) in contacts.iter().enumerate() {
            kicks.push((
                s,
                Kick {
                    puck: s as u32,
                    partner: centre as u32,
                    t: times[k],
                    before: strikers[k],
                    after: after[k],
                    version_at_contact: self.pucks[s].version,
                    record,
                    slot: k + 1,
                    contact: contact_id,
                    settles: false,
                },
            ));
        }
        // Earliest first: those due now land, the others wait.
        kicks.sort_by(|x, y| x.1.t.total_cmp(&y.1.t).then(x.0.cmp(&y.0)));
        let ids: Vec<usize> = kicks
            .iter()
            .map(|&(i, kick)| self.schedule_kick(i, kick))
            .collect();
        for (&(i, kick), id) in kicks.iter().zip(ids) {
            if kick.t <= self.time {
                self.land_kick(id);
            } else {
                // Its calendar entry is the contact just resolved: its
                // next event again, the kick among the candidates.
                self.predict(i);
            }
        }
        true
    }
}
