//! What the student sees in the window (Xvfb, 1280×720, the two panels of
//! a lesson open): every shipped scene and lesson shows the whole table,
//! and every puck is marked at least 30 px across, measured on the
//! screenshot. The game's layout file beside the screenshot says where the
//! views are and where each puck is; the pixels are checked here.

mod common;

use std::path::{Path, PathBuf};

use common::{play_under_xvfb, repo};
use lightcone_render::headless::Image;

/// Pixels of the cloth or the cushions (dark greens).
fn table_pixel(p: [u8; 4]) -> bool {
    let (r, g, b) = (i32::from(p[0]), i32::from(p[1]), i32::from(p[2]));
    g > 45 && g > r + 12 && g > b + 12
}

/// Runs `play ARGS` under Xvfb after `frames` frames; returns the image
/// and its layout.
fn shot(args: &[&str], name: &str, frames: u32) -> (Image, serde_json::Value) {
    let dir = std::env::temp_dir().join(format!("lightcone-view-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join(format!("{name}.png"));
    let (out, img) = play_under_xvfb(args, &png, frames);
    let stderr = String::from_utf8_lossy(&out.stderr);
    let img = img.unwrap_or_else(|| panic!("{name}: {stderr}"));
    assert!(
        !stderr.contains("XDG_RUNTIME_DIR"),
        "{name}: a stray driver warning: {stderr}"
    );
    let layout: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(png.with_extension("json")).unwrap())
            .unwrap();
    (img, layout)
}

/// `Err(message)` unless `cond`.
macro_rules! ensure {
    ($cond:expr, $($msg:tt)+) => {
        let holds: bool = $cond;
        if !holds {
            return Err(format!($($msg)+));
        }
    };
}

/// The whole table inside every view, with a margin, and large enough to
/// fill it on one axis; every puck marked ≥ 30 px across in its colour.
fn check(name: &str, img: &Image, layout: &serde_json::Value, pucks: usize) -> Result<(), String> {
    ensure!((img.width, img.height) == (1280, 720), "{name}: size");
    let views = layout["views"].as_array().unwrap();
    for v in views {
        let r: Vec<f64> = v["rect"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let (x0, y0) = (r[0].ceil() as u32, r[1].ceil() as u32);
        let (x1, y1) = (
            ((r[0] + r[2]).floor() as u32).min(img.width) - 1,
            ((r[1] + r[3]).floor() as u32).min(img.height) - 1,
        );
        ensure!(x1 > x0 + 200, "{name}: a view only {} px wide", x1 - x0);
        // The bounding box of the table's pixels.
        let (mut bx0, mut bx1, mut by0, mut by1) = (u32::MAX, 0, u32::MAX, 0);
        for y in y0..=y1 {
            for x in x0..=x1 {
                if table_pixel(img.pixel(x, y)) {
                    bx0 = bx0.min(x);
                    bx1 = bx1.max(x);
                    by0 = by0.min(y);
                    by1 = by1.max(y);
                }
            }
        }
        ensure!(bx1 > bx0, "{name}: no table in view {r:?}");
        let m = 4;
        ensure!(
            bx0 >= x0 + m && bx1 + m <= x1 && by0 >= y0 + m && by1 + m <= y1,
            "{name}: the table [{bx0}, {bx1}] × [{by0}, {by1}] is cut by the view \
             [{x0}, {x1}] × [{y0}, {y1}]"
        );
        let (fw, fh) = (
            f64::from(bx1 - bx0) / f64::from(x1 - x0),
            f64::from(by1 - by0) / f64::from(y1 - y0),
        );
        ensure!(
            fw > 0.7 || fh > 0.7,
            "{name}: the table fills only {fw:.2} × {fh:.2} of its view"
        );
    }
    // Every puck in every view, marked at least 30 px across.
    let marks = layout["pucks"].as_array().unwrap();
    ensure!(
        marks.len() == pucks * views.len(),
        "{name}: pucks missing from the views: {layout}"
    );
    for m in marks {
        let c: Vec<i32> = m["ring_colour"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_i64().unwrap() as i32)
            .collect();
        let (cx, cy) = (
            m["centre"][0].as_f64().unwrap(),
            m["centre"][1].as_f64().unwrap(),
        );
        let reach = m["ring_px"].as_f64().unwrap() / 2.0 + 4.0;
        let (mut lo, mut hi) = (f64::MAX, f64::MIN);
        let (ya, yb) = ((cy - reach).max(0.0) as u32, ((cy + reach) as u32).min(719));
        let (xa, xb) = (
            (cx - reach).max(0.0) as u32,
            ((cx + reach) as u32).min(1279),
        );
        for y in ya..=yb {
            for x in xa..=xb {
                let p = img.pixel(x, y);
                if (0..3).all(|k| (i32::from(p[k]) - c[k]).abs() <= 20) {
                    lo = lo.min(f64::from(x));
                    hi = hi.max(f64::from(x));
                }
            }
        }
        let across = hi - lo + 1.0;
        ensure!(
            across >= 30.0,
            "{name}: puck {} is {across} px across at ({cx:.0}, {cy:.0})",
            m["name"]
        );
    }
    Ok(())
}

/// `[x, y, w, h]` of a JSON array.
fn rect_of(v: &serde_json::Value) -> [f64; 4] {
    let r: Vec<f64> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    [r[0], r[1], r[2], r[3]]
}

/// Whether two `[x, y, w, h]` boxes share a positive area.
fn intersect(a: [f64; 4], b: [f64; 4]) -> bool {
    let w = (a[0] + a[2]).min(b[0] + b[2]) - a[0].max(b[0]);
    let h = (a[1] + a[3]).min(b[1] + b[3]) - a[1].max(b[1]);
    w > 0.0 && h > 0.0
}

/// No two of the names and clocks written (the sidecar's `labels`)
/// intersect, none is over the magnifier, and the most important puck of
/// each view (its first label) has its name written.
fn labels_apart(name: &str, layout: &serde_json::Value) -> Result<(), String> {
    let labels = layout["labels"].as_array().unwrap();
    let boxes: Vec<[f64; 4]> = labels.iter().map(|l| rect_of(&l["rect"])).collect();
    for (i, a) in boxes.iter().enumerate() {
        for (j, b) in boxes.iter().enumerate().skip(i + 1) {
            ensure!(
                !intersect(*a, *b),
                "{name}: labels {} and {} overlap: {a:?} {b:?}",
                labels[i],
                labels[j]
            );
        }
        if !layout["magnifier"].is_null() {
            let m = rect_of(&layout["magnifier"]["rect"]);
            ensure!(
                !intersect(*a, m),
                "{name}: label {} is under the magnifier",
                labels[i]
            );
        }
    }
    let pucks = layout["pucks"].as_array().unwrap().len();
    ensure!(
        pucks == 0 || !labels.is_empty(),
        "{name}: {pucks} pucks and no label"
    );
    Ok(())
}

fn scenes() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(repo().join("assets/scenes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    v.sort();
    v
}

#[test]
fn every_scene_and_lesson_shows_the_whole_table_and_every_puck() {
    // A scene, with a lesson's panel open: a two-line lesson that starts it.
    let dir = std::env::temp_dir().join(format!("lightcone-view-lessons-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut failures = Vec::new();
    for scene in scenes() {
        let name = scene.file_stem().unwrap().to_string_lossy().into_owned();
        let lesson = dir.join(format!("{name}.py"));
        std::fs::write(
            &lesson,
            format!(
                "def setup(world):\n    world.start(world.load({:?}))\n    world.pause()\n    \
                 world.say('Framing test: the whole table, every puck.')\n",
                scene.canonicalize().unwrap().display().to_string()
            ),
        )
        .unwrap();
        let pucks = lightcone_engine::scene::load(&scene).unwrap().pucks.len();
        let lesson = lesson.display().to_string();
        let (img, layout) = shot(&["play", &lesson], &name, 4);
        failures.extend(check(&name, &img, &layout, pucks).err());
        failures.extend(labels_apart(&name, &layout).err());
    }
    // The shipped lessons, as they open.
    let mut lessons: Vec<PathBuf> = std::fs::read_dir(repo().join("scripts/lessons"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    lessons.sort();
    for path in lessons {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let rel = Path::new("scripts/lessons").join(path.file_name().unwrap());
        let (img, layout) = shot(&["play", &rel.display().to_string()], &name, 4);
        let pucks = layout["scene_pucks"].as_u64().unwrap() as usize;
        assert!(pucks > 0, "{name}: no puck in the scene");
        failures.extend(check(&name, &img, &layout, pucks).err());
        failures.extend(labels_apart(&name, &layout).err());
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_split_view_and_the_top_view_frame_the_table_too() {
    let (img, layout) = shot(
        &[
            "play",
            "assets/scenes/paper_carom.toml",
            "--at",
            "1.5",
            "--view",
            "split",
        ],
        "split",
        3,
    );
    check("split", &img, &layout, 3).unwrap();
    let (img, layout) = shot(
        &[
            "play",
            "assets/scenes/ten_pucks.toml",
            "--at",
            "0.5",
            "--top",
        ],
        "top",
        3,
    );
    check("top", &img, &layout, 10).unwrap();
}

/// The magnifier of the contraction scene (the window alone) and of the
/// contraction lesson (with its two panels), measured on the screenshot:
/// the moving puck's body at least 60 px across, and its length along the
/// motion over its width within 5 % of 1/γ = 0.436 (β = 0.9); the dashed
/// rest outline is grey, so only the body has the puck's colour.
#[test]
fn the_magnified_moving_puck_is_contracted_by_one_over_gamma_on_screen() {
    for (name, args) in [
        (
            "contraction_scene",
            &["play", "assets/scenes/contraction.toml", "--at", "1.0"][..],
        ),
        (
            "contraction_lesson",
            &["play", "scripts/lessons/contraction.py"][..],
        ),
    ] {
        let (img, layout) = shot(args, name, 4);
        let m = &layout["magnifier"];
        assert!(!m.is_null(), "{name}: no magnifier: {layout}");
        assert_eq!(m["puck"], "moving", "{name}");
        let gamma = m["gamma"].as_f64().unwrap();
        // β = 0.9: γ = 1/√(1 − 0.81).
        assert!(
            (gamma - 1.0 / 0.19_f64.sqrt()).abs() < 1e-9,
            "{name}: γ {gamma}"
        );
        let c: Vec<i32> = m["colour"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_i64().unwrap() as i32)
            .collect();
        let body = rect_of(&m["body"]);
        let (mut x0, mut x1, mut y0, mut y1) = (u32::MAX, 0, u32::MAX, 0);
        for y in body[1] as u32..(body[1] + body[3]) as u32 {
            for x in body[0] as u32..(body[0] + body[2]) as u32 {
                let p = img.pixel(x, y);
                if (0..3).all(|k| (i32::from(p[k]) - c[k]).abs() <= 24) {
                    x0 = x0.min(x);
                    x1 = x1.max(x);
                    y0 = y0.min(y);
                    y1 = y1.max(y);
                }
            }
        }
        assert!(x1 > x0 && y1 > y0, "{name}: no body drawn in {body:?}");
        let (length, width) = (f64::from(x1 - x0 + 1), f64::from(y1 - y0 + 1));
        assert!(
            length.max(width) >= 60.0,
            "{name}: the body is {length} × {width} px"
        );
        let aspect = length / width;
        assert!(
            (aspect * gamma - 1.0).abs() < 0.05,
            "{name}: on screen length / width = {aspect:.4}, 1/γ = {:.4}",
            1.0 / gamma
        );
    }
}

/// The live diagram in the window (`--diagram-frame b60` on the parallel
/// tracks at t = 1 s, c = 1.42 m/s, frictionless) draws what its legend
/// says, where the sidecar's data area and ranges put it: the cushions'
/// green down x = 0 and 2.84 m, the grid down x = 0.5 m, the board's now
/// dashed along t = 1 s, and b60's now tilted, t = 1 + (β/c)(x − x₀)
/// through x₀ = 0.3 + 0.6 c · 1 s (closed form: a puck at β = 0.6 since
/// t = 0), in its colour lightened, and not along the board's now; text
/// at the time axis and in the legend under the plot.
#[test]
fn the_live_diagram_has_its_grid_cushion_and_now_lines() {
    let scene = "assets/scenes/parallel_tracks.toml";
    // Eight frames: the diagram's window fades in over egui's animation
    // time (1/12 s of real time), which three frames of a window drawing
    // one sample a pixel on llvmpipe (about 25 ms each) did not cover.
    let (img, layout) = shot(
        &["play", scene, "--at", "1", "--diagram-frame", "b60"],
        "diagram",
        8,
    );
    let d = &layout["diagram"];
    let num = |v: &serde_json::Value| -> Vec<f64> {
        v.as_array()
            .unwrap_or_else(|| panic!("no diagram in the sidecar: {layout}"))
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (rect, xr, tr) = (num(&d["rect"]), num(&d["x"]), num(&d["t"]));
    assert!(rect[2] > 400.0 && rect[3] > 250.0, "{rect:?}");
    assert!(
        rect[0] + rect[2] <= 1280.0 && rect[1] + rect[3] + 60.0 <= 720.0,
        "on screen with its legend: {rect:?}"
    );
    let px = |x: f64, t: f64| {
        (
            rect[0] + (x - xr[0]) / (xr[1] - xr[0]) * rect[2],
            rect[1] + rect[3] - (t - tr[0]) / (tr[1] - tr[0]) * rect[3],
        )
    };
    let pixel = |x: f64, y: f64| {
        let i = 4 * (y.round() as usize * img.width as usize + x.round() as usize);
        let p = &img.rgba[i..i + 3];
        [i32::from(p[0]), i32::from(p[1]), i32::from(p[2])]
    };
    // Whether a pixel within 2 px of (x, y), across (`dx`) or up (`dy`),
    // passes `is`.
    let near = |(x, y): (f64, f64), (dx, dy): (f64, f64), is: &dyn Fn([i32; 3]) -> bool| {
        (-2..=2).any(|k| is(pixel(x + dx * f64::from(k), y + dy * f64::from(k))))
    };
    let green = |p: [i32; 3]| p[1] - p[0] >= 50 && p[1] - p[2] >= 40;
    let grid = |p: [i32; 3]| p[1] >= 40 && (p[0] - p[1]).abs() <= 12 && p[2] >= p[1] && p[1] < 120;
    let grey = |p: [i32; 3]| {
        p.iter().all(|&c| c >= 140) && p.iter().max().unwrap() - p.iter().min().unwrap() <= 30
    };
    let c = 1.42;
    let scene_file = lightcone_engine::scene::load(&repo().join(scene)).unwrap();
    assert_eq!(scene_file.c, c);
    let rgb = scene_file.pucks[2].color;
    let light = [rgb.r, rgb.g, rgb.b].map(|v| i32::from(v.saturating_add(40)));
    let frame = move |p: [i32; 3]| (0..3).all(|k| (p[k] - light[k]).abs() <= 40);
    // The share of the points (x m, t s) near which `is` holds.
    let share = |points: Vec<(f64, f64)>, dir, is: &dyn Fn([i32; 3]) -> bool| {
        let n = points.len() as f64;
        points
            .into_iter()
            .filter(|&(x, t)| near(px(x, t), dir, is))
            .count() as f64
            / n
    };
    let (t_lo, t_hi) = (tr[0] + 0.05 * (tr[1] - tr[0]), 0.95);
    let down = |x: f64| -> Vec<(f64, f64)> {
        (0..40)
            .map(|k| (x, t_lo + (t_hi - t_lo) * (f64::from(k) + 0.5) / 40.0))
            .collect()
    };
    let along = |t: &dyn Fn(f64) -> f64| -> Vec<(f64, f64)> {
        (0..60)
            .map(|k| 0.1 + 0.9 * (f64::from(k) + 0.5) / 60.0)
            .map(|x| (x, t(x)))
            .collect()
    };
    let across = (1.0, 0.0);
    let up = (0.0, 1.0);
    for (x, what) in [(0.0, "x = 0"), (2.84, "x = 2.84 m")] {
        let s = share(down(x), across, &green);
        assert!(s >= 0.8, "the cushion at {what}: {s}");
    }
    assert!(
        share(down(1.25), across, &green) <= 0.1,
        "no cushion mid-table"
    );
    let s = share(down(0.5), across, &grid);
    assert!(s >= 0.7, "the grid at x = 0.5 m: {s}");
    let s = share(along(&|_| 1.0), up, &grey);
    assert!((0.3..=0.9).contains(&s), "the board's now, dashed: {s}");
    let x0 = 0.3 + 0.6 * c;
    let s = share(along(&|x| 1.0 + 0.6 / c * (x - x0)), up, &frame);
    assert!(s >= 0.75, "b60's now, tilted: {s}");
    let s = share(along(&|_| 1.0), up, &frame);
    assert!(s <= 0.15, "b60's now is not the board's: {s}");
    // Text: the seconds left of the plot, the legend under it.
    let text = |x0: f64, y0: f64, w: usize, h: usize| {
        (0..w * h)
            .filter(|i| {
                pixel(x0 + (i % w) as f64, y0 + (i / w) as f64)
                    .iter()
                    .all(|&c| c >= 120)
            })
            .count()
    };
    assert!(
        text(rect[0] - 48.0, rect[1], 44, rect[3] as usize) > 100,
        "time labels"
    );
    assert!(
        text(rect[0], rect[1] + rect[3] + 30.0, 400, 40) > 150,
        "the legend"
    );
}
