//! What is drawn over the views with egui: each puck ringed in its colour
//! with its name and clock, trails of where the pucks were seen and where
//! they were, velocity arrows, a faint ghost of the truth over the seen
//! picture, the cue with the stroke's β and γ, the dividers and captions of
//! several pictures, and the Doppler legend. Each reads its picture's view
//! (the frame schedule's output: apparent centres, clocks, eye, camera).

use glam::{DVec2, DVec3};

use super::shown::{Shown, project, ring_colour, shown};
use crate::model::{EyeChoice, GameState, Pane};
use lightcone_render::frame::ViewKind;

/// Smallest diameter of the ring marking a puck, physical px: a carom
/// puck on a whole table is 13–25 px across at 1280×720, too small to find
/// at a glance, so each is ringed in its colour at least this wide.
pub const MARKER_PX: f32 = 32.0;

/// A puck as marked over one view.
#[derive(Clone, Debug)]
pub struct Marker {
    /// Index of the view rectangle.
    pub view: usize,
    /// The puck.
    pub puck: usize,
    /// Apparent centre on screen, physical px.
    pub centre: DVec2,
    /// The ring's radius, physical px.
    pub ring: f32,
    /// The proper time its clock shows in the picture, s.
    pub clock: f64,
    /// On-screen unit direction of its rest-frame +x (its dark stripe), as
    /// the Thomas–Wigner rotation has turned it, uncontracted.
    pub heading: Option<DVec2>,
}

/// A puck's name or clock as written over a view (for the screenshot's
/// sidecar): physical px from the window's top left.
#[derive(Clone, Debug, PartialEq)]
pub struct LabelBox {
    /// The puck.
    pub puck: usize,
    /// Index of the view rectangle.
    pub view: usize,
    /// The text's box `[x, y, w, h]` (a clock's includes its dial).
    pub rect: [f32; 4],
    /// The name (`false`: the clock).
    pub is_name: bool,
}

/// What [`overlays`] drew this frame where a test or a slide needs to
/// find it, left in egui's temporary data under [`DRAWN`] for
/// `--screenshot`'s sidecar.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Drawn {
    /// Every name and clock written.
    pub labels: Vec<LabelBox>,
    /// The magnifier, when one was drawn.
    pub magnifier: Option<super::magnifier::Magnifier>,
}

/// The key of [`Drawn`] in egui's temporary data.
pub const DRAWN: &str = "lightcone overlays drawn";

/// What [`overlays`] drew at the last frame painted with `ctx`.
pub fn drawn(ctx: &egui::Context) -> Drawn {
    ctx.data(|d| d.get_temp::<Drawn>(egui::Id::unique(DRAWN)))
        .unwrap_or_default()
}

/// Which labels matter most ([`super::labels::place`]): the puck aimed,
/// then the one followed, then the fastest (board speed now).
fn label_priority(state: &GameState, markers: &[Marker]) -> Vec<f64> {
    markers
        .iter()
        .map(|m| {
            state.attention(m.puck, || {
                let u = state
                    .physics()
                    .worldline(m.puck)
                    .state_at(state.view_time)
                    .u;
                u.0.length()
            })
        })
        .collect()
}

/// The caption of a picture: what it shows, and through whose eye when
/// that is not the eye looked through.
pub fn caption(state: &GameState, pane: Pane) -> String {
    let what = match pane.kind {
        ViewKind::Truth => "truth: where the pucks are now (board frame)",
        ViewKind::Seen => "seen: what the eye's light shows",
    };
    match pane.eye {
        EyeChoice::Current => what.to_owned(),
        EyeChoice::You => format!("you, {what}"),
        EyeChoice::Scene(i) => match state.scene.observers.get(i) {
            Some(o) => format!("{}, {what}", o.name),
            None => what.to_owned(),
        },
    }
}

/// Every puck visible in its view, where it is drawn: read off each view's
/// output (the apparent centres and clocks the frame schedule computed).
pub fn markers(state: &GameState, rects: &[([f32; 4], Pane)]) -> Vec<Marker> {
    let mut out = Vec::new();
    for (k, &(rect, pane)) in rects.iter().enumerate() {
        let Some(shown) = shown(state, pane) else {
            continue;
        };
        let camera = shown.camera;
        let (right, _) = lightcone_render::camera::basis(camera.forward.normalize_or(DVec3::Y));
        for centre in state.centres(shown.view) {
            let (i, e, s) = (centre.puck, centre.emission, centre.seen);
            let Some(p) = project(&camera, rect, s.position) else {
                continue;
            };
            // Only pucks inside their own view (not over a panel or the
            // other half of a split).
            let inside = |v: f64, lo: f32, len: f32| v >= f64::from(lo) && v <= f64::from(lo + len);
            if !(inside(p.x, rect[0], rect[2]) && inside(p.y, rect[1], rect[3])) {
                continue;
            }
            let Some(spec) = state.scene.pucks.get(i) else {
                continue;
            };
            // The puck's apparent radius on screen (its rest radius at its
            // apparent distance).
            let edge = project(&camera, rect, s.position + right * spec.radius);
            let r_px = edge.map_or(0.0, |q| q.distance(p) as f32);
            let turned = state.physics().worldline(i).state_at(e.event.t).orientation;
            let ahead = s.position + DVec3::new(turned.cos(), turned.sin(), 0.0) * spec.radius;
            let heading = project(&camera, rect, ahead)
                .map(|q| q - p)
                .and_then(|d| d.try_normalize());
            out.push(Marker {
                view: k,
                puck: i,
                centre: p,
                ring: (r_px + 4.0).max(MARKER_PX / 2.0),
                clock: centre.clock,
                heading,
            });
        }
    }
    out
}

/// The clocks, names and marks over the desktop pictures, between the
/// panels' edges `left` and `right` (physical px) of a window `h` high:
/// under windows (the diagram) and the intro, in the background layer.
/// The window and the windowless slides (`render`, `record`) both draw
/// them here.
pub fn layer(ctx: &egui::Context, state: &GameState, left: f32, right: f32, h: f32) {
    let painter = ctx.layer_painter(egui::LayerId::new(
        egui::Order::Background,
        egui::Id::unique("clocks"),
    ));
    let rects = super::layout::layout(&state.pane_list(), left, right - left, h);
    overlays(state, &painter, &rects, ctx.pixels_per_point());
}

/// What is drawn over the views: each puck ringed in its colour (at least
/// [`MARKER_PX`] across) with its name and the proper time its clock shows
/// in the picture; the cue line with the stroke's β and γ; with several
/// pictures the dividers and the captions.
pub fn overlays(state: &GameState, painter: &egui::Painter, rects: &[([f32; 4], Pane)], ppp: f32) {
    let pt = |p: DVec2| egui::pos2(p.x as f32 / ppp, p.y as f32 / ppp);
    let label = egui::Color32::from_gray(235);
    let magnified = super::magnifier::layout(state, rects, ppp);
    // Where the magnifier will be drawn (points): nothing written under it.
    let blocked: Vec<egui::Rect> = magnified
        .iter()
        .map(|m| {
            egui::Rect::from_min_size(
                egui::pos2(m.rect[0] / ppp, m.rect[1] / ppp),
                egui::vec2(m.rect[2] / ppp, m.rect[3] / ppp),
            )
        })
        .collect();
    for &(rect, pane) in rects {
        if let Some(shown) = shown(state, pane) {
            physics_marks(state, painter, rect, pane.kind, &shown, ppp);
            let arc = super::collision_arcs::Place {
                rect,
                kind: pane.kind,
                blocked: &blocked,
            };
            super::collision_arcs::draw(state, painter, &arc, &shown, ppp);
        }
    }
    let markers = markers(state, rects);
    // Each clock says which time it reads: proper time (τ) with time
    // dilation, board time (t) without.
    let dilated: Vec<bool> = rects
        .iter()
        .map(|&(_, pane)| shown(state, pane).is_some_and(|s| s.effects.time_dilation))
        .collect();
    let galleys: Vec<_> = markers
        .iter()
        .map(|m| {
            let name = &state.scene.pucks[m.puck].name;
            let which = if dilated.get(m.view).copied().unwrap_or(false) {
                "τ"
            } else {
                "t"
            };
            (
                painter.layout_no_wrap(name.clone(), egui::FontId::proportional(12.0), label),
                painter.layout_no_wrap(
                    format!("{which} {:.2} s", m.clock),
                    egui::FontId::monospace(11.0),
                    label,
                ),
            )
        })
        .collect();
    let anchors: Vec<super::labels::Anchor> = markers
        .iter()
        .map(|m| super::labels::Anchor {
            centre: pt(m.centre),
            ring: m.ring / ppp,
        })
        .collect();
    let dial = |g: &std::sync::Arc<egui::Galley>| g.size().y + 3.0;
    let placed = super::labels::place(
        &anchors,
        &label_priority(state, &markers),
        &blocked,
        |i, name| {
            if name {
                galleys[i].0.size()
            } else {
                let g = &galleys[i].1;
                g.size() + egui::vec2(dial(g), 0.0)
            }
        },
    );
    for p in &placed {
        if p.is_name {
            painter.galley(p.rect.min, galleys[p.marker].0.clone(), label);
        } else {
            let g = &galleys[p.marker].1;
            let d = dial(g);
            clock_dial(
                painter,
                p.rect.min + egui::vec2(d / 2.0 - 1.0, p.rect.height() / 2.0),
                (d - 4.0) / 2.0,
                markers[p.marker].clock,
            );
            painter.galley(p.rect.min + egui::vec2(d, 0.0), g.clone(), label);
        }
    }
    // What was written where, for the screenshot's sidecar.
    let labels: Vec<LabelBox> = placed
        .iter()
        .map(|p| LabelBox {
            puck: markers[p.marker].puck,
            view: markers[p.marker].view,
            rect: [
                p.rect.min.x * ppp,
                p.rect.min.y * ppp,
                p.rect.width() * ppp,
                p.rect.height() * ppp,
            ],
            is_name: p.is_name,
        })
        .collect();
    for m in markers {
        let spec = &state.scene.pucks[m.puck];
        let colour = ring_colour(spec.color);
        let r = m.ring / ppp;
        painter.circle_stroke(pt(m.centre), r, egui::Stroke::new(2.5, colour));
        // A tick on the ring where the puck's rest-frame +x points: it turns
        // with the Thomas–Wigner rotation, not with the contraction.
        if let Some(d) = m.heading {
            let d = egui::vec2(d.x as f32, d.y as f32);
            painter.line_segment(
                [pt(m.centre) + d * r, pt(m.centre) + d * (r + 7.0)],
                egui::Stroke::new(2.5, colour),
            );
        }
        // The cue: from the puck along the stroke, with the β and γ the
        // puck will have.
        let (rect, pane) = rects[m.view];
        if let Some(cue) = state.cue.filter(|c| c.puck == m.puck)
            && pane.kind == ViewKind::Seen
            && cue.du.length() > 0.0
            && let Some(shown) = shown(state, pane)
            && let Some(centre) = state
                .centres(shown.view)
                .into_iter()
                .find(|c| c.puck == m.puck)
        {
            let metres = (cue.du.length() * state.scene.c * 0.25).clamp(0.1, 1.5);
            let tip = centre.seen.position + cue.du.normalize() * metres;
            if let Some(q) = project(&shown.camera, rect, tip) {
                let u = lightcone_engine::spacetime::ProperVelocity(
                    state
                        .physics()
                        .worldline(cue.puck)
                        .proper_velocity_at(state.live_time)
                        .0
                        + cue.du,
                );
                let cue_colour = egui::Color32::from_rgb(120, 190, 255);
                painter.arrow(
                    pt(m.centre),
                    pt(q) - pt(m.centre),
                    egui::Stroke::new(2.5, cue_colour),
                );
                painter.text(
                    pt(q) + egui::vec2(6.0, 0.0),
                    egui::Align2::LEFT_CENTER,
                    format!("β = {:.4}\nγ = {:.4}", u.beta().length(), u.gamma()),
                    egui::FontId::proportional(14.0),
                    cue_colour,
                );
            }
        }
    }
    if let Some(m) = &magnified {
        let spec = &state.scene.pucks[m.puck];
        super::magnifier::draw(painter, m, &spec.name, ring_colour(spec.color), ppp);
    }
    let drawn = Drawn {
        labels,
        magnifier: magnified,
    };
    painter
        .ctx()
        .data_mut(|d| d.insert_temp(egui::Id::unique(DRAWN), drawn));
    if rects.len() > 1 {
        for &(rect, pane) in rects {
            painter.text(
                egui::pos2((rect[0] + rect[2] / 2.0) / ppp, rect[1] / ppp + 8.0),
                egui::Align2::CENTER_TOP,
                caption(state, pane),
                egui::FontId::proportional(14.0),
                egui::Color32::from_gray(240),
            );
        }
        for &(rect, _) in &rects[1..] {
            let x = rect[0] / ppp;
            let h = rect[3] / ppp;
            painter.line_segment(
                [egui::pos2(x, 0.0), egui::pos2(x, h)],
                egui::Stroke::new(2.0, egui::Color32::from_gray(200)),
            );
        }
    }
}

/// Seconds of proper time a clock's dial hand takes to go round once.
pub const DIAL_PERIOD_S: f64 = 2.0;

/// A clock's dial: a ring of `radius` (logical px) at `centre` with one
/// hand at `clock` (s) on a [`DIAL_PERIOD_S`] face, turning clockwise from
/// the top; beside each puck's clock, so that a slow clock is seen slow.
fn clock_dial(painter: &egui::Painter, centre: egui::Pos2, radius: f32, clock: f64) {
    let grey = egui::Color32::from_gray(200);
    painter.circle_stroke(centre, radius, egui::Stroke::new(1.2, grey));
    let a = std::f64::consts::TAU * (clock / DIAL_PERIOD_S).rem_euclid(1.0);
    let hand = egui::vec2(a.sin() as f32, -(a.cos() as f32)) * (radius - 1.0);
    painter.line_segment(
        [centre, centre + hand],
        egui::Stroke::new(2.0, egui::Color32::from_gray(245)),
    );
}

/// `colour` at opacity `alpha` (0–255).
fn faded(colour: egui::Color32, alpha: u8) -> egui::Color32 {
    egui::Color32::from_rgba_unmultiplied(colour.r(), colour.g(), colour.b(), alpha)
}

/// Trails, the truth ghost and velocity arrows of every puck in one view.
fn physics_marks(
    state: &GameState,
    painter: &egui::Painter,
    rect: [f32; 4],
    kind: ViewKind,
    shown: &Shown,
    ppp: f32,
) {
    let show = state.show;
    if !(show.trails || show.ghost || show.arrows) {
        return;
    }
    let pt = |p: DVec2| egui::pos2(p.x as f32 / ppp, p.y as f32 / ppp);
    let effects = shown.effects;
    let c = state.scene.c;
    let clip = egui::Rect::from_min_size(
        egui::pos2(rect[0] / ppp, rect[1] / ppp),
        egui::vec2(rect[2] / ppp, rect[3] / ppp),
    );
    let painter = painter.with_clip_rect(clip);
    // A board point (at rest) where this view shows it.
    let board = |p: DVec3| super::trails::board_point(state, shown, rect, p);
    let t_now = state.view_time;
    let times = super::trails::sample_times(state);
    let seen_view = kind == ViewKind::Seen && effects.light_delay;
    let centres = state.centres(shown.view);
    for (i, spec) in state.scene.pucks.iter().enumerate() {
        let w = state.physics().worldline(i);
        let colour = ring_colour(spec.color);
        let lift = DVec3::new(0.0, 0.0, spec.height / 2.0);
        if show.trails && times.len() > 1 && times[0] < t_now {
            // Where it was: dotted.
            let truth = super::trails::truth(state, shown, rect, i, lift, &times);
            for (k, pair) in truth.windows(2).enumerate() {
                if let (Some(a), Some(b)) = (pair[0], pair[1])
                    && k % 2 == 0
                {
                    painter
                        .line_segment([pt(a), pt(b)], egui::Stroke::new(1.5, faded(colour, 150)));
                }
            }
            // Where the pictures showed it: solid (light delay on).
            if seen_view {
                let seen = super::trails::seen(state, shown, rect, i, lift, &times);
                for pair in seen.windows(2) {
                    if let (Some(a), Some(b)) = (pair[0], pair[1]) {
                        painter.line_segment(
                            [pt(a), pt(b)],
                            egui::Stroke::new(2.0, faded(colour, 210)),
                        );
                    }
                }
            }
        }
        // The motion now (the tangent of a braking segment).
        let segment = w.segment_at(t_now).tangent_at(t_now);
        if show.ghost && seen_view {
            // The truth now, contracted: a faint outline and fill.
            let centre = w.position_at(t_now) + lift;
            let rim: Vec<egui::Pos2> = (0..24)
                .filter_map(|k| {
                    let a = std::f64::consts::TAU * f64::from(k) / 24.0;
                    let r = segment.contract(DVec3::new(a.cos(), a.sin(), 0.0) * spec.radius);
                    board(centre + r).map(pt)
                })
                .collect();
            if rim.len() == 24 {
                painter.add(egui::Shape::convex_polygon(
                    rim,
                    faded(colour, 45),
                    egui::Stroke::new(1.2, faded(colour, 170)),
                ));
            }
        }
        if show.arrows {
            // The velocity: now (truth) or when the light left (seen). A
            // board point is drawn where light from it shows it, so the
            // emission event's position is where the seen puck is drawn.
            let seen_from = centres
                .iter()
                .find(|m| m.puck == i)
                .filter(|_| seen_view)
                .map(|m| (m.emission.event.position, m.emission.u.velocity(c)));
            let (from, v) =
                seen_from.unwrap_or_else(|| (w.position_at(t_now) + lift, segment.velocity()));
            if v.length() > 1e-9
                && let (Some(a), Some(b)) = (board(from), board(from + v * 0.5))
            {
                painter.arrow(
                    pt(a),
                    pt(b) - pt(a),
                    egui::Stroke::new(2.0, faded(colour, 230)),
                );
            }
        }
    }
}

/// The Doppler colour key, in the panel.
pub fn doppler_legend(ui: &mut egui::Ui) {
    ui.horizontal_wrapped(|ui| {
        ui.small("Doppler:");
        ui.colored_label(egui::Color32::from_rgb(140, 150, 255), "approaching: bluer");
        ui.colored_label(egui::Color32::from_rgb(255, 130, 110), "receding: redder");
    });
    ui.small("hue shifted, brightness kept; the ring keeps each puck's own colour");
}
