use super::*;
use glam::DVec2;
use lightcone_engine::optics::emission;
use lightcone_engine::scene::{Color, PuckSpec};
use lightcone_engine::spacetime::ProperVelocity;

fn shipped(name: &str) -> Scene {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes");
    lightcone_engine::scene::load(&dir.join(name)).unwrap()
}

/// A carom table (2.84 × 1.42 m, c = 1 m/s, no friction) with one puck,
/// "rocket", leaving (0.3, 0.7) m at β = 0.6 along x: at t = 0.5 s it is
/// at x = 0.3 + 0.6 · 1 · 0.5 = 0.6 m, far from a cushion.
fn rocket() -> (Scene, Billiard) {
    const BETA: f64 = 0.6;
    let mut scene = Scene::empty(DVec2::new(2.84, 1.42), Some(1.0)).unwrap();
    scene
        .add_puck(PuckSpec {
            name: "rocket".to_owned(),
            position: DVec2::new(0.3, 0.7),
            u: ProperVelocity::try_from_beta(DVec3::new(BETA, 0.0, 0.0)).unwrap(),
            radius: 0.03,
            height: 0.02,
            mass: 0.2,
            color: Color {
                r: 0,
                g: 200,
                b: 220,
            },
        })
        .unwrap();
    let mut billiard = Billiard::from_scene(&scene);
    billiard.advance_to(0.5);
    (scene, billiard)
}

/// The straight lines of `role`, as ((x₀, t₀), (x₁, t₁)).
fn lines(plot: &Plot, role: Role) -> Vec<((f64, f64), (f64, f64))> {
    plot.marks
        .iter()
        .filter(|m| m.role() == role)
        .filter_map(|m| match m {
            Mark::Line { points, .. } => Some((points[0], *points.last().unwrap())),
            _ => None,
        })
        .collect()
}

/// The plot of the rocket's table at t = 0.5 s has, in closed form: grid
/// lines at every multiple of its step in range, the full height or width,
/// labelled in m and s; the two cushions at x = 0 and x = 2.84 m (the
/// table's length); the board's now at t = 0.5 s; and the rocket's now
/// through (0.6 m, 0.5 s) with slope dt/dx = β / c = 0.6 s/m, its earlier
/// nows parallel, 0.5 / γ = 0.4 s of board time apart at fixed x.
#[test]
fn the_plot_has_its_grid_cushions_and_nows_where_the_closed_form_puts_them() {
    let (scene, billiard) = rocket();
    let eye = crate::frame::eye_of(&scene, 0, 0.5).0.event;
    let options = Options {
        axis: Axis::X,
        frame: Some(0),
    };
    let plot = plot_with(&scene, &billiard, eye, options);
    let (x, t) = (plot.x, plot.t);
    assert!(
        x.0 < 0.0 && x.1 > 2.84 && t.0 < 0.0 && t.1 > 0.5,
        "{x:?} {t:?}"
    );
    assert_eq!(
        plot.grid,
        (0.5, 0.5),
        "a 3 m by ~1 s diagram: grid every 0.5"
    );
    let grid = lines(&plot, Role::Grid);
    let vertical: Vec<f64> = grid
        .iter()
        .filter(|(a, b)| a.0 == b.0 && (a.1, b.1) == (t.0, t.1))
        .map(|(a, _)| a.0)
        .collect();
    assert_eq!(vertical, vec![0.0, 0.5, 1.0, 1.5, 2.0, 2.5]);
    let horizontal = grid
        .iter()
        .filter(|(a, b)| a.1 == b.1 && (a.0, b.0) == (x.0, x.1))
        .count();
    assert_eq!(vertical.len() + horizontal, grid.len());
    assert!(horizontal >= 2, "t = 0 and 0.5 s at least: {horizontal}");
    let labels: Vec<(&str, (f64, f64))> = plot
        .marks
        .iter()
        .filter_map(|m| match m {
            Mark::Label { text, at, .. } => Some((text.as_str(), *at)),
            _ => None,
        })
        .collect();
    assert!(labels.contains(&("1.5 m", (1.5, t.0))), "{labels:?}");
    assert!(labels.contains(&("0.5 s", (x.0, 0.5))), "{labels:?}");
    let cushions = lines(&plot, Role::Cushion);
    assert_eq!(
        cushions,
        vec![((0.0, t.0), (0.0, t.1)), ((2.84, t.0), (2.84, t.1))]
    );
    assert_eq!(lines(&plot, Role::BoardNow), vec![((x.0, 0.5), (x.1, 0.5))]);
    // The rocket's now, in closed form.
    let (beta, c) = (0.6, 1.0);
    let gamma = 1.0 / (1.0f64 - beta * beta).sqrt();
    let x_now = 0.3 + beta * c * 0.5;
    let now = lines(&plot, Role::FrameNow);
    assert_eq!(now.len(), 1);
    let (a, b) = now[0];
    let slope = (b.1 - a.1) / (b.0 - a.0);
    assert!((slope - beta / c).abs() < 1e-12, "slope {slope} s/m");
    assert!(
        (a.1 + slope * (x_now - a.0) - 0.5).abs() < 1e-12,
        "through its event"
    );
    let sim = plot.simultaneity.unwrap();
    assert!((sim.slope - beta / c).abs() < 1e-12);
    assert!((sim.event.position.x - x_now).abs() < 1e-12);
    let earlier = lines(&plot, Role::FrameEarlierNow);
    assert!(!earlier.is_empty());
    for (k, (a, b)) in earlier.iter().enumerate() {
        let s = (b.1 - a.1) / (b.0 - a.0);
        assert!((s - beta / c).abs() < 1e-12, "{s}");
        let at_x_now = a.1 + s * (x_now - a.0);
        let dt = 0.5 * (k + 1) as f64 / gamma;
        assert!((at_x_now - (0.5 - dt)).abs() < 1e-12, "earlier now {k}");
    }
    // Its keys in the legend, with the slope.
    let texts: Vec<&str> = plot.legend.iter().map(|k| k.text.as_str()).collect();
    assert!(
        texts
            .iter()
            .any(|t| t.contains("rocket's now") && t.contains("0.600 s/m")),
        "{texts:?}"
    );
    assert!(
        texts
            .iter()
            .any(|t| t.contains("cushions") && t.contains("2.84 m")),
        "{texts:?}"
    );
    assert!(texts.iter().any(|t| t.contains("board's now")), "{texts:?}");
}

/// How close pixel `(x, y)` of `img` is to `rgb` (largest channel gap).
fn gap(img: &crate::headless::Image, (x, y): (f64, f64), rgb: [u8; 3]) -> i32 {
    let i = 4 * (y.round() as usize * img.width as usize + x.round() as usize);
    (0..3)
        .map(|k| (i32::from(img.rgba[i + k]) - i32::from(rgb[k])).abs())
        .max()
        .unwrap()
}

/// The PNG painter puts the marks where [`Plot::to_px`] says, in their
/// colours: the cushions' green down the column of x = 0 and 2.84 m, the
/// grid's grey down x = 1 m, the board's now's dashes along t = 0.5 s, the
/// rocket's now along its tilted line, text under the x axis and in the
/// legend.
#[test]
fn the_png_has_its_grid_cushion_and_now_lines_in_their_colours() {
    let (scene, billiard) = rocket();
    let options = Options {
        axis: Axis::X,
        frame: Some(0),
    };
    let drawn = draw_with(&scene, &billiard, 0, 0.5, (1000, 700), options);
    let (img, plot, area) = (&drawn.image, &drawn.plot, drawn.area);
    assert!(area.top + area.height < 600.0, "room for the legend below");
    let px = |x, t| plot.to_px(area, (x, t));
    // Down a column: 20 samples of t from −2 to 0.4 s, except within
    // 0.03 s of the rocket's nows (0.4 s apart) and of the grid's level
    // lines (0.5 s apart), which cross it.
    // A hit: summed over 2 px either side, each channel's excess over the
    // background is that of a line `width` px wide in `rgb`, within 25 %
    // (an antialiased line spreads over two or three pixels).
    let column = |x: f64, rgb: [u8; 3], width: f64| {
        let clear = |t: f64| {
            let now = 0.5 + 0.6 * (x - 0.6);
            let k = ((now - t) / 0.4).round();
            (now - 0.4 * k - t).abs() > 0.03 && (t - (t / 0.5).round() * 0.5).abs() > 0.03
        };
        let ts: Vec<f64> = (0..240)
            .map(|k| -2.0 + 0.01 * f64::from(k))
            .filter(|&t| clear(t))
            .collect();
        let hits = ts
            .iter()
            .filter(|&&t| {
                let p = px(x, t);
                let (xi, yi) = (p.0.round() as i64, p.1.round() as usize);
                (0..3).all(|ch| {
                    let sum: f64 = (-2..=2)
                        .map(|d| {
                            let i = 4 * (yi * img.width as usize + (xi + d) as usize) + ch;
                            f64::from(img.rgba[i]) - f64::from(BACKGROUND[ch])
                        })
                        .sum();
                    let want = width * (f64::from(rgb[ch]) - f64::from(BACKGROUND[ch]));
                    (sum - want).abs() <= 0.25 * want.abs() + 3.0
                })
            })
            .count();
        (hits, ts.len())
    };
    // The cushions are drawn 2 px wide at opacity 0.9 (over the grid at
    // x = 0), the grid 1 px wide.
    let cushion = faint(CUSHION_RGB, 0.9);
    let (hits, n) = column(0.0, cushion, 2.0);
    assert!(
        n > 100 && hits as f64 >= 0.9 * n as f64,
        "the cushion at x = 0: {hits} of {n}"
    );
    let (hits, n) = column(2.84, cushion, 2.0);
    assert!(hits == n, "the cushion at x = 2.84 m: {hits} of {n}");
    let (hits, n) = column(2.0, GRID_RGB, 1.0);
    assert!(hits == n, "the grid at x = 2 m: {hits} of {n}");
    assert_eq!(column(1.75, GRID_RGB, 1.0).0, 0, "no grid between");
    // Along the board's now, from x = 1.6 to 2.4 m: dashes and gaps.
    let along: Vec<bool> = (0..200)
        .map(|k| {
            let p = px(1.6 + 0.004 * f64::from(k), 0.5);
            (-1..=1).any(|d| gap(img, (p.0, p.1 + f64::from(d)), BOARD_NOW_RGB) <= 80)
        })
        .collect();
    let on = along.iter().filter(|&&b| b).count();
    assert!((60..170).contains(&on), "dashed: {on} of 200 on the line");
    // The rocket's now: t = 0.5 + 0.6 (x − 0.6), its colour lightened
    // (from x = 0.05 to 0.45 m; it leaves the time range at 0.97 m).
    let light = [40, 240, 255];
    let tilted = (0..20)
        .filter(|k| {
            let x = 0.05 + 0.02 * f64::from(*k);
            let p = px(x, 0.5 + 0.6 * (x - 0.6));
            (-1..=1).any(|d| gap(img, (p.0, p.1 + f64::from(d)), light) <= 30)
        })
        .count();
    assert_eq!(tilted, 20, "the rocket's now");
    // Text: the label "1 m" under the axis, the legend under the plot.
    let bright = |x0: f64, y0: f64, w: usize, h: usize| {
        (0..w * h)
            .filter(|i| gap(img, (x0 + (i % w) as f64, y0 + (i / w) as f64), BACKGROUND) > 80)
            .count()
    };
    let (lx, ly) = px(1.0, plot.t.0);
    assert!(bright(lx - 15.0, ly + 3.0, 30, 16) > 20, "the label 1 m");
    assert!(bright(lx - 15.0, ly - 40.0, 30, 16) < 5, "nothing above it");
    assert!(
        bright(area.left + 30.0, area.top + area.height + 30.0, 300, 60) > 200,
        "the legend"
    );
}

/// The grid is at a round step with at most 16 lines and 8 labels in
/// range, and stays bounded far from the origin, where adding a step no
/// longer changes a number (a diagram at board time −10¹⁸ s once looped
/// there until memory ran out).
#[test]
fn the_grid_is_round_and_bounded_far_out() {
    let near = GridAxis::over((-0.2, 1.2));
    assert_eq!((near.step, near.lines.clone()), (0.5, vec![0.0, 0.5, 1.0]));
    let long = GridAxis::over((-1.0, 27.0));
    assert_eq!(long.step, 2.0);
    assert_eq!(long.lines.len(), 14);
    assert_eq!(GridAxis::over((-1.0, 31.0)).step, 5.0);
    assert_eq!(long.label_every, 2);
    assert_eq!(long.labelled().collect::<Vec<_>>()[..3], [0.0, 4.0, 8.0]);
    assert_eq!(GridAxis::over((0.0, 1e6)).step, 1e5);
    assert!(GridAxis::over((-1e18 - 3.0, -1e18 + 1.0)).lines.len() <= grid::MAX_LINES);
    assert!(GridAxis::over((0.0, f64::INFINITY)).lines.is_empty());
    assert_eq!(
        [0.5, 2.0, -0.0, 1.25, 2.84].map(label_text),
        ["0.5", "2", "0", "1.25", "2.84"]
    );
    let scene = shipped("paper_carom.toml");
    let billiard = Billiard::from_scene(&scene);
    let drawn = draw(&scene, &billiard, 0, -1e18, 64, 64);
    assert_eq!(drawn.image.width, 64);
}

/// Dashes of 7 px with 5 px gaps, the pattern running on over vertices.
#[test]
fn dashes_are_seven_on_five_off_across_vertices() {
    let pieces = dashes(&[(0.0, 0.0), (10.0, 0.0), (30.0, 0.0)]);
    let spans: Vec<(f64, f64)> = pieces
        .iter()
        .map(|p| (p[0].0, p.last().unwrap().0))
        .collect();
    assert_eq!(spans, vec![(0.0, 7.0), (12.0, 19.0), (24.0, 30.0)]);
    assert_eq!(pieces[1].len(), 2);
    assert!(dashes(&[(0.0, 0.0)]).is_empty());
}

/// The frame's line passes through the puck's event now, with slope
/// β_x / c, in closed form from the scene: the white puck, struck at
/// proper velocity u₀ (|β₀| = 0.95), brakes on the cloth (μg) with
/// u(t) = u₀ − μg t / c along its line and has slid
/// (c²/μg)(γ₀ − γ(t)) by t = 0.8 s, before its hit; points on the line
/// are simultaneous with that event in the puck's frame (Lorentz
/// transform t' = γ(t − v·x/c²)).
#[test]
fn the_frame_line_is_the_pucks_now() {
    let scene = shipped("paper_carom.toml");
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
    assert!(lines(&plain.plot, Role::FrameNow).is_empty());
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
    for name in ["paper_carom.toml", "parallel_tracks.toml", "ten_pucks.toml"] {
        let scene = shipped(name);
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
                let light = scene.c * (drawn.eye.t - e.t) - e.position.distance(drawn.eye.position);
                assert!(light.abs() < 1e-9, "{light}");
            }
        }
    }
}
