//! What the billiard remembers: the history horizon of worldlines and
//! collision records, and a puck's new version when its worldline changes.

use super::*;

impl Billiard {
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
    #[must_use]
    pub fn history(&self) -> Option<f64> {
        self.history
    }

    /// Puck `i`'s worldline changed: it gets a new version (predictions
    /// made with the old one go stale), its history is trimmed to the
    /// horizon, and it is predicted again.
    pub(super) fn bump(&mut self, i: usize) {
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
    pub(super) fn trim_records(&mut self) {
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
}
