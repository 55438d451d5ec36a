//! The space-time diagram (`lightcone diagram`, and the live diagram in
//! the window): board time up, a board axis across. Each puck's worldline
//! (its centre's x against t), the eye's worldline and its observation
//! event, where the eye's past light cone meets each worldline (the
//! emission event whose light the eye receives then), collisions as marked
//! events, over a grid labelled in metres and seconds with the cushions and
//! the board's "now".
//!
//! One description, two painters: [`plot_with`] lists every mark in
//! diagram coordinates (board x or y in m, board time in s) with the
//! legend's keys, and the painters only map those to pixels
//! ([`Plot::to_px`], [`dashes`]): [`draw_with`] into an [`Image`](crate::headless::Image) on the CPU
//! (no GPU needed), the game's window with egui's painter.
//!
//! The light cone of an eye at a height above the board is not a pair of
//! straight lines in the (x, t) plane: for each puck the diagram draws, as a
//! dashed curve in its colour, the cone's trace along that puck's path,
//! `t = T − |X(t) − eye| / c`; the puck's worldline crosses it exactly at the
//! emission event.
//!
//! With a *frame* (a puck, [`Options::frame`]) it also draws that puck's
//! line of simultaneity through its event at the current instant: the
//! board events its rest frame calls "now", `t = t₀ + v·Δx / c²`
//! ([`lightcone_engine::spacetime::simultaneous_board_time`]), beside the
//! board's own "now" (the horizontal line through the observation).

use glam::DVec3;
use lightcone_engine::physics::Billiard;
use lightcone_engine::scene::Scene;
use lightcone_engine::spacetime::{Event, simultaneity_slope, simultaneous_board_time};
use lightcone_engine::worldline::Worldline;

mod grid;
mod raster;

pub use grid::{GridAxis, label_text};
pub use raster::{Drawn, draw, draw_with};

#[cfg(test)]
mod tests;

/// Where the eye's past light cone, from observation event `eye`, meets
/// the worldline of the point at `offset` from the body's centre (not
/// contracted: `offset` is vertical), with light speed `c`: the root of
/// `g(t) = c (T − t) − |X(t) − x_eye|`, which falls strictly along any
/// worldline slower than light, found by bisection. Computed here on the
/// diagram's own terms, independently of the optics' closed form.
#[must_use]
pub fn cone_crossing(worldline: &Worldline, offset: DVec3, eye: Event, c: f64) -> Event {
    let g = |t: f64| c * (eye.t - t) - (worldline.position_at(t) + offset).distance(eye.position);
    let mut hi = eye.t;
    let mut step = 1.0;
    let mut lo = eye.t - step;
    while g(lo) < 0.0 && step < 1e12 {
        hi = lo;
        step *= 2.0;
        lo = eye.t - step;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if g(mid) >= 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let t = 0.5 * (lo + hi);
    Event::new(t, worldline.position_at(t) + offset)
}

/// What a mark shows: the legend's subject, and how tests find a mark.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// A grid line (every [`Plot::grid`] step, m across or s up).
    Grid,
    /// The line t = 0.
    TimeZero,
    /// A cushion: the table's edge along the axis across (0 or the side).
    Cushion,
    /// The eye's worldline (where it is now, through the time shown).
    EyeWorldline,
    /// The eye's past light cone traced along puck `i`'s path.
    Cone(usize),
    /// Puck `i`'s worldline.
    Worldline(usize),
    /// The board's "now": the horizontal line through the observation.
    BoardNow,
    /// The frame's "now": its line of simultaneity through its event.
    FrameNow,
    /// One of the frame's earlier nows (every 0.5 s of its proper time).
    FrameEarlierNow,
    /// An event the eye sees now (on puck `i`'s worldline).
    Seen(usize),
    /// The observation event: the eye, now.
    Eye,
    /// The frame puck's event now.
    FrameEvent,
    /// A collision.
    Collision,
    /// A grid line's value (m or s).
    GridLabel,
}

/// Where a label sits from its point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Place {
    /// Centred under it (the x axis' values).
    Below,
    /// Ending left of it, centred on it (the time axis' values).
    Left,
}

/// One thing drawn, in diagram coordinates (board x or y in m, board time
/// in s); sizes are in pixels (points in the window).
#[derive(Clone, Debug, PartialEq)]
pub enum Mark {
    /// A polyline.
    Line {
        /// What it is.
        role: Role,
        /// Its points (x, t).
        points: Vec<(f64, f64)>,
        /// sRGB colour.
        rgb: [u8; 3],
        /// Width, px.
        width: f64,
        /// Opacity, 0–1.
        alpha: f64,
        /// Dashed ([`DASH`] on, [`GAP`] off, px).
        dashed: bool,
    },
    /// An event: a disc of radius [`EVENT_RADIUS`] ringed in white.
    Event {
        /// What it is.
        role: Role,
        /// Where (x, t).
        at: (f64, f64),
        /// sRGB colour.
        rgb: [u8; 3],
    },
    /// A collision: a white cross, [`CROSS`] px each way.
    Cross {
        /// Where (x, t).
        at: (f64, f64),
    },
    /// A text of [`LABEL_PX`] px beside a point.
    Label {
        /// What it labels.
        role: Role,
        /// The point (x, t).
        at: (f64, f64),
        /// The text.
        text: String,
        /// Where it sits from the point.
        place: Place,
        /// sRGB colour.
        rgb: [u8; 3],
    },
}

impl Mark {
    /// What the mark shows (a cross: [`Role::Collision`]).
    #[must_use]
    pub fn role(&self) -> Role {
        match self {
            Self::Line { role, .. } | Self::Event { role, .. } | Self::Label { role, .. } => *role,
            Self::Cross { .. } => Role::Collision,
        }
    }
}

/// A dash's length along a dashed line, px.
pub const DASH: f64 = 7.0;
/// The gap between dashes, px.
pub const GAP: f64 = 5.0;
/// An event's disc: its radius, px (with a white ring 2 px wider).
pub const EVENT_RADIUS: f64 = 5.0;
/// A collision's cross: half its side, px.
pub const CROSS: f64 = 5.0;
/// The labels' and the legend's text height, px (points in the window).
pub const LABEL_PX: f64 = 13.0;
/// Room left around the plotting area for the labels, px: left (the time
/// values), right, top, bottom (the x values).
pub const MARGINS: [f64; 4] = [52.0, 12.0, 10.0, 24.0];
/// The background, sRGB.
pub const BACKGROUND: [u8; 3] = [18, 18, 24];

/// What one key of the legend looks like.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Swatch {
    /// A line.
    Line,
    /// A dashed line.
    Dashed,
    /// A disc.
    Dot,
    /// A cross.
    Cross,
}

/// One key of the legend: a swatch of a mark's look and what it means.
#[derive(Clone, Debug, PartialEq)]
pub struct Key {
    /// What it looks like.
    pub swatch: Swatch,
    /// Its colour.
    pub rgb: [u8; 3],
    /// What it means.
    pub text: String,
}

/// Which board axis runs across the diagram.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Axis {
    /// Board x (the table's long side).
    #[default]
    X,
    /// Board y.
    Y,
}

impl Axis {
    /// The component of `v` along this axis.
    #[must_use]
    pub fn of(self, v: DVec3) -> f64 {
        match self {
            Self::X => v.x,
            Self::Y => v.y,
        }
    }

    /// Parses `x` or `y`.
    pub fn parse(s: &str) -> Result<Self, String> {
        match s {
            "x" => Ok(Self::X),
            "y" => Ok(Self::Y),
            _ => Err(format!("axis {s:?}: give \"x\" or \"y\"")),
        }
    }

    /// `"x"` or `"y"`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::X => "x",
            Self::Y => "y",
        }
    }
}

/// What the diagram shows beyond the worldlines and the cone.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Options {
    /// The board axis across.
    pub axis: Axis,
    /// The puck (index) whose lines of simultaneity are drawn; `None`:
    /// only the board's.
    pub frame: Option<usize>,
}

/// A frame's line of simultaneity on the diagram.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Simultaneity {
    /// The puck whose frame it is.
    pub puck: usize,
    /// Its event at the current instant: the line passes through it.
    pub event: Event,
    /// The line's slope on the diagram, dt/d(axis), s/m: `v_axis / c²`.
    pub slope: f64,
}

/// A rectangle of pixels (or points), from the top left.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Area {
    /// Left edge.
    pub left: f64,
    /// Top edge.
    pub top: f64,
    /// Width.
    pub width: f64,
    /// Height.
    pub height: f64,
}

impl Area {
    /// `self` less [`MARGINS`]: where the data goes, the labels around it.
    #[must_use]
    pub fn inside_margins(self) -> Self {
        let [l, r, t, b] = MARGINS;
        Self {
            left: self.left + l,
            top: self.top + t,
            width: (self.width - l - r).max(1.0),
            height: (self.height - t - b).max(1.0),
        }
    }
}

/// The diagram as marks, with its ranges and its legend.
pub struct Plot {
    /// Board x (or y) shown, m.
    pub x: (f64, f64),
    /// Board time shown, s.
    pub t: (f64, f64),
    /// The grid's steps: (m across, s up).
    pub grid: (f64, f64),
    /// What to draw, back to front.
    pub marks: Vec<Mark>,
    /// What the marks mean, in the order read.
    pub legend: Vec<Key>,
    /// The eye's observation event.
    pub eye: Event,
    /// Each puck's emission event: where the cone meets its worldline.
    pub emissions: Vec<Event>,
    /// The chosen frame's line of simultaneity, if a frame was chosen.
    pub simultaneity: Option<Simultaneity>,
}

impl Plot {
    /// Where diagram point `(x, t)` falls in `area` (px from the top left:
    /// [`Plot::x`] spans its width, [`Plot::t`] its height, time up).
    #[must_use]
    pub fn to_px(&self, area: Area, (x, t): (f64, f64)) -> (f64, f64) {
        (
            area.left + (x - self.x.0) / (self.x.1 - self.x.0) * area.width,
            area.top + area.height - (t - self.t.0) / (self.t.1 - self.t.0) * area.height,
        )
    }
}

/// A polyline in pixels cut into dashes of [`DASH`] px with gaps of
/// [`GAP`] px, the pattern running on across its vertices: the pieces to
/// stroke.
#[must_use]
pub fn dashes(points: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::new();
    let mut piece: Vec<(f64, f64)> = Vec::new();
    // Distance into the current period of DASH + GAP.
    let mut phase = 0.0;
    for pair in points.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let len = (b.0 - a.0).hypot(b.1 - a.1);
        if !len.is_finite() {
            continue;
        }
        let at = |s: f64| (a.0 + (b.0 - a.0) * s / len, a.1 + (b.1 - a.1) * s / len);
        let mut s = 0.0;
        while s < len {
            let on = phase < DASH;
            let left = if on { DASH - phase } else { DASH + GAP - phase };
            let step = left.min(len - s);
            if on {
                if piece.is_empty() {
                    piece.push(at(s));
                }
                piece.push(at(s + step));
            }
            s += step;
            phase += step;
            if phase >= DASH && on {
                out.push(std::mem::take(&mut piece));
            }
            if phase >= DASH + GAP {
                phase = 0.0;
            }
        }
    }
    if piece.len() > 1 {
        out.push(piece);
    }
    out
}

/// The diagram of `scene` (its `billiard` run to at least `eye.t`) for
/// an eye at observation event `eye`.
#[must_use]
pub fn plot(scene: &Scene, billiard: &Billiard, eye: Event) -> Plot {
    plot_with(scene, billiard, eye, Options::default())
}

/// A line mark.
fn line(role: Role, points: Vec<(f64, f64)>, rgb: [u8; 3], width: f64, alpha: f64) -> Mark {
    Mark::Line {
        role,
        points,
        rgb,
        width,
        alpha,
        dashed: false,
    }
}

/// A dashed line mark.
fn dashed(role: Role, points: Vec<(f64, f64)>, rgb: [u8; 3], width: f64, alpha: f64) -> Mark {
    Mark::Line {
        role,
        points,
        rgb,
        width,
        alpha,
        dashed: true,
    }
}

/// `rgb` at opacity `alpha` over the background, as one colour (a key's
/// swatch for a faint mark).
fn faint(rgb: [u8; 3], alpha: f64) -> [u8; 3] {
    let mut out = BACKGROUND;
    for (o, &c) in out.iter_mut().zip(&rgb) {
        *o = (f64::from(*o) + (f64::from(c) - f64::from(*o)) * alpha).round() as u8;
    }
    out
}

/// The grid's colour.
pub const GRID_RGB: [u8; 3] = [70, 70, 84];
/// The cushions' colour.
pub const CUSHION_RGB: [u8; 3] = [70, 170, 80];
/// The board's now's colour.
pub const BOARD_NOW_RGB: [u8; 3] = [215, 215, 215];

/// [`plot`] along `options.axis`, with `options.frame`'s line of
/// simultaneity. A frame index beyond the pucks draws none.
pub fn plot_with(scene: &Scene, billiard: &Billiard, eye: Event, options: Options) -> Plot {
    let axis = options.axis;
    let t = eye.t;
    let c = scene.c;
    let lifts: Vec<DVec3> = scene
        .pucks
        .iter()
        .map(|p| DVec3::new(0.0, 0.0, p.height / 2.0))
        .collect();
    let emissions: Vec<Event> = (0..billiard.len())
        .map(|i| cone_crossing(billiard.worldline(i), lifts[i], eye, c))
        .collect();
    let earliest = emissions.iter().map(|e| e.t).fold(0.0f64, f64::min);
    let span = (t - earliest).max(0.5);
    let t_range = (earliest - 0.15 * span, t + 0.08 * span);
    let side = match axis {
        Axis::X => scene.table.size.x,
        Axis::Y => scene.table.size.y,
    };
    let eye_x = axis.of(eye.position);
    let x_range = ((-0.1f64).min(eye_x - 0.1), (side + 0.1).max(eye_x + 0.1));
    let a = axis.name();
    let mut marks = Vec::new();
    let mut legend = Vec::new();
    // The grid, labelled; t = 0 and the cushions brighter.
    let across = GridAxis::over(x_range);
    let up = GridAxis::over(t_range);
    grid::marks(&mut marks, (&across, &up), (x_range, t_range));
    legend.push(Key {
        swatch: Swatch::Line,
        rgb: GRID_RGB,
        text: format!(
            "board {a} across, time up: grid {} m, {} s",
            label_text(across.step),
            label_text(up.step)
        ),
    });
    marks.push(line(
        Role::TimeZero,
        vec![(x_range.0, 0.0), (x_range.1, 0.0)],
        [150, 150, 160],
        1.5,
        0.9,
    ));
    for x in [0.0, side] {
        marks.push(line(
            Role::Cushion,
            vec![(x, t_range.0), (x, t_range.1)],
            CUSHION_RGB,
            2.0,
            0.9,
        ));
    }
    legend.push(Key {
        swatch: Swatch::Line,
        rgb: CUSHION_RGB,
        text: format!("cushions: {a} = 0 and {a} = {} m", label_text(side)),
    });
    // The eye's worldline (where it is now, at rest or not).
    marks.push(line(
        Role::EyeWorldline,
        vec![(eye_x, t_range.0), (eye_x, t)],
        [230, 230, 230],
        1.5,
        0.7,
    ));
    const N: usize = 800;
    let times: Vec<f64> = (0..=N)
        .map(|k| t_range.0 + (t - t_range.0) * k as f64 / N as f64)
        .collect();
    let colours: Vec<[u8; 3]> = scene
        .pucks
        .iter()
        .map(|p| {
            let rgb = [p.color.r, p.color.g, p.color.b];
            if u32::from(rgb[0]) + u32::from(rgb[1]) + u32::from(rgb[2]) < 120 {
                [150, 150, 150]
            } else {
                rgb
            }
        })
        .collect();
    for (i, &rgb) in colours.iter().enumerate() {
        let w = billiard.worldline(i);
        // The cone's trace along this puck's path: dashed.
        let trace = times
            .iter()
            .map(|&s| {
                let p = w.position_at(s) + lifts[i];
                (axis.of(p), t - p.distance(eye.position) / c)
            })
            .collect();
        marks.push(dashed(Role::Cone(i), trace, rgb, 1.5, 0.55));
        let path = times
            .iter()
            .map(|&s| (axis.of(w.position_at(s)), s))
            .collect();
        marks.push(line(Role::Worldline(i), path, rgb, 2.5, 1.0));
    }
    let first = colours.first().copied().unwrap_or([200, 200, 200]);
    legend.extend([
        Key {
            swatch: Swatch::Line,
            rgb: first,
            text: format!("each puck's worldline ({a} against t), its colour"),
        },
        Key {
            swatch: Swatch::Dashed,
            rgb: first,
            text: "the eye's past light cone along each path".to_owned(),
        },
        Key {
            swatch: Swatch::Dot,
            rgb: first,
            text: "the events the eye sees now".to_owned(),
        },
    ]);
    let collisions: Vec<_> = billiard.collisions().iter().filter(|k| k.t <= t).collect();
    for k in &collisions {
        marks.push(Mark::Cross {
            at: (axis.of(k.contact), k.t),
        });
    }
    if !collisions.is_empty() {
        legend.push(Key {
            swatch: Swatch::Cross,
            rgb: [255, 255, 255],
            text: "a collision".to_owned(),
        });
    }
    for (i, (e, &rgb)) in emissions.iter().zip(&colours).enumerate() {
        marks.push(Mark::Event {
            role: Role::Seen(i),
            at: (axis.of(e.position), e.t),
            rgb,
        });
    }
    let simultaneity = options.frame.filter(|&f| f < billiard.len()).map(|f| {
        let w = billiard.worldline(f);
        let event = w.event_at(t);
        let slope = axis.of(simultaneity_slope(w.proper_velocity_at(t), c));
        Simultaneity {
            puck: f,
            event,
            slope,
        }
    });
    // The board's "now" and the frame's "now" through its puck's event,
    // clipped to the time range.
    marks.push(dashed(
        Role::BoardNow,
        vec![(x_range.0, t), (x_range.1, t)],
        BOARD_NOW_RGB,
        1.5,
        0.8,
    ));
    legend.push(Key {
        swatch: Swatch::Dashed,
        rgb: BOARD_NOW_RGB,
        text: format!("the board's now, t = {t:.2} s"),
    });
    if let Some(sim) = simultaneity {
        frame_lines(
            &mut marks,
            &mut legend,
            scene,
            billiard,
            sim,
            (x_range, t_range),
            colours[sim.puck],
            axis,
        );
    }
    marks.push(Mark::Event {
        role: Role::Eye,
        at: (eye_x, t),
        rgb: [255, 255, 255],
    });
    legend.push(Key {
        swatch: Swatch::Dot,
        rgb: [255, 255, 255],
        text: "the eye now, on its worldline".to_owned(),
    });
    Plot {
        x: x_range,
        t: t_range,
        grid: (across.step, up.step),
        marks,
        legend,
        eye,
        emissions,
        simultaneity,
    }
}

/// The frame's now through its event `sim` (bright, in the puck's colour
/// lightened) and its earlier nows (faint), clipped to `ranges`, with
/// their keys.
#[allow(clippy::too_many_arguments)]
fn frame_lines(
    marks: &mut Vec<Mark>,
    legend: &mut Vec<Key>,
    scene: &Scene,
    billiard: &Billiard,
    sim: Simultaneity,
    (x_range, t_range): ((f64, f64), (f64, f64)),
    rgb: [u8; 3],
    axis: Axis,
) {
    let c = scene.c;
    let t = sim.event.t;
    let u = billiard.worldline(sim.puck).proper_velocity_at(t);
    let x0 = axis.of(sim.event.position);
    // The board time `simultaneous_board_time` gives at this x (on the
    // line through the event along the axis), shifted by `dt`.
    let at = |x: f64, dt: f64| {
        let mut p = sim.event.position;
        match axis {
            Axis::X => p.x = x,
            Axis::Y => p.y = x,
        }
        simultaneous_board_time(sim.event, u, c, p) + dt
    };
    // The x span over which the line shifted by `dt` stays in the time
    // range.
    let span = |dt: f64| {
        let (mut a, mut b) = x_range;
        if sim.slope.abs() > 1e-300 {
            let xa = x0 + (t_range.0 - t - dt) / sim.slope;
            let xb = x0 + (t_range.1 - t - dt) / sim.slope;
            let (lo, hi) = if xa < xb { (xa, xb) } else { (xb, xa) };
            a = a.max(lo);
            b = b.min(hi);
        } else if !(t_range.0..=t_range.1).contains(&(t + dt)) {
            return None;
        }
        (a < b).then_some((a, b))
    };
    // Earlier "nows" of the same frame, faint: every 0.5 s of the puck's
    // frame time (0.5 / γ s of board time apart at fixed x).
    let gamma = u.gamma();
    for k in 1..=8 {
        let dt = -0.5 * f64::from(k) / gamma;
        if let Some((a, b)) = span(dt) {
            marks.push(line(
                Role::FrameEarlierNow,
                vec![(a, at(a, dt)), (b, at(b, dt))],
                rgb,
                1.0,
                0.4,
            ));
        }
    }
    let light = [
        rgb[0].saturating_add(40),
        rgb[1].saturating_add(40),
        rgb[2].saturating_add(40),
    ];
    if let Some((a, b)) = span(0.0) {
        marks.push(line(
            Role::FrameNow,
            vec![(a, at(a, 0.0)), (b, at(b, 0.0))],
            light,
            2.5,
            0.95,
        ));
    }
    marks.push(Mark::Event {
        role: Role::FrameEvent,
        at: (x0, t),
        rgb,
    });
    let name = &scene.pucks[sim.puck].name;
    let a = axis.name();
    legend.push(Key {
        swatch: Swatch::Line,
        rgb: light,
        text: format!("{name}'s now: dt/d{a} = v/c² = {:.3} s/m", sim.slope),
    });
    legend.push(Key {
        swatch: Swatch::Line,
        rgb: faint(rgb, 0.4),
        text: format!("{name}'s earlier nows, 0.5 s of its time apart"),
    });
}
