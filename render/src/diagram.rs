//! The space-time diagram (`lightcone diagram`): board time up, the board's
//! x axis across. Each puck's worldline (its centre's x against t), the
//! eye's worldline and its observation event, where the eye's past light
//! cone meets each worldline (the emission event whose light the eye
//! receives then), collisions as marked events. Drawn on the CPU into an
//! [`Image`]: no GPU needed.
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

use super::headless::Image;

/// Where the eye's past light cone, from observation event `eye`, meets
/// the worldline of the point at `offset` from the body's centre (not
/// contracted: `offset` is vertical), with light speed `c`: the root of
/// `g(t) = c (T − t) − |X(t) − x_eye|`, which falls strictly along any
/// worldline slower than light, found by bisection. Computed here on the
/// diagram's own terms, independently of the optics' closed form.
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

/// A canvas mapping board x (m) and time (s) to pixels.
struct Canvas {
    img: Image,
    x: (f64, f64),
    t: (f64, f64),
    margin: f64,
}

impl Canvas {
    fn px(&self, x: f64, t: f64) -> (f64, f64) {
        let (w, h) = (f64::from(self.img.width), f64::from(self.img.height));
        let m = self.margin;
        (
            m + (x - self.x.0) / (self.x.1 - self.x.0) * (w - 2.0 * m),
            h - m - (t - self.t.0) / (self.t.1 - self.t.0) * (h - 2.0 * m),
        )
    }

    fn dot(&mut self, x: f64, y: f64, rgb: [u8; 3], alpha: f64) {
        if !(x.is_finite() && y.is_finite()) {
            return;
        }
        let (xi, yi) = (x.round(), y.round());
        if xi < 0.0
            || yi < 0.0
            || xi >= f64::from(self.img.width)
            || yi >= f64::from(self.img.height)
        {
            return;
        }
        let i = 4 * (yi as usize * self.img.width as usize + xi as usize);
        for (px, &new) in self.img.rgba[i..i + 3].iter_mut().zip(&rgb) {
            let old = f64::from(*px);
            *px = (old + (f64::from(new) - old) * alpha).round() as u8;
        }
    }

    /// A line of `width` px between two pixel positions.
    fn line(&mut self, a: (f64, f64), b: (f64, f64), width: f64, rgb: [u8; 3], alpha: f64) {
        let len = (b.0 - a.0).hypot(b.1 - a.1);
        let n = (len * 2.0).ceil().max(1.0) as usize;
        let r = (width / 2.0).max(0.5);
        for s in 0..=n {
            let f = s as f64 / n as f64;
            let (x, y) = (a.0 + (b.0 - a.0) * f, a.1 + (b.1 - a.1) * f);
            let ri = r.ceil() as i32;
            for dy in -ri..=ri {
                for dx in -ri..=ri {
                    if f64::from(dx * dx + dy * dy) <= r * r {
                        self.dot(x + f64::from(dx), y + f64::from(dy), rgb, alpha);
                    }
                }
            }
        }
    }

    fn disc(&mut self, c: (f64, f64), r: f64, rgb: [u8; 3]) {
        let ri = r.ceil() as i32;
        for dy in -ri..=ri {
            for dx in -ri..=ri {
                if f64::from(dx * dx + dy * dy) <= r * r {
                    self.dot(c.0 + f64::from(dx), c.1 + f64::from(dy), rgb, 1.0);
                }
            }
        }
    }
}

/// One thing drawn, in diagram coordinates (board x in m, board time in s).
#[derive(Clone, Debug, PartialEq)]
pub enum Mark {
    /// A polyline.
    Line {
        /// Its points (x, t).
        points: Vec<(f64, f64)>,
        /// sRGB colour.
        rgb: [u8; 3],
        /// Width, px.
        width: f64,
        /// Opacity, 0–1.
        alpha: f64,
        /// Dashed.
        dashed: bool,
    },
    /// An event: a disc ringed in white.
    Event {
        /// Where (x, t).
        at: (f64, f64),
        /// sRGB colour.
        rgb: [u8; 3],
    },
    /// A collision: a white cross.
    Cross {
        /// Where (x, t).
        at: (f64, f64),
    },
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

/// The diagram as marks, with its ranges.
pub struct Plot {
    /// Board x shown, m.
    pub x: (f64, f64),
    /// Board time shown, s.
    pub t: (f64, f64),
    /// What to draw, back to front.
    pub marks: Vec<Mark>,
    /// The eye's observation event.
    pub eye: Event,
    /// Each puck's emission event: where the cone meets its worldline.
    pub emissions: Vec<Event>,
    /// The chosen frame's line of simultaneity, if a frame was chosen.
    pub simultaneity: Option<Simultaneity>,
}

/// The diagram of `scene` (its `billiard` run to at least `eye.t`) for
/// an eye at observation event `eye`.
/// Most grid lines drawn across one axis of a diagram.
const MAX_GRID_LINES: f64 = 1000.0;

/// The grid's lines across `range` (m or s): every multiple of 0.5 in it,
/// none if there would be more than [`MAX_GRID_LINES`] (far from the
/// origin, where steps of 0.5 no longer change the number, the count is
/// still bounded: a diagram at board time −10¹⁸ s must not loop).
fn grid_lines(range: (f64, f64)) -> impl Iterator<Item = f64> {
    let first = (range.0 / 0.5).ceil();
    let last = (range.1 / 0.5).floor();
    let count = last - first + 1.0;
    let count = if count.is_finite() && count > 0.0 && count <= MAX_GRID_LINES {
        count as usize
    } else {
        0
    };
    (0..count).map(move |k| (first + k as f64) * 0.5)
}

pub fn plot(scene: &Scene, billiard: &Billiard, eye: Event) -> Plot {
    plot_with(scene, billiard, eye, Options::default())
}

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
    let mut marks = Vec::new();
    let line =
        |points: Vec<(f64, f64)>, rgb: [u8; 3], width: f64, alpha: f64, dashed: bool| Mark::Line {
            points,
            rgb,
            width,
            alpha,
            dashed,
        };
    // Grid: every 0.5 m and 0.5 s, t = 0 and the cushions brighter.
    let grid = [60, 60, 70];
    for g in grid_lines(x_range) {
        marks.push(line(
            vec![(g, t_range.0), (g, t_range.1)],
            grid,
            1.0,
            0.6,
            false,
        ));
    }
    for g in grid_lines(t_range) {
        marks.push(line(
            vec![(x_range.0, g), (x_range.1, g)],
            grid,
            1.0,
            0.6,
            false,
        ));
    }
    marks.push(line(
        vec![(x_range.0, 0.0), (x_range.1, 0.0)],
        [150, 150, 160],
        1.5,
        0.9,
        false,
    ));
    for x in [0.0, side] {
        marks.push(line(
            vec![(x, t_range.0), (x, t_range.1)],
            [60, 140, 70],
            2.0,
            0.9,
            false,
        ));
    }
    // The eye's worldline (where it is now, at rest or not).
    marks.push(line(
        vec![(eye_x, t_range.0), (eye_x, t)],
        [230, 230, 230],
        1.5,
        0.7,
        false,
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
        marks.push(line(trace, rgb, 1.5, 0.55, true));
        let path = times
            .iter()
            .map(|&s| (axis.of(w.position_at(s)), s))
            .collect();
        marks.push(line(path, rgb, 2.5, 1.0, false));
    }
    for k in billiard.collisions().iter().filter(|k| k.t <= t) {
        marks.push(Mark::Cross {
            at: (axis.of(k.contact), k.t),
        });
    }
    for (e, &rgb) in emissions.iter().zip(&colours) {
        marks.push(Mark::Event {
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
    // The board's "now" (faint) and the frame's "now" through its puck's
    // event, clipped to the time range.
    marks.push(line(
        vec![(x_range.0, t), (x_range.1, t)],
        [200, 200, 200],
        1.0,
        0.45,
        true,
    ));
    if let Some(sim) = simultaneity {
        let x0 = axis.of(sim.event.position);
        let at = |x: f64| {
            // The board time `simultaneous_board_time` gives at this x (on
            // the line through the event along the axis).
            let mut p = sim.event.position;
            match axis {
                Axis::X => p.x = x,
                Axis::Y => p.y = x,
            }
            let u = billiard.worldline(sim.puck).proper_velocity_at(t);
            simultaneous_board_time(sim.event, u, c, p)
        };
        let (mut a, mut b) = (x_range.0, x_range.1);
        if sim.slope.abs() > 1e-300 {
            // Clip x so the line stays within the time range.
            let xa = x0 + (t_range.0 - sim.event.t) / sim.slope;
            let xb = x0 + (t_range.1 - sim.event.t) / sim.slope;
            let (lo, hi) = if xa < xb { (xa, xb) } else { (xb, xa) };
            a = a.max(lo);
            b = b.min(hi);
        }
        // Earlier "nows" of the same frame, faint: every 0.5 s of the
        // puck's frame time (0.5 / γ s of board time apart at fixed x).
        let gamma = billiard.worldline(sim.puck).proper_velocity_at(t).gamma();
        for k in 1..=8 {
            let dt = -0.5 * f64::from(k) / gamma;
            if sim.slope.abs() <= 1e-300 && sim.event.t + dt < t_range.0 {
                break;
            }
            let (mut a, mut b) = (x_range.0, x_range.1);
            if sim.slope.abs() > 1e-300 {
                let xa = x0 + (t_range.0 - sim.event.t - dt) / sim.slope;
                let xb = x0 + (t_range.1 - sim.event.t - dt) / sim.slope;
                let (lo, hi) = if xa < xb { (xa, xb) } else { (xb, xa) };
                a = a.max(lo);
                b = b.min(hi);
            }
            if a < b {
                let rgb = colours[sim.puck];
                marks.push(line(
                    vec![(a, at(a) + dt), (b, at(b) + dt)],
                    rgb,
                    1.0,
                    0.35,
                    false,
                ));
            }
        }
        let rgb = colours[sim.puck];
        let light = [
            rgb[0].saturating_add(40),
            rgb[1].saturating_add(40),
            rgb[2].saturating_add(40),
        ];
        marks.push(line(vec![(a, at(a)), (b, at(b))], light, 2.5, 0.9, false));
        marks.push(Mark::Event {
            at: (x0, sim.event.t),
            rgb,
        });
    }
    marks.push(Mark::Event {
        at: (eye_x, t),
        rgb: [255, 255, 255],
    });
    Plot {
        x: x_range,
        t: t_range,
        marks,
        eye,
        emissions,
        simultaneity,
    }
}

/// What the diagram shows, for tests and captions.
pub struct Drawn {
    /// The image.
    pub image: Image,
    /// The eye's observation event.
    pub eye: Event,
    /// Each puck's emission event: where the cone meets its worldline.
    pub emissions: Vec<Event>,
    /// The chosen frame's line of simultaneity.
    pub simultaneity: Option<Simultaneity>,
}

/// Draws the diagram of `scene` (its `billiard` run to at least `t`) for
/// observer `observer` at board time `t`, `width × height` px.
pub fn draw(
    scene: &Scene,
    billiard: &Billiard,
    observer: usize,
    t: f64,
    width: u32,
    height: u32,
) -> Drawn {
    draw_with(
        scene,
        billiard,
        observer,
        t,
        (width, height),
        Options::default(),
    )
}

/// [`draw`] with [`Options`] (axis, frame).
pub fn draw_with(
    scene: &Scene,
    billiard: &Billiard,
    observer: usize,
    t: f64,
    (width, height): (u32, u32),
    options: Options,
) -> Drawn {
    let (eye, _) = super::frame::eye_of(scene, observer, t);
    let plot = plot_with(scene, billiard, eye.event, options);
    let mut cv = Canvas {
        img: Image {
            width,
            height,
            rgba: [18u8, 18, 24, 255].repeat(width as usize * height as usize),
        },
        x: plot.x,
        t: plot.t,
        margin: 24.0,
    };
    for mark in &plot.marks {
        match mark {
            Mark::Line {
                points,
                rgb,
                width,
                alpha,
                dashed,
            } => {
                for (k, pair) in points.windows(2).enumerate() {
                    if !dashed || (k / 6) % 2 == 0 {
                        let (a, b) = (cv.px(pair[0].0, pair[0].1), cv.px(pair[1].0, pair[1].1));
                        cv.line(a, b, *width, *rgb, *alpha);
                    }
                }
            }
            Mark::Cross { at } => {
                let p = cv.px(at.0, at.1);
                let white = [255, 255, 255];
                cv.line(
                    (p.0 - 5.0, p.1 - 5.0),
                    (p.0 + 5.0, p.1 + 5.0),
                    2.0,
                    white,
                    1.0,
                );
                cv.line(
                    (p.0 - 5.0, p.1 + 5.0),
                    (p.0 + 5.0, p.1 - 5.0),
                    2.0,
                    white,
                    1.0,
                );
            }
            Mark::Event { at, rgb } => {
                let p = cv.px(at.0, at.1);
                cv.disc(p, 7.0, [255, 255, 255]);
                cv.disc(p, 5.0, *rgb);
            }
        }
    }
    Drawn {
        image: cv.img,
        eye: plot.eye,
        emissions: plot.emissions,
        simultaneity: plot.simultaneity,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lightcone_engine::optics::emission;

    /// The frame's line passes through the puck's event now, with slope
    /// β_x / c, in closed form from the scene: the white puck, struck at
    /// proper velocity u₀ (|β₀| = 0.95), brakes on the cloth (μg) with
    /// u(t) = u₀ − μg t / c along its line and has slid
    /// (c²/μg)(γ₀ − γ(t)) by t = 0.8 s, before its hit; points on the line
    /// are simultaneous with that event in the puck's frame (Lorentz
    /// transform t' = γ(t − v·x/c²)).
    /// The grid is every 0.5 m or s in range, and stays bounded far from
    /// the origin, where adding 0.5 no longer changes a number (a diagram
    /// at board time −10¹⁸ s once looped there until memory ran out).
    #[test]
    fn grid_lines_are_every_half_and_bounded_far_out() {
        let near: Vec<f64> = grid_lines((-0.2, 1.2)).collect();
        assert_eq!(near, vec![0.0, 0.5, 1.0]);
        assert!(grid_lines((-1e18 - 3.0, -1e18 + 1.0)).count() <= 1000);
        assert_eq!(grid_lines((0.0, 1e6)).count(), 0, "too many: none");
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes");
        let scene = lightcone_engine::scene::load(&dir.join("paper_carom.toml")).unwrap();
        let billiard = Billiard::from_scene(&scene);
        let drawn = draw(&scene, &billiard, 0, -1e18, 64, 64);
        assert_eq!(drawn.image.width, 64);
    }

    #[test]
    fn the_frame_line_is_the_pucks_now() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes");
        let scene = lightcone_engine::scene::load(&dir.join("paper_carom.toml")).unwrap();
        let white = scene.pucks.iter().position(|p| p.name == "white").unwrap();
        let t = 0.8;
        let mut billiard = Billiard::from_scene(&scene);
        billiard.advance_to(t);
        assert!(billiard.collisions().iter().all(|k| k.t > t));
        let options = Options {
            axis: Axis::X,
            frame: Some(white),
        };
        let drawn = draw_with(&scene, &billiard, 0, t, (320, 200), options);
        let sim = drawn.simultaneity.expect("a frame line");
        let c = scene.c;
        let a = scene.table.deceleration();
        assert!(a > 0.0, "the paper's scene is on a cloth");
        let u0 = scene.pucks[white].u.0.truncate();
        let n = u0.normalize();
        let u = u0.length() - a * t / c;
        let gamma = (1.0 + u * u).sqrt();
        let (bx, by) = (u * n.x / gamma, u * n.y / gamma);
        let slid = c * c / a * ((1.0 + u0.length_squared()).sqrt() - gamma);
        assert!((sim.slope - bx / c).abs() < 1e-12, "{}", sim.slope);
        let start = scene.pucks[white].position;
        assert!((sim.event.t - t).abs() < 1e-15);
        assert!((sim.event.position.x - (start.x + slid * n.x)).abs() < 1e-12);
        let t_frame = |t: f64, x: f64, y: f64| gamma * (t - (bx * x + by * y) / c);
        let y = sim.event.position.y;
        let now = t_frame(sim.event.t, sim.event.position.x, y);
        for x in [0.0, 1.0, 2.84] {
            let tb = sim.event.t + sim.slope * (x - sim.event.position.x);
            assert!((t_frame(tb, x, y) - now).abs() < 1e-12, "x = {x}");
        }
        // No frame, no line; a y diagram has the y slope.
        let plain = draw(&scene, &billiard, 0, t, 320, 200);
        assert!(plain.simultaneity.is_none());
        let y_options = Options {
            axis: Axis::Y,
            frame: Some(white),
        };
        let drawn = draw_with(&scene, &billiard, 0, t, (320, 200), y_options);
        let slope = drawn.simultaneity.unwrap().slope;
        assert!((slope - by / c).abs() < 1e-12, "{slope}");
    }

    #[test]
    fn the_cone_meets_each_worldline_at_the_emission_event_observe_reports() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes");
        for name in ["paper_carom.toml", "parallel_tracks.toml", "ten_pucks.toml"] {
            let scene = lightcone_engine::scene::load(&dir.join(name)).unwrap();
            for t in [0.5, 1.7, 3.0] {
                let mut billiard = Billiard::from_scene(&scene);
                billiard.advance_to(t);
                let drawn = draw(&scene, &billiard, 0, t, 320, 200);
                assert_eq!((drawn.image.width, drawn.image.height), (320, 200));
                // `observe` reports the centre at mid-height, found by the
                // optics' closed form on the worldline's segments.
                let report =
                    crate::observe::report(&scene, &billiard, 0, t, scene.effects, false).unwrap();
                for (i, e) in drawn.emissions.iter().enumerate() {
                    let r = &report.pucks[i].centre.emission;
                    let reported = Event::new(r.t, DVec3::from(r.position));
                    let worldline = billiard.worldline(i);
                    let optics = emission::solve(
                        worldline,
                        DVec3::new(0.0, 0.0, scene.pucks[i].height / 2.0),
                        &lightcone_engine::worldline::ContractedShape::of(worldline),
                        drawn.eye,
                    );
                    assert!(
                        (e.t - reported.t).abs() < 1e-9
                            && e.position.distance(reported.position) < 1e-9
                            && (optics.event.t - e.t).abs() < 1e-9,
                        "{name} at {t}: puck {i}: diagram {e:?}, observe {reported:?}"
                    );
                    // On the cone: light from it reaches the eye now.
                    let light =
                        scene.c * (drawn.eye.t - e.t) - e.position.distance(drawn.eye.position);
                    assert!(light.abs() < 1e-9, "{light}");
                }
            }
        }
    }
}
