//! Anticipation: each puck's one pending event, the earliest of its kicks,
//! cushions, shell exit, stop and pair contacts (the pair policy and the
//! cheap bounds are `predict::pair` and `predict::bounds`).

use super::*;

impl Billiard {
    pub(super) fn mover(&self, i: usize) -> puck_puck::Mover<'_> {
        puck_puck::Mover {
            segment: self.pucks[i].worldline.last(),
            radius: self.pucks[i].radius,
        }
    }

    /// Whether pucks `a` and `b` have collided and nothing has changed
    /// either since: their last kicks are of one pair contact, one is the
    /// other's partner there (no pair of contacts resolved together,
    /// `simultaneous`, is: their outcome need not separate each pair), and
    /// neither has changed since (see `Puck::kicked_by`).
    pub(super) fn settled(&self, a: usize, b: usize) -> bool {
        let (pa, pb) = (&self.pucks[a], &self.pucks[b]);
        match (pa.kicked_by, pb.kicked_by) {
            (Some((ca, va, partner_a)), Some((cb, vb, partner_b))) => {
                ca == cb
                    && va == pa.version
                    && vb == pb.version
                    && (partner_a as usize == b || partner_b as usize == a)
            }
            _ => false,
        }
    }

    /// Whether a kick of a contact between pucks `a` and `b` is still
    /// ahead of one of them: a kick whose partner is the other, or (a
    /// group of contacts resolved together, `simultaneous`) a kick of the
    /// group whose kick the other has taken last. Any two pucks of a group
    /// wait for its kicks, whether or not they were a pair in it (two
    /// strikers of one puck never met: they are predicted against each
    /// other once the later of their kicks has landed, and a contact of
    /// theirs before that is found then, at once).
    pub(super) fn pending_with(&self, a: usize, b: usize) -> bool {
        let waits = |x: usize, y: usize| {
            let taken = self.pucks[y].kicked_by.map(|(contact, _, _)| contact);
            self.pucks[x].pending.iter().any(|&k| {
                self.kicks[k].is_some_and(|kick| {
                    kick.partner as usize == y || (!kick.settles && Some(kick.contact) == taken)
                })
            })
        };
        waits(a, b) || waits(b, a)
    }

    /// The next contact of pucks `a` and `b` from board time `now` on
    /// ([`pair::contact`]; `board_only` for a settled pair, see
    /// `Puck::kicked_by`). Only a contact processed at or before `horizon`
    /// (s) counts: a braking pair's search stops there (not on the
    /// reference path, which searches on so that the test comparing the
    /// two loops checks the cut).
    pub(super) fn contact_of(
        &self,
        a: usize,
        b: usize,
        now: f64,
        board_only: bool,
        horizon: f64,
    ) -> Option<PairContact> {
        pair::contact(
            self.mover(a),
            self.mover(b),
            self.c,
            now,
            board_only,
            !self.reference,
            horizon,
        )
    }

    /// Puck `i`'s pending event from now on: the earliest of its pending
    /// velocity changes, its cushion contacts, its shell exit and its
    /// contacts with its candidate partners. A pair's exact prediction is
    /// made only if a cheap lower bound on its time ([`bounds::disc_touch`]) can
    /// beat the earliest found so far; a pair contact later than either
    /// puck's shell exit is left for the shell move to find (so the outcome
    /// does not depend on which pairs the broad phase reports beyond what
    /// the shells guarantee).
    pub(super) fn predict(&mut self, i: usize) {
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
        let mut own_reach = None;
        for j in candidates {
            if self.reference {
                bounded.push((f64::NEG_INFINITY, j as u32));
                continue;
            }
            let other = &self.hot[j];
            let limit = best.t.min(other.exit);
            let bound = if own.braking || other.braking {
                // Rest discs grown so that their touch bounds the earlier
                // kick, which can precede the contact ([`bounds::braking_kick`]).
                if own.braking_apart_until(other, self.deceleration, self.c, now, limit) {
                    pruned += 1;
                    continue;
                }
                let own_reach = *own_reach.get_or_insert_with(|| {
                    bounds::BrakingReach::of(self.pucks[i].worldline.last(), now)
                });
                let reach = bounds::BrakingReach::of(self.pucks[j].worldline.last(), now);
                let (ri, rj) = (self.pucks[i].radius, self.pucks[j].radius);
                if i < j {
                    bounds::braking_kick(&own_reach, ri, &reach, rj, self.c, now, limit)
                } else {
                    bounds::braking_kick(&reach, rj, &own_reach, ri, self.c, now, limit)
                }
            } else {
                bounds::disc_touch(
                    own_now,
                    own.v,
                    own.radius,
                    other.position_at(now),
                    other.v,
                    other.radius,
                    now,
                )
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
            let horizon = if self.reference { f64::INFINITY } else { limit };
            let Some(hit) = self.contact_of(a, b, now, settled, horizon) else {
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
    pub(super) fn shell_exit(&self, i: usize) -> f64 {
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
        // |d + v τ|² = margin²: the positive root (q < 0, so there is one).
        self.time + bounds::later_root(d.dot(v), q, vv).unwrap_or(0.0)
    }
}
