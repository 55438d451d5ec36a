//! One-line hints for what the screen shows but does not explain: a struck
//! puck still seen at rest (the stroke's light is on its way), clocks that
//! read below zero (light that left before the scene began), and
//! aberration, which a resting eye never shows.

use glam::DVec3;

use super::GameState;

/// The last stroke of the cue: which puck, and the board event (s, m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stroke {
    /// The puck struck.
    pub puck: usize,
    /// Board time of the stroke, s.
    pub t: f64,
    /// The puck's centre at the stroke, board frame, m.
    pub position: DVec3,
}

impl GameState {
    /// Board seconds until the eye looked through sees the last stroke
    /// (its light reaches the eye), or `None` once it has (or with no
    /// stroke). For an eye at rest at `e` the light arrives at
    /// `t_s + |x_s − e| / c`; a moving eye is taken where it is now (a
    /// hint, not a measurement: the seen pictures are exact).
    pub fn stroke_light_in(&self) -> Option<f64> {
        let s = self.last_stroke?;
        let eye = self.eye();
        let arrival = s.t + (s.position - eye.event.position).length() / self.scene.c;
        let left = arrival - self.view_time;
        (self.view_time >= s.t && left > 0.0).then_some(left)
    }

    /// The hints to show now, most useful first (empty when there is
    /// nothing to explain). `seen_clocks`: the clocks the seen picture
    /// shows, s.
    pub fn hints(&self, seen_clocks: &[f64]) -> Vec<String> {
        let mut out = Vec::new();
        if let Some(left) = self.stroke_light_in()
            && let Some(s) = self.last_stroke
        {
            out.push(format!(
                "{} is still seen where it was: the light from your stroke is on its way ({left:.1} s)",
                self.physics().name(s.puck)
            ));
        }
        if seen_clocks.iter().any(|&c| c < 0.0) {
            out.push(
                "a clock below 0 s: the light you see left that puck before the scene began (t = 0)"
                    .to_owned(),
            );
        }
        let still = self.eye().u.0.length() < 1e-9;
        if self.effects.aberration && still && self.observer.is_none() {
            out.push("aberration needs a moving eye: hold W (X stops)".to_owned());
        }
        out
    }
}
