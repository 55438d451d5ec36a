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
    let c = scene.c;
    let lifts: Vec<DVec3> = scene
        .pucks
        .iter()
        .map(|p| DVec3::new(0.0, 0.0, p.height / 2.0))
        .collect();
    let emissions: Vec<Event> = (0..billiard.len())
        .map(|i| cone_crossing(billiard.worldline(i), lifts[i], eye.event, c))
        .collect();
    let earliest = emissions.iter().map(|e| e.t).fold(0.0f64, f64::min);
    let span = (t - earliest).max(0.5);
    let t_range = (earliest - 0.15 * span, t + 0.08 * span);
    let size = scene.table.size;
    let x_range = (
        (-0.1f64).min(eye.event.position.x - 0.1),
        (size.x + 0.1).max(eye.event.position.x + 0.1),
    );
    let mut cv = Canvas {
        img: Image {
            width,
            height,
            rgba: [18u8, 18, 24, 255].repeat(width as usize * height as usize),
        },
        x: x_range,
        t: t_range,
        margin: 24.0,
    };
    // Grid: every 0.5 m and 0.5 s, t = 0 and the cushions brighter.
    let grid = [60, 60, 70];
    let mut g = (x_range.0 / 0.5).ceil() * 0.5;
    while g <= x_range.1 {
        let (a, b) = (cv.px(g, t_range.0), cv.px(g, t_range.1));
        cv.line(a, b, 1.0, grid, 0.6);
        g += 0.5;
    }
    let mut g = (t_range.0 / 0.5).ceil() * 0.5;
    while g <= t_range.1 {
        let (a, b) = (cv.px(x_range.0, g), cv.px(x_range.1, g));
        cv.line(a, b, 1.0, grid, 0.6);
        g += 0.5;
    }
    let (a, b) = (cv.px(x_range.0, 0.0), cv.px(x_range.1, 0.0));
    cv.line(a, b, 1.5, [150, 150, 160], 0.9);
    for x in [0.0, size.x] {
        let (a, b) = (cv.px(x, t_range.0), cv.px(x, t_range.1));
        cv.line(a, b, 2.0, [60, 140, 70], 0.9);
    }
    // The eye: its worldline and the observation event.
    let (a, b) = (
        cv.px(eye.event.position.x, t_range.0),
        cv.px(eye.event.position.x, t),
    );
    cv.line(a, b, 1.5, [230, 230, 230], 0.7);
    const N: usize = 800;
    let times: Vec<f64> = (0..=N)
        .map(|k| t_range.0 + (t - t_range.0) * k as f64 / N as f64)
        .collect();
    for (i, spec) in scene.pucks.iter().enumerate() {
        let rgb = [spec.color.r, spec.color.g, spec.color.b];
        let rgb = if u32::from(rgb[0]) + u32::from(rgb[1]) + u32::from(rgb[2]) < 120 {
            [150, 150, 150]
        } else {
            rgb
        };
        let w = billiard.worldline(i);
        // The cone's trace along this puck's path: dashed.
        let trace: Vec<(f64, f64)> = times
            .iter()
            .map(|&s| {
                let p = w.position_at(s) + lifts[i];
                cv.px(p.x, t - p.distance(eye.event.position) / c)
            })
            .collect();
        for (k, pair) in trace.windows(2).enumerate() {
            if (k / 6) % 2 == 0 {
                cv.line(pair[0], pair[1], 1.5, rgb, 0.55);
            }
        }
        // The worldline.
        let line: Vec<(f64, f64)> = times
            .iter()
            .map(|&s| cv.px(w.position_at(s).x, s))
            .collect();
        for pair in line.windows(2) {
            cv.line(pair[0], pair[1], 2.5, rgb, 1.0);
        }
    }
    // Collisions: white crosses at the contact events.
    for k in billiard.collisions().iter().filter(|k| k.t <= t) {
        let p = cv.px(k.contact.x, k.t);
        cv.line(
            (p.0 - 5.0, p.1 - 5.0),
            (p.0 + 5.0, p.1 + 5.0),
            2.0,
            [255, 255, 255],
            1.0,
        );
        cv.line(
            (p.0 - 5.0, p.1 + 5.0),
            (p.0 + 5.0, p.1 - 5.0),
            2.0,
            [255, 255, 255],
            1.0,
        );
    }
    // Emission events: discs ringed in white, and the eye's event.
    for (i, e) in emissions.iter().enumerate() {
        let spec = &scene.pucks[i];
        let p = cv.px(e.position.x, e.t);
        cv.disc(p, 7.0, [255, 255, 255]);
        cv.disc(p, 5.0, [spec.color.r, spec.color.g, spec.color.b]);
    }
    let p = cv.px(eye.event.position.x, t);
    cv.disc(p, 6.0, [255, 255, 255]);
    Drawn {
        image: cv.img,
        eye: eye.event,
        emissions,
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
                let report =
                    crate::commands::observe::report(&scene, &billiard, 0, t, scene.effects, false);
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
