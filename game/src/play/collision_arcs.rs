//! Angle arcs at a puck–puck collision: after a contact, the two pucks'
//! outgoing directions drawn from the contact point and the angle between
//! them, in degrees (the lesson's "79.8° instead of 90°", on the table).
//!
//! In the truth view an arc appears once both velocities have changed
//! (the two kicks, see the guide's collision convention) and stays for
//! [`ARC_S`] seconds of board time or until either puck is kicked again
//! (braking on the cloth and stopping do not end it). In the seen view the same, but late by the light delay
//! from the contact point to the eye: it appears when the contact is
//! seen. The angle is the board-frame angle between the outgoing
//! velocities (the engine's exact proper velocities).

use glam::{DVec2, DVec3};
use lightcone_engine::physics::{Billiard, CollisionKind};

use super::shown::{Shown, project, ring_colour};
use crate::model::GameState;
use lightcone_render::frame::ViewKind;

/// How long an arc stays, s of board time.
pub const ARC_S: f64 = 4.0;

/// Outgoing speeds below this proper velocity have no direction to draw.
const AT_REST: f64 = 1e-9;

/// An arc to draw: a puck–puck contact and its outgoing directions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arc {
    /// Index of the collision in [`Billiard::collisions`].
    pub collision: usize,
    /// The contact point on the board, m.
    pub contact: DVec3,
    /// The two pucks.
    pub pucks: [usize; 2],
    /// Their outgoing board directions (unit).
    pub directions: [DVec3; 2],
    /// The angle between them, degrees.
    pub degrees: f64,
}

/// The arc shown at board time `t` of the latest puck–puck collision, for
/// a view whose light from the contact point takes `delay(contact)`
/// seconds to arrive (0 in the truth view): `None` if no collision's arc is
/// showing.
pub fn showing(billiard: &Billiard, t: f64, delay: impl Fn(DVec3) -> f64) -> Option<Arc> {
    let records = billiard.collisions();
    for (index, k) in records.iter().enumerate().rev() {
        let then = t - delay(k.contact);
        if then > k.t + ARC_S {
            return None; // older ones are older still
        }
        if k.t > then || k.kind != CollisionKind::PuckPuck || k.pucks.len() != 2 {
            continue; // not yet (seen), or not a pair
        }
        let last_kick = k.pucks[0].t.max(k.pucks[1].t);
        if last_kick > then {
            return None; // the outcome is not complete yet
        }
        // Gone when either puck was kicked again since (a later contact's
        // velocity change); braking on the cloth and coming to rest keep
        // the direction, so the arc stays.
        let changed = records[index + 1..].iter().any(|later| {
            later.pucks.iter().any(|o| {
                o.t <= then
                    && k.pucks
                        .iter()
                        .any(|mine| mine.puck == o.puck && o.t > mine.t)
            })
        });
        if changed {
            return None;
        }
        let (a, b) = (k.pucks[0].u_after.0, k.pucks[1].u_after.0);
        if a.length() < AT_REST || b.length() < AT_REST {
            return None;
        }
        let (da, db) = (a.normalize(), b.normalize());
        let degrees = da.dot(db).clamp(-1.0, 1.0).acos().to_degrees();
        return Some(Arc {
            collision: index,
            contact: k.contact,
            pucks: [k.pucks[0].puck, k.pucks[1].puck],
            directions: [da, db],
            degrees,
        });
    }
    None
}

/// Where an arc is drawn: its view's rectangle `[x, y, w, h]` (physical
/// px), the view's kind, and the rectangles (points) its angle must not be
/// written over (the magnifier).
pub struct Place<'a> {
    /// The view's rectangle, physical px.
    pub rect: [f32; 4],
    /// Seen or truth.
    pub kind: ViewKind,
    /// What the angle's text keeps clear of, points.
    pub blocked: &'a [egui::Rect],
}

/// Draws the arc (if one is showing) in one view (`place`): the outgoing
/// directions from the contact point (a board point, where this view shows
/// it), the arc between them and the angle in degrees, written clear of
/// the magnifier where a spot beside the arc is.
pub fn draw(
    state: &GameState,
    painter: &egui::Painter,
    place: &Place<'_>,
    shown: &Shown,
    ppp: f32,
) {
    let (rect, kind) = (place.rect, place.kind);
    let (eye, camera, effects) = (shown.eye, shown.camera, shown.effects);
    let c = state.scene.c;
    let seen_view = kind == ViewKind::Seen && effects.light_delay;
    let delay = |p: DVec3| {
        if seen_view {
            (p - eye.event.position).length() / c
        } else {
            0.0
        }
    };
    let Some(arc) = showing(state.physics(), state.view_time, delay) else {
        return;
    };
    let clip = egui::Rect::from_min_size(
        egui::pos2(rect[0] / ppp, rect[1] / ppp),
        egui::vec2(rect[2] / ppp, rect[3] / ppp),
    );
    let painter = painter.with_clip_rect(clip);
    let pt = |p: DVec2| egui::pos2(p.x as f32 / ppp, p.y as f32 / ppp);
    let lift = DVec3::new(0.0, 0.0, 0.01);
    let board = |p: DVec3| {
        let s = eye.see_static(p + lift, c, effects.aberration);
        project(&camera, rect, s.position).map(pt)
    };
    let Some(centre) = board(arc.contact) else {
        return;
    };
    // Lengths on the board, m: a fraction of the table.
    let size = state.scene.table.size;
    let reach = 0.3 * size.x.min(size.y).max(1e-6);
    for (k, &d) in arc.directions.iter().enumerate() {
        let colour = ring_colour(state.scene.pucks[arc.pucks[k]].color);
        if let Some(tip) = board(arc.contact + d * reach) {
            painter.arrow(centre, tip - centre, egui::Stroke::new(2.5, colour));
        }
    }
    // The arc from the first direction to the second, the short way.
    let radius = reach * 0.45;
    let [a, b] = arc.directions;
    let turn = a.cross(b).z.signum();
    let theta = arc.degrees.to_radians();
    let points: Vec<egui::Pos2> = (0..=32)
        .filter_map(|s| {
            let phi = turn * theta * f64::from(s) / 32.0;
            let (sin, cos) = phi.sin_cos();
            let d = DVec3::new(a.x * cos - a.y * sin, a.x * sin + a.y * cos, 0.0);
            board(arc.contact + d * radius)
        })
        .collect();
    let arc_colour = egui::Color32::from_rgb(255, 225, 120);
    painter.add(egui::Shape::line(
        points.clone(),
        egui::Stroke::new(2.0, arc_colour),
    ));
    let mid = {
        let phi = turn * theta / 2.0;
        let (sin, cos) = phi.sin_cos();
        DVec3::new(a.x * cos - a.y * sin, a.x * sin + a.y * cos, 0.0)
    };
    // The angle beyond the arc's middle; where the magnifier covers that,
    // inside the arc, then across the contact from it.
    let text = painter.layout_no_wrap(
        format!("{:.1}°", arc.degrees),
        egui::FontId::proportional(16.0),
        arc_colour,
    );
    let clear = |at: egui::Pos2| {
        let r = egui::Align2::CENTER_CENTER.anchor_size(at, text.size());
        place.blocked.iter().all(|b| !b.intersects(r))
    };
    let spots: Vec<egui::Pos2> = [2.0, 0.6, -1.4]
        .iter()
        .filter_map(|&k| board(arc.contact + mid * radius * k))
        .collect();
    if let Some(&at) = spots.iter().find(|&&at| clear(at)).or(spots.first()) {
        let r = egui::Align2::CENTER_CENTER.anchor_size(at, text.size());
        painter.galley(r.min, text, arc_colour);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lightcone_engine::scene;

    /// A glancing elastic hit on an equal puck at rest, half a radius off
    /// centre, at the speed `beta` when light goes at `c`, frictionless.
    fn glancing(c: f64, beta: f64) -> (Billiard, f64) {
        glancing_on(c, beta, 0.0)
    }

    /// The same on a cloth of sliding friction `friction`.
    fn glancing_on(c: f64, beta: f64, friction: f64) -> (Billiard, f64) {
        let text = format!(
            "c = {c}\n[table]\nfriction = {friction}\n[[puck]]\nname = \"a\"\nposition = [0.5, 0.7]\nbeta = [{beta}, 0.0]\n\
             [[puck]]\nname = \"b\"\nposition = [1.4, 0.73]\n"
        );
        let scene = scene::parse(&text, "glancing.toml").expect("scene");
        let mut billiard = Billiard::from_scene(&scene);
        // The hit comes at about 0.84 m / v.
        let t_hit = 0.84 / (beta * c);
        billiard.advance_to(t_hit * 1.2);
        (billiard, t_hit)
    }

    #[test]
    fn newtonian_limit_opens_at_ninety_degrees_and_relativity_closes_it() {
        // Classical (β = 10⁻⁶): equal masses, one at rest, elastic: 90°.
        let (billiard, t) = glancing(1e6, 1e-6);
        let arc = showing(&billiard, t * 1.2, |_| 0.0).expect("an arc after the hit");
        assert!((arc.degrees - 90.0).abs() < 0.01, "{}", arc.degrees);
        // At β = 0.8 the opening angle is below 90° (tan θ₁ tan θ₂ =
        // 2 / (γ + 1), so θ₁ + θ₂ < 90°).
        let (billiard, t) = glancing(1.42, 0.8);
        let arc = showing(&billiard, t * 1.2, |_| 0.0).expect("an arc after the hit");
        let k = &billiard.collisions()[arc.collision];
        let incoming = k
            .pucks
            .iter()
            .find(|o| o.u_before.0.length() > 0.1)
            .unwrap();
        let gamma = incoming.u_before.gamma();
        let angle = |d: DVec3| d.y.atan2(d.x).abs();
        let product = angle(arc.directions[0]).tan() * angle(arc.directions[1]).tan();
        assert!(
            arc.degrees < 85.0 && (product - 2.0 / (gamma + 1.0)).abs() < 1e-6,
            "{} deg, tan·tan = {product}, 2/(γ+1) = {}",
            arc.degrees,
            2.0 / (gamma + 1.0)
        );
    }

    #[test]
    fn arcs_wait_for_the_light_and_go_after_their_time() {
        let (billiard, t) = glancing(1.42, 0.8);
        let contact_t = billiard.collisions()[0].t;
        // Seen from 2 s of light away: nothing yet just after the hit.
        assert!(showing(&billiard, contact_t + 0.1, |_| 2.0).is_none());
        assert!(showing(&billiard, t * 1.2, |_| 0.0).is_some());
        assert!(showing(&billiard, contact_t + ARC_S + 0.5, |_| 0.0).is_none());
    }

    #[test]
    fn on_a_cloth_the_arc_stays_while_the_pucks_brake_and_rest() {
        let (mut billiard, _) = glancing_on(1.42, 0.9, 0.2);
        billiard.advance_to(4.0);
        let k = billiard
            .collisions()
            .iter()
            .position(|k| k.kind == CollisionKind::PuckPuck)
            .expect("a hit");
        let hit = billiard.collisions()[k].t;
        // Both pucks at rest well before the arc's time is up.
        let rest = hit + 1.5;
        for i in 0..2 {
            assert_eq!(
                billiard.worldline(i).proper_velocity_at(rest).0,
                DVec3::ZERO
            );
        }
        let arc = showing(&billiard, rest, |_| 0.0).expect("the arc outlives the braking");
        assert_eq!(arc.collision, k);
        let outcome = &billiard.collisions()[k].pucks;
        for (d, o) in arc.directions.iter().zip(outcome) {
            assert!((*d - o.u_after.0.normalize()).length() < 1e-15);
        }
        assert!(showing(&billiard, hit + ARC_S + 0.1, |_| 0.0).is_none());
    }
}
