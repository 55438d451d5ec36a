//! Contacts at one board time, resolved together
//! ([`resolve::simultaneous::on_graph`]): two mirror-image strikers
//! meeting a puck at once, or twins meeting each other while a third meets
//! both, come back mirror images, whatever the order in which the loop
//! takes the contacts.

use super::*;

/// Two contacts on one puck count as simultaneous when its velocity
/// changes from them are due within this fraction of the time light takes
/// to cross the table (plus the same fraction of the board time, for the
/// rounding of late times) of each other: far below anything a scene can
/// set on purpose, far above the rounding that makes mirror-image contacts
/// differ in their last bits.
const SIMULTANEOUS: f64 = 1e-12;

/// The most pucks a group of contacts at one board time resolved
/// together holds; a larger group (a packed cluster struck at once) is
/// taken one contact at a time, as before groups were resolved.
const MAX_GROUP: usize = 32;

impl Billiard {
    /// How near two board times around `t` (s) count as one: [`SIMULTANEOUS`]
    /// of the time light takes to cross the table plus of `t`.
    fn tolerance_at(&self, t: f64) -> f64 {
        SIMULTANEOUS * (t.abs() + self.table.length() / self.c)
    }

    /// Puck `c`'s candidate partners: its broad-phase partners, or on the
    /// reference path every puck (`c` itself included: callers skip it).
    fn candidates(&self, c: usize) -> impl Iterator<Item = usize> + '_ {
        let everyone = if self.reference {
            0..self.pucks.len()
        } else {
            0..0
        };
        let partners = if self.reference {
            &[][..]
        } else {
            self.broad.partners(c)
        };
        partners.iter().map(|&j| j as usize).chain(everyone)
    }

    /// Whether a kick at board time `t` (s) is due now: at or before now,
    /// or within [`SIMULTANEOUS`] after (a contact's kick an ulp after its
    /// partner's, which lands now, would leave it pending while contacts
    /// at that same time are predicted for the one and not the other).
    pub(super) fn due_now(&self, t: f64) -> bool {
        t <= self.time + self.tolerance_at(self.time)
    }

    /// Handles, before the contact of `a` and `b` due now is resolved, the
    /// other pucks' velocity changes due now too (within [`SIMULTANEOUS`]:
    /// kicks and cushion contacts, the calendar's next entries, at most
    /// [`MAX_GROUP`] of them, none past the board time the loop runs to):
    /// the mirror image of the kick or cushion bounce that led to this
    /// contact, an ulp later or merely taken second, would otherwise still
    /// be ahead when the contact looks for others at its board time, and
    /// those other contacts, predicted after it, would start from a
    /// changed state. (`a` and `b` take their own pending kicks next.)
    /// Returns `false` if that changed `a` or `b` (a cushion contact's Zeno
    /// merge moves a pressed cluster): their contact is then stale.
    pub(super) fn changes_due_now(&mut self, a: usize, b: usize) -> bool {
        let versions = [self.pucks[a].version, self.pucks[b].version];
        for _ in 0..MAX_GROUP {
            let Some((key, j)) = self.calendar.peek() else {
                break;
            };
            let j = j as usize;
            if !self.due_now(key.t)
                || key.t > self.until
                || j == a
                || j == b
                || !matches!(self.next[j].what, What::Kick(_) | What::Cushion(_))
            {
                break;
            }
            self.handle(j, key.t);
        }
        versions == [self.pucks[a].version, self.pucks[b].version]
    }

    /// The pucks other than `a` and `b`, with a kick pending, that meet
    /// `a` or `b` in a contact processed at board time `t` (within
    /// [`SIMULTANEOUS`]), as predicted from now, in index order: when the
    /// contact of `a` and `b` makes one of them take a pending kick early,
    /// these take theirs too. Two mirror-image twins whose own contact's
    /// kicks are still ahead, both met at once by a puck between them,
    /// then meet it from the same kind of state, and the two contacts are
    /// resolved together ([`Self::simultaneous_group`]); taking one twin's
    /// kick first left the other's contact to be predicted from a changed
    /// puck. (The other contact need not be any puck's calendar entry: the
    /// puck between holds the one a few ulps earlier.) Predicted for each
    /// partner whose rest disc can reach by then, on this rare path only.
    pub(super) fn due_with(&self, a: usize, b: usize, t: f64) -> Vec<usize> {
        let now = self.time;
        let tolerance = self.tolerance_at(t);
        let mut due = Vec::new();
        for c in [a, b] {
            let own = std::cell::OnceCell::new();
            for j in self.candidates(c) {
                if j == a || j == b || self.pucks[j].pending.is_empty() || due.contains(&j) {
                    continue;
                }
                let (lo, hi) = (c.min(j), c.max(j));
                if self.pending_with(lo, hi) || !self.may_touch_by(lo, hi, t + tolerance, (c, &own))
                {
                    continue;
                }
                let settled = self.settled(lo, hi);
                if settled && (self.hot[lo].braking || self.hot[hi].braking) {
                    continue;
                }
                let Some(h) = self.contact_of(lo, hi, now, settled, t + tolerance) else {
                    continue;
                };
                let at = h.kicks[0].t.min(h.kicks[1].t).min(h.contact.t).max(now);
                if (at - t).abs() <= tolerance {
                    due.push(j);
                }
            }
        }
        due.sort_unstable();
        due
    }

    /// Whether pucks `lo` and `hi` can have a contact whose earlier kick
    /// is at or before board time `by` (s), from now: their rest discs
    /// can touch by then ([`bounds::disc_touch`], which bounds the earlier
    /// kick of a contact of uniform motions). On the cloth the rest discs
    /// are grown ([`bounds::braking_kick`], as a puck's prediction prunes
    /// its partners): there a kick can come before the rest discs touch
    /// (1.8·10⁻⁴ s before, in a mirror scene at c = 1 m/s and μg = 4.9
    /// m/s²), because the worldlines curve between the kick and the
    /// pair-frame contact.
    ///
    /// One of the two is `own.0`, whose [`bounds::BrakingReach`] `own.1`
    /// holds once worked out (a puck's candidates share it).
    #[inline]
    fn may_touch_by(
        &self,
        lo: usize,
        hi: usize,
        by: f64,
        own: (usize, &std::cell::OnceCell<bounds::BrakingReach>),
    ) -> bool {
        let now = self.time;
        let (hl, hh) = (self.hot[lo], self.hot[hi]);
        let bound = if hl.braking || hh.braking {
            // The records' first test, as a puck's prediction makes it.
            if hl.braking_apart_until(&hh, self.deceleration, self.c, now, by) {
                return false;
            }
            let (sl, sh) = (
                self.pucks[lo].worldline.last(),
                self.pucks[hi].worldline.last(),
            );
            let (rl, rh) = (self.pucks[lo].radius, self.pucks[hi].radius);
            let reach = |i: usize, s: &crate::worldline::Segment| {
                if i == own.0 {
                    *own.1.get_or_init(|| bounds::BrakingReach::of(s, now))
                } else {
                    bounds::BrakingReach::of(s, now)
                }
            };
            bounds::braking_kick(&reach(lo, sl), rl, &reach(hi, sh), rh, self.c, now, by)
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
        bound.is_some_and(|bound| bound <= by)
    }

    /// The contacts due together with `hit`, the contact of pucks `a` <
    /// `b`: every contact whose velocity change of a puck already in the
    /// group falls at the board time that puck's velocity changes (within
    /// [`SIMULTANEOUS`]), and with it its other puck, found puck by puck
    /// from `a` and `b` (a star of strikers on one puck, a chain, a cycle:
    /// twins meeting each other while a third meets both). A contact
    /// between two pucks already in the group counts if it falls at both
    /// their times. `None` if `hit` is alone, or if the group would pass
    /// [`MAX_GROUP`] pucks (then taken one by one).
    ///
    /// Such a contact need not be any puck's calendar entry (a puck holds
    /// only its earliest event, and a contact waiting for another's kick
    /// was not predicted), so each partner of a puck in the group that
    /// could touch it by then is predicted again: those whose rest discs
    /// (grown on the cloth) can meet by the puck's kick (at the earlier
    /// kick of a contact such discs touch, and no kick of it is before
    /// now: [`bounds::disc_touch`], [`bounds::braking_kick`]), in a dense
    /// gas rarely any. Only pucks with no kick pending count.
    ///
    /// Each is predicted from `predicted_at` (s), when `hit` was (or from
    /// the later start of either segment): what a prediction finds depends
    /// on when it is made (two shapes can overlap on the board before
    /// their contact in the pair frame, and a prediction made then pushes
    /// them apart on the board at once), and a mirror image of `hit` would
    /// have been predicted when `hit` was.
    pub(super) fn simultaneous_group(
        &self,
        a: usize,
        b: usize,
        hit: &PairContact,
        predicted_at: f64,
    ) -> Option<Group> {
        let now = self.time;
        // Nothing allocated unless a second contact is found (the common
        // case, on every pair contact).
        let mut group = Group {
            members: SmallVec::from_slice(&[
                (a, hit.kicks[0].t.max(now)),
                (b, hit.kicks[1].t.max(now)),
            ]),
            contacts: Vec::new(),
        };
        let mut next = 0;
        while next < group.members.len() {
            let (m, t) = group.members[next];
            next += 1;
            if !self.pucks[m].pending.is_empty() {
                continue;
            }
            let tolerance = self.tolerance_at(t);
            let mut found = Vec::new();
            let own = std::cell::OnceCell::new();
            for j in self.candidates(m) {
                let (lo, hi) = (m.min(j), m.max(j));
                if j == m
                    || !self.pucks[j].pending.is_empty()
                    || [lo, hi] == [a, b]
                    || group.contacts.iter().any(|&(pair, _)| pair == [lo, hi])
                {
                    continue;
                }
                if !self.may_touch_by(lo, hi, t + tolerance, (m, &own)) {
                    continue;
                }
                let settled = self.settled(lo, hi);
                if settled && (self.hot[lo].braking || self.hot[hi].braking) {
                    continue;
                }
                let from = predicted_at
                    .max(self.pucks[lo].worldline.last().start.t)
                    .max(self.pucks[hi].worldline.last().start.t);
                let Some(h) = self.contact_of(lo, hi, from, settled, t + tolerance) else {
                    continue;
                };
                let (on_m, on_j) = if lo == m { (0, 1) } else { (1, 0) };
                if (h.kicks[on_m].t.max(now) - t).abs() > tolerance {
                    continue;
                }
                let t_j = h.kicks[on_j].t.max(now);
                if let Some(&(_, t_member)) = group.members.iter().find(|&&(i, _)| i == j) {
                    // A cycle: the contact must fall at j's time too.
                    let tolerance_j = self.tolerance_at(t_member);
                    if (t_j - t_member).abs() > tolerance_j {
                        continue;
                    }
                }
                found.push((j, t_j, [lo, hi], h));
            }
            // In index order, whichever list they came from, so that the
            // reference loop resolves them to the same bits.
            found.sort_by_key(|&(j, ..)| j);
            for (j, t_j, pair, h) in found {
                if !group.members.iter().any(|&(i, _)| i == j) {
                    group.members.push((j, t_j));
                }
                group.contacts.push((pair, h));
            }
            if group.members.len() > MAX_GROUP {
                return None;
            }
        }
        if group.contacts.is_empty() {
            return None;
        }
        group.contacts.insert(0, ([a, b], *hit));
        Some(group)
    }

    /// Resolves `group` ([`Self::simultaneous_group`]) as one contact
    /// numbered `contact_id`: each puck's velocity changes once, at its
    /// time in the group, by [`resolve::simultaneous::on_graph`] from what
    /// each contact would do alone. One collision record holds every puck
    /// of the group (`a` and `b` of the contact that led to it first) and
    /// the pairs in contact. Returns `false`, with nothing changed, if the
    /// rule has no outcome for them: the contacts are then resolved one by
    /// one, as any others. Not asked at restitution 0 (`pair_contact` says
    /// why).
    pub(super) fn group_contact(&mut self, group: Group, contact_id: u64) -> bool {
        let Group { members, contacts } = group;
        let now = self.time;
        let index = |i: usize| {
            members
                .iter()
                .position(|&(m, _)| m == i)
                .expect("a contact of the group's pucks")
        };
        let before: Vec<Body> = members
            .iter()
            .map(|&(i, t)| Body {
                mass: self.pucks[i].mass,
                u: self.pucks[i].worldline.last().u_at(t),
            })
            .collect();
        let graph: Vec<resolve::simultaneous::GroupContact> = contacts
            .iter()
            .map(|&([lo, hi], h)| {
                let pair = [index(lo), index(hi)];
                let bodies = [before[pair[0]], before[pair[1]]];
                let alone = if h.on_board {
                    self.board_push(lo, hi, bodies, h.normal, self.restitution)
                } else {
                    resolve::puck_puck(
                        bodies[0],
                        bodies[1],
                        h.normal,
                        h.pair_frame,
                        self.restitution,
                    )
                };
                resolve::simultaneous::GroupContact { pair, alone }
            })
            .collect();
        let Some(after) = resolve::simultaneous::on_graph(&before, &graph) else {
            return false;
        };
        self.stats.pair_contacts += contacts.len() as u64 - 1;
        self.stats.simultaneous_contacts += 1;
        for &(i, _) in &members[2..] {
            self.quick_streak(i, now);
        }
        let record = self.record.then(|| {
            let overlap_bound = contacts
                .iter()
                .zip(&graph)
                .map(|(&(pair, h), g)| {
                    let [x, y] = g.pair;
                    self.overlap_bound_of(
                        pair,
                        [members[x].1, members[y].1],
                        [before[x], before[y]],
                        [after[x], after[y]],
                        h.gamma_pair,
                    )
                })
                .fold(0.0, f64::max);
            let pucks = members
                .iter()
                .zip(before.iter().zip(&after))
                .map(|(&(i, t), (&before, &after))| PuckOutcome {
                    puck: self.pucks[i].external as usize,
                    t,
                    // Each at its own kick (as scheduled).
                    position: self.pucks[i].worldline.last().position_at(t),
                    u_before: before.u,
                    u_after: after.u,
                    mass_before: before.mass,
                    mass_after: after.mass,
                    // As scheduled; set again when the kick is taken.
                    orientation_after: self.pucks[i].worldline.last().orientation
                        + rotation_of_velocity_change(before.u, after.u),
                    pending: true,
                })
                .collect();
            let hit = contacts[0].1;
            self.collisions.push(Collision {
                kind: CollisionKind::PuckPuck,
                t: hit.contact.t.max(now),
                contact: hit.contact.position,
                pucks,
                overlap_bound,
                simultaneous: true,
                pairs: graph.iter().map(|g| g.pair).collect(),
            });
            self.collision_count() - 1
        });
        // Each puck's kick, numbered by its place in the record; its
        // partner the other puck of its first contact.
        let mut kicks: Vec<(usize, Kick)> = members
            .iter()
            .enumerate()
            .map(|(k, &(i, t))| {
                let partner = graph
                    .iter()
                    .find_map(|g| match g.pair {
                        [x, y] if x == k => Some(members[y].0),
                        [x, y] if y == k => Some(members[x].0),
                        _ => None,
                    })
                    .expect("every puck of the group in a contact");
                (
                    i,
                    Kick {
                        puck: i as u32,
                        partner: partner as u32,
                        t,
                        before: before[k],
                        after: after[k],
                        version_at_contact: self.pucks[i].version,
                        record,
                        slot: k,
                        contact: contact_id,
                        settles: false,
                    },
                )
            })
            .collect();
        // Earliest first: those due now land, the others wait.
        kicks.sort_by(|x, y| x.1.t.total_cmp(&y.1.t).then(x.0.cmp(&y.0)));
        let ids: Vec<usize> = kicks
            .iter()
            .map(|&(i, kick)| self.schedule_kick(i, kick))
            .collect();
        for (&(i, kick), id) in kicks.iter().zip(ids) {
            if self.due_now(kick.t) {
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

/// Contacts due together ([`Billiard::simultaneous_group`]).
pub(super) struct Group {
    /// Each puck (index into the billiard's) and the board time (s) its
    /// velocity changes, the pair of the contact that led to the group
    /// first.
    members: SmallVec<[(usize, f64); 4]>,
    /// Each contact: its pucks, lower index first, and the contact.
    contacts: Vec<([usize; 2], PairContact)>,
}
