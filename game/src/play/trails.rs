//! What a trail is. The dotted trail is where a puck *was*: its board
//! positions over the last [`crate::model::TRAIL_S`] seconds. The solid,
//! seen trail is where the pictures *showed* it: for each past frame, the
//! board point the light of that frame's picture of the puck left from
//! (the emission event's position, on the puck's own path), drawn where
//! the picture now shows that board point. A resting eye sees a board
//! point where the light left it, so for a resting eye this is exactly
//! where each past frame showed the puck; for a moving eye (whose past
//! pictures were taken from elsewhere, with another aberration) it is the
//! one meaning that stays on the table: a resting puck's seen trail is a
//! single point, never a line into the void.

use glam::{DVec2, DVec3};

use super::shown::{Shown, project};
use crate::model::GameState;

/// The board times a trail is sampled at, ending at the view's time: the
/// last [`crate::model::TRAIL_S`] seconds, not before board time 0 (unless
/// the view's time is before 0 itself).
pub fn sample_times(state: &GameState) -> Vec<f64> {
    const SAMPLES: usize = 90;
    let t_now = state.view_time;
    let t_from = (t_now - crate::model::TRAIL_S).max(t_now.min(0.0));
    (0..=SAMPLES)
        .map(|k| t_from + (t_now - t_from) * k as f64 / SAMPLES as f64)
        .collect()
}

/// A board point `p` (at rest, board frame, m) where the picture `shown`
/// in `rect` (physical px) shows it now; `None` behind the camera.
pub fn board_point(state: &GameState, shown: &Shown, rect: [f32; 4], p: DVec3) -> Option<DVec2> {
    let s = shown
        .eye
        .see_static(p, state.scene.c, shown.effects.aberration);
    project(&shown.camera, rect, s.position)
}

/// Where puck `puck` was at each of `times` (its point `lift` above the
/// reference point), as the picture shows those board points, physical px.
pub fn truth(
    state: &GameState,
    shown: &Shown,
    rect: [f32; 4],
    puck: usize,
    lift: DVec3,
    times: &[f64],
) -> Vec<Option<DVec2>> {
    let w = state.physics().worldline(puck);
    times
        .iter()
        .map(|&t| board_point(state, shown, rect, w.position_at(t) + lift))
        .collect()
}

/// Where the picture showed puck `puck` at each of `times` (the module's
/// definition: the board point its light left from then, through the
/// view's own history, drawn as the picture shows that point now),
/// physical px.
pub fn seen(
    state: &GameState,
    shown: &Shown,
    rect: [f32; 4],
    puck: usize,
    lift: DVec3,
    times: &[f64],
) -> Vec<Option<DVec2>> {
    state
        .sim
        .seen_history(shown.view, puck, lift, times)
        .into_iter()
        .map(|then| board_point(state, shown, rect, then?.emission.event.position))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{EyeChoice, Pane};
    use lightcone_render::frame::ViewKind;

    /// Whether `p` is inside the polygon `poly` (ray casting; any shape).
    fn inside(poly: &[DVec2], p: DVec2) -> bool {
        let mut inside = false;
        for k in 0..poly.len() {
            let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
            if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) {
                inside = !inside;
            }
        }
        inside
    }

    /// While the free eye flies past the table at β = 0.7 (aberration and
    /// light delay on), every resting puck's seen trail is the one point
    /// where the picture shows it, inside the table's seen image (the
    /// cloth's rim sampled densely through the same view, curved by
    /// aberration); the moving puck's trail lies on its path on the table.
    #[test]
    fn with_the_eye_flying_at_0_7_c_resting_trails_stay_on_the_table() {
        let text = r#"
            title = "trails"
            [table]
            size = [2.84, 1.42]
            friction = 0.0
            [[puck]]
            name = "a"
            position = [0.4, 0.3]
            [[puck]]
            name = "b"
            position = [2.4, 1.1]
            [[puck]]
            name = "c"
            position = [1.4, 0.7]
            [[puck]]
            name = "mover"
            position = [0.3, 1.0]
            beta = [0.5, 0.0]
            [[observer]]
            name = "eye"
            position = [-1.5, -1.6, 1.2]
        "#;
        let scene = lightcone_engine::scene::parse(text, "trails.toml").unwrap();
        let (w, h) = (scene.table.size.x, scene.table.size.y);
        let mut g = GameState::new(scene);
        g.paused = false;
        g.intro = false;
        // u = γβ for β = 0.7 along +x.
        let u = 0.7 / (0.51_f64).sqrt();
        g.thrust(DVec3::new(u, 0.0, 0.0), DVec3::ZERO);
        let pane = Pane {
            eye: EyeChoice::Current,
            kind: ViewKind::Seen,
        };
        for _ in 0..150 {
            g.step(1.0 / 30.0);
            g.run_frame(&[(pane, 16.0 / 9.0)]);
        }
        assert!((g.eye().u.beta().length() - 0.7).abs() < 1e-9);
        let shown = super::super::shown::shown(&g, pane).unwrap();
        assert!(shown.effects.aberration && shown.effects.light_delay);
        let rect = [0.0, 0.0, 1280.0, 720.0];
        // The cloth's rim as this picture shows it.
        let rim: Vec<DVec2> = (0..400)
            .map(|k| {
                let s = f64::from(k) / 100.0;
                let (x, y) = match k / 100 {
                    0 => (s * w, 0.0),
                    1 => (w, (s - 1.0) * h),
                    2 => ((3.0 - s) * w, h),
                    _ => (0.0, (4.0 - s) * h),
                };
                board_point(&g, &shown, rect, DVec3::new(x, y, 0.0)).unwrap()
            })
            .collect();
        let times = sample_times(&g);
        assert!(times.len() > 2 && times[0] < g.view_time);
        for (i, spec) in g.scene.pucks.clone().iter().enumerate() {
            let lift = DVec3::new(0.0, 0.0, spec.height / 2.0);
            let trail = seen(&g, &shown, rect, i, lift, &times);
            let here = board_point(&g, &shown, rect, spec.position.extend(0.0) + lift).unwrap();
            for p in &trail {
                let p = p.unwrap();
                assert!(
                    inside(&rim, p),
                    "{}: trail point {p} off the table",
                    spec.name
                );
                if spec.name != "mover" {
                    assert!(p.distance(here) < 1e-6, "{}: {p} vs {here}", spec.name);
                }
            }
            if spec.name == "mover" {
                // Its trail runs along y = 1.0 m (the path), not a point.
                let spread = trail
                    .iter()
                    .map(|p| p.unwrap().distance(trail[0].unwrap()))
                    .fold(0.0, f64::max);
                assert!(spread > 20.0, "mover: trail only {spread} px long");
            }
        }
    }
}
