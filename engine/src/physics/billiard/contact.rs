//! Resolving contacts: a puck on a cushion, a pair of pucks (in the pair
//! frame, or pushed apart on the board), and the clusters they press.

use super::*;

impl Billiard {
    pub(super) fn cushion_contact(&mut self, i: usize, cushion: Cushion, t: f64) {
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
        // Where the first puck touched the cushion (before any hold).
        let mut touched = None;
        for &k in &cluster {
            touched.get_or_insert_with(|| self.pucks[k].worldline.position_at(t_kink));
            if self.pucks[k].worldline.push(t_kink, after).is_err() {
                continue;
            }
            // An elastic bounce keeps both half-widths (it negates the
            // normal part of `u`, exactly). The Zeno limit drops the normal
            // part, widening the shape along the normal into the cushion
            // pressed: held. An inelastic bounce widens it too, but is not
            // held: the puck is then often pressed by another, and each
            // hold would move it into that one, a settled pair whose
            // overlap is not resolved, bounce after bounce (found: a pusher
            // ratcheted through the pressed puck). Its shape stays in the
            // cushion by at most R (1 − 1/γ) until it moves out.
            if zeno {
                self.hold_off_cushions(k);
            }
            let puck = &self.pucks[k];
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
            let contact = touched.unwrap_or(outcomes[0].position)
                + puck_cushion::support_offset(radius, before, cushion);
            self.collisions.push(Collision {
                kind: CollisionKind::Cushion(cushion),
                t: t_kink,
                contact,
                pucks: outcomes,
                overlap_bound: 0.0,
                simultaneous: false,
                pairs: Vec::new(),
            });
        }
        for k in cluster {
            self.bump(k);
        }
    }

    /// Keeps puck `i`'s board shape out of the cushions after a velocity
    /// change at the start of its last segment (a collision's kick, an
    /// impulse, a Zeno merge).
    ///
    /// A kick changes the board-frame contraction of the whole body at one
    /// board time: its half-width along a table axis, `R √(1 − βₖ²)`, can
    /// grow by up to `R (1 − 1/γ)`. Next to a cushion (a puck touching
    /// one when its kick lands, or kicked an instant before it gets there)
    /// the new shape would reach into the cushion by that much, up to
    /// centimetres at γ of a few hundred (issue 30, item 4), although no
    /// point of a real body passes through the cushion: the cushion holds
    /// the rim point it touches. So the body re-contracts about that point:
    /// its centre moves back from the cushion by the depth the new shape
    /// would have had, so that the shape just touches it. Momenta, energy
    /// and the kick's board time are unchanged. If the puck then moves into
    /// the cushion, the cushion contact is predicted at once (at this same
    /// board time) and resolved as any other. A shape the move brings
    /// towards another puck overlaps it by at most that jump: an unsettled
    /// pair overlapping and closing is pushed apart at once (a board
    /// contact), while the pair whose contact made the kick, settled, is
    /// not predicted again while they overlap (`predict::pair`): that
    /// overlap stays until they part, within the pair's allowance plus the
    /// jump. The puck's broad-phase shell follows the
    /// centre if the jump takes it past the shell's margin.
    pub(super) fn hold_off_cushions(&mut self, i: usize) {
        let table = self.table;
        let puck = &mut self.pucks[i];
        let segment = *puck.worldline.last();
        let centre = segment.start.position;
        let mut shift = DVec3::ZERO;
        for axis in 0..2 {
            let h = puck_cushion::half_width(puck.radius, segment.u, axis);
            let below = h - centre[axis];
            let above = centre[axis] + h - table[axis];
            if below > 0.0 {
                shift[axis] = below;
            } else if above > 0.0 {
                shift[axis] = -above;
            }
        }
        if shift != DVec3::ZERO {
            puck.worldline.shift_last(shift);
            self.stats.cushion_holds += 1;
            let centre = self.pucks[i].worldline.last().start.position.truncate();
            if (centre - self.shells[i]).length() > self.margin {
                self.move_shell(i);
            }
        }
    }

    /// The pucks that can touch puck `m` now: its broad-phase partners
    /// (every puck, on the reference path), in index order, so a cluster
    /// grows in the same order either way.
    pub(super) fn neighbours(&self, m: usize) -> Vec<usize> {
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
    pub(super) fn pressed_cluster(&self, i: usize, u: ProperVelocity, t: f64) -> Vec<usize> {
        let same = |w: ProperVelocity| (w.0 - u.0).length() <= 1e-12 * u.0.length();
        self.touching_cluster(vec![i], t, |p| {
            p.pending.is_empty() && same(p.worldline.last().u_at(t))
        })
    }

    /// `seeds` and every puck reached from them through touching pucks
    /// (centres at most the sum of radii apart at board time `t`, m) that
    /// `joins` accepts, in the order reached.
    pub(super) fn touching_cluster(
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
    pub(super) fn pair_contact(
        &mut self,
        a: usize,
        b: usize,
        kept: Option<PairContact>,
        predicted_at: f64,
    ) {
        let hit = if self.reference {
            self.contact_of(a, b, predicted_at, self.settled(a, b), f64::INFINITY)
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
        // Another contact on one of them at this same board time: resolved
        // together, whatever their order (`simultaneous`). Not at
        // restitution 0: moving each group together at once, a cluster
        // pressed into a cushion was merged group by overlapping group
        // (every merge setting a shared puck apart from the other group)
        // some 10⁵ times at one board time (random scene seed 26); one by
        // one, the Zeno merge ends such a sequence after 64.
        if !zeno
            && self.restitution > 0.0
            && let Some(group) = self.simultaneous_group(a, b, &hit, predicted_at)
            && self.group_contact(group, contact_id)
        {
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
        let overlap_bound = if self.record {
            self.overlap_bound_of([a, b], times, before, after, hit.gamma_pair)
        } else {
            0.0
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
                simultaneous: false,
                pairs: Vec::new(),
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
                settles: true,
            };
            ids[k] = self.schedule_kick(i, kick);
        }
        // The kicks that are due land now, earliest first; a later one
        // becomes its puck's pending event if it is the earliest.
        let order = if times[0] <= times[1] { [0, 1] } else { [1, 0] };
        for k in order {
            let id = ids[k];
            if self.due_now(times[k]) {
                self.land_kick(id);
            } else {
                self.offer_kick([a, b][k], id, times[k]);
            }
        }
    }

    /// The most pucks `ab` may overlap on the board because of their
    /// contact (m), for its record: each puck's kick at `times` (s), from
    /// `before` to `after` ([`overlap::bound`], with the depth the first
    /// kick's new shape has against the other's old one).
    pub(super) fn overlap_bound_of(
        &self,
        ab: [usize; 2],
        times: [f64; 2],
        before: [Body; 2],
        after: [Body; 2],
        gamma_pair: f64,
    ) -> f64 {
        let [a, b] = ab;
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
            gamma_pair,
            (times[second] - times[first]) * closing.length(),
            early,
        )
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
    pub(super) fn board_push(
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
            let found = overlap::penetration(sa, ra, sb, rb, t)
                .map(|found| overlap::contact_normal(sa, ra, sb, rb, t, found));
            let m = match found {
                // Still overlapping: closing along the new direction?
                Some(m) if m.dot(v_rel) < -still => m,
                Some(_) => break,
                // Apart: would sliding bring them together again?
                None => match pair::touch_again(xa, ra, after[0].u, xb, rb, after[1].u, self.c) {
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
}
