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
