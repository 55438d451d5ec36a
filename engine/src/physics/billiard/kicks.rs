//! Velocity changes still ahead: the second kick of a pair contact
//! offered, landed or flushed early, and impulses from outside.

use super::*;

impl Billiard {
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
        self.hold_off_cushions(i);
        self.bump(i);
        Ok(())
    }

    /// A puck about to meet something while the second kick of an earlier
    /// contact is still ahead of it takes that kick now, so every collision
    /// starts from the puck's complete state and 4-momentum stays exactly
    /// conserved. Returns whether anything landed (the puck then has new
    /// predictions).
    pub(super) fn flush_pending(&mut self, i: usize) -> bool {
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

    /// Stores `kick` (of puck `i`) in the kick table and among the puck's
    /// pending kicks; returns its id.
    pub(super) fn schedule_kick(&mut self, i: usize, kick: Kick) -> usize {
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
        id
    }

    /// A kick of puck `i` at board time `t` has been scheduled and nothing
    /// else about the puck changed: it becomes the puck's pending event if
    /// it comes first.
    pub(super) fn offer_kick(&mut self, i: usize, id: usize, t: f64) {
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

    pub(super) fn land_kick(&mut self, id: usize) {
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
        self.hold_off_cushions(i);
        let puck = &mut self.pucks[i];
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
        // The version this change leaves: with the partner's kick of this
        // contact taken too and nothing else since, the pair is settled.
        let version = self.pucks[i].version.wrapping_add(1);
        let partner = if kick.settles { kick.partner } else { u32::MAX };
        self.pucks[i].kicked_by = Some((kick.contact, version, partner));
        self.bump(i);
    }
}
