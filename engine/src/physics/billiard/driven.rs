//! A billiard driven from outside (a CAVE render node): no events, the
//! worldlines written by the caller.

use super::*;

impl Billiard {
    /// Stops predicting anything: from now on the worldlines are written from
    /// outside, by [`Self::replace_worldline`] and [`Self::extend_worldline`],
    /// and running ahead only moves the board time. A CAVE render node
    /// drives its copy of the master's billiard this way, so that every wall
    /// sees the master's worldlines bit for bit. Pending kicks are dropped.
    pub fn drive_from_outside(&mut self) {
        self.driven = true;
        for i in 0..self.pucks.len() {
            self.calendar.remove(i as u32);
        }
        self.kicks.clear();
        self.free_kicks.clear();
    }

    /// Whether the worldlines are written from outside
    /// ([`Self::drive_from_outside`]).
    #[must_use]
    pub fn is_driven(&self) -> bool {
        self.driven
    }

    /// Puts `worldline` in place of puck `i`'s (a copy of another billiard's
    /// puck), trimmed to the history horizon. Only for a billiard driven
    /// from outside: otherwise it is re-predicted as after an impulse.
    pub fn replace_worldline(&mut self, i: usize, worldline: Worldline) {
        let k = self.internal[i] as usize;
        self.pucks[k].worldline = worldline;
        self.written(k);
    }

    /// Appends `segments` (copies of another billiard's puck `i`'s newest
    /// segments, in time order) to puck `i`'s worldline, trimmed to the
    /// history horizon. Fails, leaving what was appended before the bad
    /// one, on a segment that is not finite or does not start after the
    /// last one.
    pub fn extend_worldline(
        &mut self,
        i: usize,
        segments: &[crate::worldline::Segment],
    ) -> Result<(), crate::worldline::WorldlineError> {
        let k = self.internal[i] as usize;
        let mut result = Ok(());
        for s in segments {
            result = self.pucks[k].worldline.append(*s);
            if result.is_err() {
                break;
            }
        }
        self.written(k);
        result
    }

    /// Puck `k` (internal index) was written from outside.
    pub(super) fn written(&mut self, k: usize) {
        // A worldline from elsewhere may brake harder than any here.
        let worldline = &self.pucks[k].worldline;
        self.deceleration = self
            .deceleration
            .max(worldline.deceleration())
            .max(worldline.last().deceleration());
        if self.driven {
            let puck = &mut self.pucks[k];
            puck.version = puck.version.wrapping_add(1);
            if let Some(h) = self.history {
                let cutoff = self.time - h;
                if puck.worldline.segments().len() > 1
                    && puck.worldline.segments()[1].start.t <= cutoff
                {
                    puck.worldline.forget_before(cutoff);
                }
            }
        } else {
            self.bump(k);
        }
    }
}
