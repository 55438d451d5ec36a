//! Running the loop: take the earliest event from the calendar, hand it
//! to what it is about, predict again what it changed.

use super::*;

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
        self.until = t;
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

    /// Handles puck `i`'s pending event, due at board time `t`.
    pub(super) fn handle(&mut self, i: usize, t: f64) {
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
                } else if !self.changes_due_now(a, b) {
                    // A cushion bounce due now moved one of them (a Zeno
                    // cluster's merge): their contact is predicted again.
                    self.stats.stale += 1;
                } else {
                    let flushed_a = self.flush_pending(a);
                    let flushed_b = self.flush_pending(b);
                    if flushed_a || flushed_b {
                        // Others due to meet one of them now land theirs
                        // too, so that contacts at one board time start
                        // from states that do not depend on which of them
                        // the loop took first.
                        for j in self.due_with(a, b, t) {
                            self.flush_pending(j);
                        }
                    }
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
    pub(super) fn fetch_upcoming(&self, deep: bool) {
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
    pub(super) fn move_shell(&mut self, i: usize) {
        self.stats.shell_moves += 1;
        self.shells[i] = self.pucks[i]
            .worldline
            .last()
            .position_at(self.time)
            .truncate();
        self.broad
            .set_shell(i, self.shells[i], self.pucks[i].radius + self.margin);
    }
}
