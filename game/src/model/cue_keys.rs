//! The cue by keys, for play without a mouse: put the cue on a puck (C,
//! the next one each time), turn it (`[` and `]`), make the stroke weaker
//! or stronger (`,` and `.`), strike (Enter). The stroke is the same
//! [`Cue`] the mouse aims, so the panel and the cue line show its β and γ.

use glam::{DVec2, DVec3};

use super::{Cue, GameState, MAX_STROKE};

/// A stroke's proper velocity γv when the cue is first put on a puck by
/// keys, m/s (60 px of mouse pull).
pub const KEY_STROKE: f64 = 1.0;

/// Weakest stroke by keys, γv in m/s.
const MIN_KEY_STROKE: f64 = 0.01;

impl GameState {
    /// Puts the cue on the next puck (the first one when none is cued),
    /// aimed from it towards the table's middle (along +x from the middle
    /// itself) with a proper velocity γv of `KEY_STROKE` m/s, or the
    /// strength the cue had.
    pub fn cue_next(&mut self) {
        let n = self.physics().len();
        if n == 0 {
            return;
        }
        let (puck, strength) = match self.cue {
            Some(c) => ((c.puck + 1) % n, c.du.length() * self.scene.c),
            None => (0, KEY_STROKE),
        };
        let here = self.physics().worldline(puck).position_at(self.live_time);
        let middle = (self.scene.table.size / 2.0).extend(0.0);
        let towards = DVec3::new(middle.x - here.x, middle.y - here.y, 0.0)
            .try_normalize()
            .unwrap_or(DVec3::X);
        self.cue = Some(Cue {
            puck,
            du: towards * (strength / self.scene.c).min(MAX_STROKE),
        });
    }

    /// Turns the cued stroke by `radians` in the board plane
    /// (counter-clockwise seen from above).
    pub fn cue_turn(&mut self, radians: f64) {
        if let Some(c) = &mut self.cue {
            let d = DVec2::from_angle(radians).rotate(c.du.truncate());
            c.du = d.extend(0.0);
        }
    }

    /// Makes the cued stroke `factor` times as strong, between 0.01 m/s of
    /// γv and [`MAX_STROKE`] in γβ.
    pub fn cue_scale(&mut self, factor: f64) {
        let c_light = self.scene.c;
        if let Some(c) = &mut self.cue
            && factor.is_finite()
            && factor > 0.0
        {
            let u = (c.du.length() * factor).clamp(MIN_KEY_STROKE / c_light, MAX_STROKE);
            c.du = c.du.normalize_or(DVec3::X) * u;
        }
    }
}
