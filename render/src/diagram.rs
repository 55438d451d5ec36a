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

use glam::DVec3;
use lightcone_engine::physics::Billiard;
use lightcone_engine::scene::Scene;
use lightcone_engine::spacetime::Event;
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
}

/// The diagram of `scene` (its `billiard` run to at least `eye.t`) for
/// an eye at observation event `eye`.
pub fn plot(scene: &Scene, billiard: &Billiard, eye: Event) -> Plot {
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
    let size = scene.table.size;
    let x_range = (
        (-0.1f64).min(eye.position.x - 0.1),
        (size.x + 0.1).max(eye.position.x + 0.1),
    );
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
    let mut g = (x_range.0 / 0.5).ceil() * 0.5;
    while g <= x_range.1 {
        marks.push(line(
            vec![(g, t_range.0), (g, t_range.1)],
            grid,
            1.0,
            0.6,
            false,
        ));
        g += 0.5;
    }
    let mut g = (t_range.0 / 0.5).ceil() * 0.5;
    while g <= t_range.1 {
        marks.push(line(
            vec![(x_range.0, g), (x_range.1, g)],
            grid,
            1.0,
            0.6,
            false,
        ));
        g += 0.5;
    }
    marks.push(line(
        vec![(x_range.0, 0.0), (x_range.1, 0.0)],
        [150, 150, 160],
        1.5,
        0.9,
        false,
    ));
    for x in [0.0, size.x] {
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
        vec![(eye.position.x, t_range.0), (eye.position.x, t)],
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
                (p.x, t - p.distance(eye.position) / c)
            })
            .collect();
        marks.push(line(trace, rgb, 1.5, 0.55, true));
        let path = times.iter().map(|&s| (w.position_at(s).x, s)).collect();
        marks.push(line(path, rgb, 2.5, 1.0, false));
    }
    for k in billiard.collisions().iter().filter(|k| k.t <= t) {
        marks.push(Mark::Cross {
            at: (k.contact.x, k.t),
        });
    }
    for (e, &rgb) in emissions.iter().zip(&colours) {
        marks.push(Mark::Event {
            at: (e.position.x, e.t),
            rgb,
        });
    }
    marks.push(Mark::Event {
        at: (eye.position.x, t),
        rgb: [255, 255, 255],
    });
    Plot {
        x: x_range,
        t: t_range,
        marks,
        eye,
        emissions,
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
    let (eye, _) = super::frame::eye_of(scene, observer, t);
    let plot = plot(scene, billiard, eye.event);
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
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lightcone_engine::optics::emission;

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
                let report = crate::observe::report(&scene, &billiard, 0, t, scene.effects, false);
                for (i, e) in drawn.emissions.iter().enumerate() {
                    let r = &report.pucks[i].centre.emission;
                    let reported = Event::new(r.t, DVec3::from(r.position));
                    let optics = emission::solve(
                        billiard.worldline(i),
                        DVec3::new(0.0, 0.0, scene.pucks[i].height / 2.0),
                        true,
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
