//! The magnifier: one moving puck's body drawn large in a corner of the
//! picture, seen from straight above with its direction of motion to the
//! right, over the dashed outline of its rest shape, with its β, its 1/γ
//! and the length / width of the outline drawn, so that length contraction
//! can be read off the screen. A carom puck on a whole table is 12–21 px
//! across, too small to see it shorten by 1/γ; here its rest diameter is
//! 100 px or more.
//!
//! What is drawn is the view's own output: the board-frame points where
//! the light the eye receives left each of the body's vertices (the
//! emission events the frame schedule solved), in the board's (x, y)
//! plane. Without light delay those points are board-simultaneous, so
//! the outline is the body on the table now: contracted by exactly 1/γ
//! along its motion when the view has contraction, round when it has not.
//! With light delay it is the shape the light left from (stretched when
//! the puck comes towards the eye, shortened when it goes away).

use glam::{DVec2, DVec3};

use super::shown::shown;
use crate::model::{GameState, Pane};
use lightcone_engine::ecs::BodyRef;
use lightcone_render::frame::ViewKind;

/// Smallest γ a puck must be seen with to be magnified (β ≈ 0.2).
const MIN_GAMMA: f64 = 1.02;

/// One magnified puck, physical px from the window's top left.
#[derive(Clone, Debug, PartialEq)]
pub struct Magnifier {
    /// Index of the view rectangle it is drawn over.
    pub view: usize,
    /// The puck.
    pub puck: usize,
    /// The whole inset `[x, y, w, h]` (body and caption).
    pub rect: [f32; 4],
    /// The square the body is drawn in, `[x, y, w, h]`.
    pub body: [f32; 4],
    /// Screen px per board metre in the inset.
    pub px_per_m: f64,
    /// The body's outline (convex), physical px: motion to the right.
    pub outline: Vec<DVec2>,
    /// Its rest outline's centre and radius, physical px.
    pub rest: (DVec2, f64),
    /// The speed it is seen with (at the centre's emission event), v / c.
    pub beta: f64,
    /// Its Lorentz factor then.
    pub gamma: f64,
    /// The outline's length along the motion over its width across it.
    pub length_over_width: f64,
    /// Whether the view has contraction on.
    pub contraction: bool,
    /// Whether the view has light delay on (the outline is where the
    /// light left, not the body now).
    pub light_delay: bool,
}

impl Magnifier {
    /// The caption's lines, under the body.
    pub fn caption(&self, name: &str) -> [String; CAPTION_LINES] {
        let what = match (self.contraction, self.light_delay) {
            (false, _) => "contraction off (1)",
            (true, false) => "on the table now",
            (true, true) => "where its light left it",
        };
        [
            format!("{name} from above: {what}"),
            format!("β = {:.3}    1/γ = {:.3}", self.beta, 1.0 / self.gamma),
            format!("length / width = {:.3}", self.length_over_width),
            "dashed: its shape at rest".to_owned(),
        ]
    }
}

/// Lines of a magnifier's caption.
const CAPTION_LINES: usize = 4;

/// The puck to magnify and where, over the first of `rects` (physical px)
/// that shows a seen picture (else the first): the aimed puck, then the
/// followed one, then the fastest, among those seen moving with γ ≥ 1.02;
/// `None` when no puck is seen moving or the view is too small.
pub fn layout(state: &GameState, rects: &[([f32; 4], Pane)], ppp: f32) -> Option<Magnifier> {
    if !state.show.magnifier {
        return None;
    }
    let k = rects
        .iter()
        .position(|(_, p)| p.kind == ViewKind::Seen)
        .or((!rects.is_empty()).then_some(0))?;
    let (rect, pane) = rects[k];
    let shown = shown(state, pane)?;
    let apparent = state.apparent(shown.view)?;
    let c = state.scene.c;
    // Each puck's body as seen: (puck, γ at its centre's emission, points).
    let seen: Vec<_> = apparent
        .bodies
        .iter()
        .filter_map(|b| match b.body {
            BodyRef::Puck(i) => {
                let centre = b.emissions.get(b.centre())?;
                Some((i, centre.u.gamma(), b))
            }
            BodyRef::Fixture(_) => None,
        })
        .filter(|(_, g, _)| *g >= MIN_GAMMA)
        .collect();
    let rank = |i: usize, g: f64| state.attention(i, || g);
    let &(puck, gamma, body) = seen.iter().max_by(|a, b| {
        rank(a.0, a.1)
            .total_cmp(&rank(b.0, b.1))
            .then(b.0.cmp(&a.0))
    })?;
    let spec = state.scene.pucks.get(puck)?;
    let centre = body.emissions.get(body.centre())?;
    // The inset: a square of a third of the picture's height (120–220
    // logical px), in its top right corner, the caption under it.
    let side = (rect[3] / ppp * 0.34).clamp(120.0, 220.0) * ppp;
    let line = 15.0 * ppp;
    let margin = 10.0 * ppp;
    let (w, h) = (
        side.max(250.0 * ppp),
        side + CAPTION_LINES as f32 * line + 8.0 * ppp,
    );
    if w + 2.0 * margin > rect[2] || h + 2.0 * margin > rect[3] {
        return None;
    }
    let x0 = rect[0] + rect[2] - margin - w;
    let y0 = rect[1] + margin;
    let body_sq = [x0 + (w - side) / 2.0, y0, side, side];
    // Motion along +x of the inset; the body's points in the board plane
    // relative to the centre's emission position.
    let v = centre.u.velocity(c);
    let along = DVec2::new(v.x, v.y).try_normalize().unwrap_or(DVec2::X);
    let across = along.perp();
    let flat: Vec<DVec2> = body.emissions[..body.centre()]
        .iter()
        .map(|e| {
            let d: DVec3 = e.event.position - centre.event.position;
            DVec2::new(d.truncate().dot(along), d.truncate().dot(across))
        })
        .collect();
    let hull = convex_hull(&flat);
    let extent = |f: fn(DVec2) -> f64| {
        hull.iter().fold((f64::MAX, f64::MIN), |(lo, hi), &p| {
            (lo.min(f(p)), hi.max(f(p)))
        })
    };
    let (x_lo, x_hi) = extent(|p| p.x);
    let (y_lo, y_hi) = extent(|p| p.y);
    let (length, width) = (x_hi - x_lo, y_hi - y_lo);
    if !(length > 0.0 && width > 0.0) {
        return None;
    }
    // The rest diameter fills 70 % of the square, unless the outline
    // (stretched by light delay) needs more room.
    let span = (2.0 * spec.radius).max(length).max(width);
    let px_per_m = 0.7 * f64::from(side) / span;
    let mid = DVec2::new(
        f64::from(body_sq[0] + side / 2.0),
        f64::from(body_sq[1] + side / 2.0),
    );
    let centre_of = DVec2::new((x_lo + x_hi) / 2.0, (y_lo + y_hi) / 2.0);
    let to_screen = |p: DVec2| {
        let q = (p - centre_of) * px_per_m;
        DVec2::new(mid.x + q.x, mid.y - q.y)
    };
    Some(Magnifier {
        view: k,
        puck,
        rect: [x0, y0, w, h],
        body: body_sq,
        px_per_m,
        outline: hull.iter().map(|&p| to_screen(p)).collect(),
        rest: (mid, spec.radius * px_per_m),
        beta: centre.u.beta().length(),
        gamma,
        length_over_width: length / width,
        contraction: shown.effects.contraction,
        light_delay: shown.effects.light_delay,
    })
}

/// Draws `m` (physical px; the painter's points are `ppp` px) in the
/// puck's ring colour `colour`.
pub fn draw(painter: &egui::Painter, m: &Magnifier, name: &str, colour: egui::Color32, ppp: f32) {
    let pt = |p: DVec2| egui::pos2(p.x as f32 / ppp, p.y as f32 / ppp);
    let r = |a: [f32; 4]| {
        egui::Rect::from_min_size(
            egui::pos2(a[0] / ppp, a[1] / ppp),
            egui::vec2(a[2] / ppp, a[3] / ppp),
        )
    };
    let painter = painter.with_clip_rect(r(m.rect));
    painter.rect(
        r(m.rect),
        6.0,
        egui::Color32::from_rgba_unmultiplied(12, 14, 20, 235),
        egui::Stroke::new(1.0, egui::Color32::from_gray(110)),
        egui::StrokeKind::Inside,
    );
    painter.add(egui::Shape::convex_polygon(
        m.outline.iter().map(|&p| pt(p)).collect(),
        colour,
        egui::Stroke::NONE,
    ));
    // The rest shape, dashed, over the body.
    let (c, radius) = m.rest;
    let rim: Vec<egui::Pos2> = (0..=96)
        .map(|k| {
            let a = std::f64::consts::TAU * f64::from(k) / 96.0;
            pt(c + DVec2::new(a.cos(), a.sin()) * radius)
        })
        .collect();
    painter.extend(egui::Shape::dashed_line(
        &rim,
        egui::Stroke::new(1.5, egui::Color32::from_gray(235)),
        6.0,
        4.0,
    ));
    // The direction of motion.
    let y = (m.body[1] + m.body[3] - 8.0 * ppp) / ppp;
    let x = m.body[0] / ppp + 8.0;
    painter.arrow(
        egui::pos2(x, y),
        egui::vec2(28.0, 0.0),
        egui::Stroke::new(1.5, egui::Color32::from_gray(200)),
    );
    let text = m.caption(name);
    for (k, line) in text.iter().enumerate() {
        painter.text(
            egui::pos2(
                (m.rect[0] / ppp) + 8.0,
                (m.body[1] + m.body[3]) / ppp + 2.0 + 15.0 * k as f32,
            ),
            egui::Align2::LEFT_TOP,
            line,
            egui::FontId::proportional(12.5),
            egui::Color32::from_gray(235),
        );
    }
}

/// The convex hull of `points`, counter-clockwise (Andrew's monotone
/// chain); fewer than three distinct points come back as they are.
pub fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut p: Vec<DVec2> = points.iter().copied().filter(|q| q.is_finite()).collect();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut hull: Vec<DVec2> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &DVec2>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hull_of_a_square_with_inner_points_is_its_corners() {
        let mut pts = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
        ];
        pts.extend((1..9).map(|k| DVec2::splat(f64::from(k) / 10.0)));
        pts.push(DVec2::new(0.5, 0.0));
        let hull = convex_hull(&pts);
        assert_eq!(hull.len(), 4);
        // Counter-clockwise: positive area 1.
        let area: f64 = (0..4)
            .map(|k| hull[k].perp_dot(hull[(k + 1) % 4]))
            .sum::<f64>()
            / 2.0;
        assert!((area - 1.0).abs() < 1e-12);
    }
}
