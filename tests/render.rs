//! Image tests: headless rendering on whatever adapter the machine has
//! (Mesa's lavapipe on CI), checked against the pinhole model, against
//! physics, and against golden images.

mod common;

use common::repo;

use glam::{DVec2, DVec3};
use lightcone_engine::physics::Billiard;
use lightcone_engine::scene::{self, Color, Effects, ObserverSpec, PuckSpec, Scene, TableSpec};
use lightcone_engine::spacetime::ProperVelocity;
use lightcone_render::frame::{self, ViewKind};
use lightcone_render::gpu;
use lightcone_render::headless::{self, Image};

/// One red puck, seen from `eye` looking at `look_at`.
fn one_puck(
    u: ProperVelocity,
    position: DVec2,
    eye: DVec3,
    look_at: DVec3,
    effects: Effects,
) -> Scene {
    Scene {
        title: "test".into(),
        description: String::new(),
        c: 1.42,
        table: TableSpec::frictionless(DVec2::new(2.84, 1.42), 1.0),
        restitution: 1.0,
        effects,
        optics: Default::default(),
        before_start: Default::default(),
        pucks: vec![PuckSpec {
            name: "red".into(),
            position,
            u,
            radius: 0.0305,
            height: 0.02,
            mass: 0.21,
            color: Color::rgb(255, 0, 0),
        }],
        observers: vec![ObserverSpec {
            name: "eye".into(),
            position: eye,
            look_at: Some(look_at),
            u: ProperVelocity::ZERO,
        }],
    }
}

fn is_red(p: [u8; 4]) -> bool {
    p[0] > 90 && p[1] < 40 && p[2] < 40
}

/// Centroid (x, y) and count of red pixels.
fn red_centroid(img: &Image) -> (f64, f64, usize) {
    let (mut sx, mut sy, mut n) = (0.0, 0.0, 0usize);
    for y in 0..img.height {
        for x in 0..img.width {
            if is_red(img.pixel(x, y)) {
                sx += f64::from(x);
                sy += f64::from(y);
                n += 1;
            }
        }
    }
    (sx / n.max(1) as f64, sy / n.max(1) as f64, n)
}

#[test]
fn a_puck_at_rest_renders_where_the_pinhole_model_puts_it() {
    let gpu = gpu::headless().expect("a graphics adapter (CI installs mesa-vulkan-drivers)");
    let eye = DVec3::new(1.2, 0.3, 0.25);
    let look = DVec3::new(1.4, 0.7, 0.0);
    let puck = DVec2::new(1.5, 0.6);
    let scene = one_puck(ProperVelocity::ZERO, puck, eye, look, Effects::default());
    let (w, h) = (320u32, 240u32);
    let img = headless::render_scene(&gpu, &scene, 3.0, 0, ViewKind::Seen, w, h).unwrap();
    // Pinhole projection of the puck's top centre, written out here
    // independently of the renderer's matrices.
    let p = DVec3::new(puck.x, puck.y, 0.02);
    let f = (look - eye).normalize();
    let right = f.cross(DVec3::Z).normalize();
    let up = right.cross(f);
    let d = p - eye;
    let scale = (f64::from(h) / 2.0) / (std::f64::consts::FRAC_PI_3 / 2.0).tan();
    let px = f64::from(w) / 2.0 + scale * d.dot(right) / d.dot(f);
    let py = f64::from(h) / 2.0 - scale * d.dot(up) / d.dot(f);
    let pixel = img.pixel(px.round() as u32, py.round() as u32);
    assert!(is_red(pixel), "pixel at ({px:.1}, {py:.1}) is {pixel:?}");
    // The red blob (top face and the side facing us) is centred on that
    // column within two pixels, and lies between the projections of the
    // top centre and the bottom centre (plus a pixel).
    let bottom = p - DVec3::new(0.0, 0.0, 0.02) - eye;
    let py_bottom = f64::from(h) / 2.0 - scale * bottom.dot(up) / bottom.dot(f);
    let (cx, cy, n) = red_centroid(&img);
    assert!(n > 50, "{n} red pixels");
    assert!((cx - px).abs() < 2.0, "centroid x {cx} vs {px}");
    assert!(
        cy > py - 1.0 && cy < py_bottom + 1.0,
        "centroid y {cy} not in [{py}, {py_bottom}]"
    );
}

#[test]
fn the_seen_fast_puck_lags_behind_the_truth() {
    // A puck at 0.9 c moving +x across the view of an observer looking +y:
    // light delay shows it where it was, further back along its motion.
    let gpu = gpu::headless().expect("a graphics adapter");
    let eye = DVec3::new(1.42, -1.0, 0.6);
    let look = DVec3::new(1.42, 0.71, 0.0);
    let u = ProperVelocity::try_from_beta(DVec3::new(0.7, 0.0, 0.0)).unwrap();
    let scene = one_puck(u, DVec2::new(0.6, 0.5), eye, look, Effects::default());
    let t = 1.5;
    let truth = headless::render_scene(&gpu, &scene, t, 0, ViewKind::Truth, 640, 360).unwrap();
    let seen = headless::render_scene(&gpu, &scene, t, 0, ViewKind::Seen, 640, 360).unwrap();
    let (tx, _, tn) = red_centroid(&truth);
    let (sx, _, sn) = red_centroid(&seen);
    assert!(tn > 20 && sn > 20, "{tn} {sn}");
    assert!(sx < tx - 50.0, "seen at x = {sx}, truth at x = {tx}");
    // How far behind, in closed form: the puck's centre moves uniformly,
    // P(t') = P(t) − v (t − t'), and the light reaching the eye E at t left
    // it τ = t − t' earlier with c τ = |E − P(t')|. With D = P(t) − E:
    // (c² − v²) τ² + 2 (D·v) τ − D² = 0, whose positive root, in the form
    // without cancellation, is τ = D² / (D·v + √((D·v)² + (c² − v²) D²)).
    let c = scene.c;
    let v = u.velocity(c);
    let now = DVec3::new(0.6 + v.x * t, 0.5, 0.0);
    let d = now - eye;
    let (dv, cv2) = (d.dot(v), (c - v.length()) * (c + v.length()));
    let tau = d.length_squared() / (dv + (dv * dv + cv2 * d.length_squared()).sqrt());
    assert!(t - tau > 0.0, "emitted after the start: {tau}");
    let mut b = Billiard::from_scene(&scene);
    b.advance_to(t);
    assert!((b.worldline(0).position_at(t) - now).length() < 1e-12);
    let (e, _) = frame::eye_of(&scene, 0, t);
    let w = b.worldline(0);
    let contracted = lightcone_engine::worldline::ContractedShape::of(w);
    let delayed = lightcone_engine::optics::emission::solve(w, DVec3::ZERO, &contracted, e.event);
    // The engine's emission event is the closed form's, to 1e-12 of the
    // light delay: seen v τ = 1.2 m behind where it is.
    assert!(
        (delayed.event.t - (t - tau)).abs() < 1e-12 * tau,
        "emitted at {} s, closed form {} s",
        delayed.event.t,
        t - tau
    );
    let behind = now.x - delayed.event.position.x;
    assert!(
        (behind - v.x * tau).abs() < 1e-12,
        "{behind} vs {}",
        v.x * tau
    );
}

/// Mean absolute difference per channel (0–255) and the share of pixels
/// that differ by more than 48 in any channel.
fn difference(a: &Image, b: &Image) -> (f64, f64) {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let (mut sum, mut big) = (0u64, 0usize);
    for (pa, pb) in a.rgba.chunks(4).zip(b.rgba.chunks(4)) {
        let d: Vec<u32> = (0..3).map(|i| u32::from(pa[i].abs_diff(pb[i]))).collect();
        sum += u64::from(d.iter().sum::<u32>());
        if d.iter().any(|&x| x > 48) {
            big += 1;
        }
    }
    let n = (a.width * a.height) as f64;
    (sum as f64 / (3.0 * n), big as f64 / n)
}

#[test]
fn golden_images() {
    // Tolerance: mean difference ≤ 2 / 255 per channel and ≤ 0.5 % of
    // pixels off by more than 48 (software rasterisers differ at edges).
    // Set LIGHTCONE_BLESS=1 to rewrite the goldens after an intended change.
    let gpu = gpu::headless().expect("a graphics adapter");
    let bless = std::env::var_os("LIGHTCONE_BLESS").is_some();
    for (name, file, t, kind) in [
        ("paper_seen", "paper_carom.toml", 1.0, ViewKind::Seen),
        ("parallel_seen", "parallel_tracks.toml", 1.2, ViewKind::Seen),
        (
            "parallel_truth",
            "parallel_tracks.toml",
            1.2,
            ViewKind::Truth,
        ),
    ] {
        let scene = scene::load(&repo().join("assets/scenes").join(file)).unwrap();
        let img = headless::render_scene(&gpu, &scene, t, 0, kind, 320, 180).unwrap();
        let golden = repo().join("tests/golden").join(format!("{name}.png"));
        if bless {
            img.save_png(&golden).unwrap();
            continue;
        }
        let expected = Image::load_png(&golden).unwrap();
        let (mean, big) = difference(&img, &expected);
        assert!(
            mean <= 2.0 && big <= 0.005,
            "{name}: mean {mean:.2}, {:.2} % pixels off",
            big * 100.0
        );
    }
}

/// The paper's scene as its first observer sees it at board time `t`
/// (s), framed for a `w × h` image: the triangles and the camera the
/// renderer draws them with.
fn paper_seen(t: f64, w: u32, h: u32) -> (Vec<frame::FrameVertex>, frame::Camera) {
    let scene = scene::load(&repo().join("assets/scenes/paper_carom.toml")).unwrap();
    let (mut sim, view) =
        frame::scene_view(&scene, 0, t, ViewKind::Seen, f64::from(w) / f64::from(h));
    let meshes = frame::ViewMeshes::new(&mut sim);
    let mut vertices = Vec::new();
    frame::build_view(sim.apparent(view).unwrap(), &meshes, &mut vertices);
    (vertices, sim.camera(view).unwrap().into())
}

#[test]
fn a_window_on_a_software_rasteriser_draws_the_same_picture() {
    // A window on a CPU adapter draws one sample a pixel, and in a browser
    // into a plain (not sRGB) canvas whose colours the scene's shader
    // encodes itself (`Gpu::window_samples`, the web window's format).
    // Against the pictures written to files (sRGB target, 4 samples): the
    // plain target holds the sRGB target's bytes to rounding (every
    // channel within 1 of 255, the shader's `pow` against the target's
    // own encoding); one sample differs from four only along edges (under
    // 3 % of the pixels off by more than 48, where MSAA's coverage blends
    // an edge pixel; mean under 3 levels).
    let gpu = gpu::headless().expect("a graphics adapter");
    let (w, h) = (320u32, 180u32);
    let (vertices, camera) = paper_seen(2.2, w, h);
    let draw = |format, samples| {
        headless::Offscreen::with(&gpu, w, h, format, samples)
            .draw(&gpu, &vertices, &camera)
            .unwrap()
    };
    let srgb = wgpu::TextureFormat::Rgba8UnormSrgb;
    let files = draw(srgb, lightcone_render::pipeline::SAMPLES);
    let window = draw(srgb, 1);
    let canvas = draw(wgpu::TextureFormat::Rgba8Unorm, 1);
    let worst = window
        .rgba
        .iter()
        .zip(&canvas.rgba)
        .map(|(a, b)| a.abs_diff(*b))
        .max()
        .unwrap();
    assert!(worst <= 1, "the plain target is off by {worst} levels");
    let (mean, big) = difference(&window, &files);
    assert!(
        mean < 3.0 && big < 0.03,
        "one sample against four: mean {mean:.2}, {:.2} % pixels off",
        big * 100.0
    );
    assert!(mean > 0.0, "the two sample counts drew the same bytes");
}

#[test]
fn a_view_with_nothing_to_draw_still_clears() {
    // A view whose triangles are all culled (an eye behind a CAVE wall, a
    // camera looking away) clears to the background: with one sample a
    // pixel the renderer draws into the target itself, so a skipped clear
    // showed what it held (a window's last frame). Each target here is
    // first drawn with the table, then with nothing, one sample and four.
    let gpu = gpu::headless().expect("a graphics adapter");
    let (w, h) = (160u32, 90u32);
    let (vertices, camera) = paper_seen(1.0, w, h);
    let srgb = wgpu::TextureFormat::Rgba8UnormSrgb;
    for samples in [1, lightcone_render::pipeline::SAMPLES] {
        let mut target = headless::Offscreen::with(&gpu, w, h, srgb, samples);
        let table = target.draw(&gpu, &vertices, &camera).unwrap();
        let background = table.pixel(0, 0);
        assert!(
            table.rgba.chunks(4).any(|p| p[..3] != background[..3]),
            "{samples} samples: the table drew nothing"
        );
        let empty = target.draw(&gpu, &[], &camera).unwrap();
        assert!(
            empty.rgba.chunks(4).all(|p| p[..3] == background[..3]),
            "{samples} samples: an empty view kept the last picture"
        );
    }
}

#[test]
fn a_default_render_shows_the_whole_table() {
    // No `look_at` in the scene: the camera frames the whole table
    // (cushions included) with a margin, at any image shape.
    let gpu = gpu::headless().expect("a graphics adapter");
    let scene = scene::load(&repo().join("assets/scenes/paper_carom.toml")).unwrap();
    for (w, h) in [(320u32, 180u32), (200, 240)] {
        for kind in [ViewKind::Seen, ViewKind::Truth] {
            let img = headless::render_scene(&gpu, &scene, 0.5, 0, kind, w, h).unwrap();
            // The bounding box of the cloth's and cushions' greens.
            let (mut x0, mut x1, mut y0, mut y1) = (u32::MAX, 0, u32::MAX, 0);
            for y in 0..h {
                for x in 0..w {
                    let p = img.pixel(x, y).map(i32::from);
                    if p[1] > 45 && p[1] > p[0] + 12 && p[1] > p[2] + 12 {
                        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
                    }
                }
            }
            let what = format!("{w}×{h} {kind:?}: table [{x0}, {x1}] × [{y0}, {y1}]");
            assert!(x1 > x0 && y1 > y0, "{what}");
            // Inside with a margin on every side...
            assert!(x0 >= 3 && y0 >= 3 && x1 + 3 < w && y1 + 3 < h, "{what}");
            // ...and filling the image on one axis (8 % margin each side).
            let (fw, fh) = (
                f64::from(x1 - x0) / f64::from(w),
                f64::from(y1 - y0) / f64::from(h),
            );
            assert!(fw > 0.8 || fh > 0.8, "{what}: fills {fw:.2} × {fh:.2}");
        }
    }
}

#[test]
fn the_meshes_cover_every_shipped_scene() {
    for entry in std::fs::read_dir(repo().join("assets/scenes")).unwrap() {
        let scene = scene::load(&entry.unwrap().path()).unwrap();
        let (mut sim, view) = frame::scene_view(&scene, 0, 2.0, ViewKind::Seen, 16.0 / 9.0);
        let meshes = frame::ViewMeshes::new(&mut sim);
        let mut out = Vec::new();
        frame::build_view(sim.apparent(view).unwrap(), &meshes, &mut out);
        assert!(!out.is_empty());
        assert_eq!(out.len() % 3, 0);
    }
}

#[test]
fn render_prints_no_driver_warning_without_a_runtime_dir() {
    // Mesa's device-select layer reaches libwayland, which prints
    // "error: XDG_RUNTIME_DIR is invalid or not set in the environment."
    // when the variable is unset or relative; `lightcone` gives it a
    // private one first.
    let out_dir = std::env::temp_dir().join(format!("lightcone-xdg-{}", std::process::id()));
    std::fs::create_dir_all(&out_dir).unwrap();
    let png = out_dir.join("shot.png");
    for value in [None, Some("relative/dir")] {
        let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_lightcone"));
        cmd.args(["render", "--at", "0.5", "--size", "64x36", "-o"])
            .arg(&png)
            .arg(repo().join("assets/scenes/paper_carom.toml"))
            .env_remove("WAYLAND_DISPLAY");
        match value {
            None => cmd.env_remove("XDG_RUNTIME_DIR"),
            Some(v) => cmd.env("XDG_RUNTIME_DIR", v),
        };
        let out = cmd.output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{value:?}: {stderr}");
        assert!(
            !stderr.contains("XDG_RUNTIME_DIR"),
            "{value:?}: a stray driver warning: {stderr}"
        );
        assert!(Image::load_png(&png).is_ok());
    }
    let _ = std::fs::remove_dir_all(&out_dir);
}
