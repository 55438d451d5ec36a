//! Every shipped lesson (`scripts/lessons/*.py`) run headless through the
//! game's embedded interpreter (`lightcone lesson`): it must finish, and
//! every physics claim it checks must hold. Broken lessons must fail with
//! their traceback, in the terminal and on screen, without a crash.

mod common;

use std::path::Path;
use std::process::Output;

use common::{cloth_pixels, lightcone, play_under_xvfb, repo};
use lightcone::render::headless::Image;

fn lessons() -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(repo().join("scripts/lessons"))
        .expect("scripts/lessons exists")
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "py"))
        .map(|p| {
            format!(
                "scripts/lessons/{}",
                p.file_name().unwrap().to_string_lossy()
            )
        })
        .collect();
    v.sort();
    v
}

#[test]
fn the_paper_observations_are_all_there() {
    let names = lessons();
    for needed in [
        "simultaneity",
        "approach_recede",
        "collision_angle",
        "contraction",
        "cushion",
        "clocks",
        "gas",
    ] {
        assert!(
            names.iter().any(|n| n.contains(needed)),
            "no lesson for {needed} in {names:?}"
        );
    }
}

#[test]
fn every_lesson_finishes_and_its_claims_hold() {
    for lesson in lessons() {
        let out = lightcone(&["lesson", &lesson, "--json"]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{lesson} failed:\n{stderr}");
        let outcome: serde_json::Value = serde_json::from_slice(&out.stdout)
            .unwrap_or_else(|e| panic!("{lesson}: not JSON ({e})"));
        assert!(outcome["error"].is_null(), "{lesson}: {}", outcome["error"]);
        assert!(
            outcome["finished"].is_string(),
            "{lesson} did not call finish() by t = {}",
            outcome["t"]
        );
        let claims = outcome["claims"].as_array().expect("claims");
        assert!(!claims.is_empty(), "{lesson} checks no claim");
        for c in claims {
            assert_eq!(c["ok"], true, "{lesson}: {} ({})", c["claim"], c["detail"]);
        }
        assert!(
            !outcome["answers"].as_array().expect("answers").is_empty(),
            "{lesson} asks the student nothing"
        );
    }
}

#[test]
fn a_lesson_that_raises_in_setup_fails_with_its_traceback() {
    let out = lightcone(&["lesson", "tests/lessons/broken_setup.py"]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("Traceback"), "{stderr}");
    assert!(
        stderr.contains("broken_setup.py\", line 9, in setup"),
        "{stderr}"
    );
    assert!(
        stderr.contains("RuntimeError: this lesson is broken"),
        "{stderr}"
    );
}

#[test]
fn a_hook_that_raises_stops_the_lesson_but_keeps_the_state() {
    let out = lightcone(&["lesson", "tests/lessons/broken_midway.py", "--json"]);
    assert!(!out.status.success());
    let outcome: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let error = outcome["error"].as_str().expect("an error");
    assert!(error.contains("in on_collision"), "{error}");
    assert!(error.contains("KeyError: 'no such key'"), "{error}");
    // The claim made before the failure is kept, and time stopped at the
    // collision instead of running on.
    assert_eq!(outcome["claims"][0]["ok"], true);
    let t = outcome["t"].as_f64().unwrap();
    assert!(t > 0.02 && t < 0.15, "stopped at {t}");
}

#[test]
fn lesson_rejects_bad_arguments_and_missing_files() {
    let out = lightcone(&["lesson", "no/such/lesson.py"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("no such lesson file"));
    let out = lightcone(&["lesson", "scripts/lessons/cushion.py", "--fps", "0"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--fps"));
}

/// Runs `play LESSON --screenshot` under Xvfb; returns the screenshot.
fn play_screenshot(lesson: &str, name: &str, frames: u32) -> (Output, Image) {
    let dir = std::env::temp_dir().join(format!("lightcone-lesson-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (out, img) = play_under_xvfb(&["play", lesson], &dir.join(format!("{name}.png")), frames);
    let img = img.unwrap_or_else(|| panic!("{lesson}: {}", String::from_utf8_lossy(&out.stderr)));
    (out, img)
}

/// Pixels of the traceback's pink in the right-hand third of the window.
fn traceback_pixels(img: &Image) -> usize {
    let w = img.width as usize;
    img.rgba
        .chunks(4)
        .enumerate()
        .filter(|(i, p)| {
            i % w > w * 2 / 3 && p[0] > 200 && p[1] > 80 && p[1] < 190 && p[2] > 80 && p[2] < 190
        })
        .count()
}

#[test]
fn every_lesson_plays_under_xvfb() {
    for lesson in lessons() {
        let name = Path::new(&lesson)
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        let (out, img) = play_screenshot(&lesson, &name, 10);
        assert!(!String::from_utf8_lossy(&out.stderr).contains("Traceback"));
        assert_eq!((img.width, img.height), (1280, 720));
        assert!(traceback_pixels(&img) < 50, "{lesson} shows an error");
    }
}

#[test]
fn a_broken_lesson_shows_its_traceback_in_the_game_and_does_not_crash() {
    for (lesson, name) in [
        ("tests/lessons/broken_setup.py", "broken_setup"),
        ("tests/lessons/broken_midway.py", "broken_midway"),
    ] {
        // Enough frames (≥ 0.5 s) for the midway lesson to reach its collision.
        let (out, img) = play_screenshot(lesson, name, 60);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains("Traceback"), "{stderr}");
        let pink = traceback_pixels(&img);
        assert!(
            pink > 200,
            "{lesson}: only {pink} traceback pixels on screen"
        );
        // The table is still drawn.
        let cloth = cloth_pixels(&img);
        assert!(
            cloth > 1280 * 720 / 20,
            "{lesson}: only {cloth} cloth pixels"
        );
    }
}

#[test]
fn an_endless_hook_is_stopped_with_a_timeout() {
    let start = std::time::Instant::now();
    let out = lightcone(&[
        "lesson",
        "tests/lessons/endless.py",
        "--hook-limit",
        "1",
        "--json",
    ]);
    assert!(!out.status.success());
    let outcome: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let error = outcome["error"].as_str().expect("an error");
    assert!(error.contains("in on_frame"), "{error}");
    assert!(error.contains("TimeoutError"), "{error}");
    assert!(error.contains("endless.py\", line 13"), "{error}");
    assert!(start.elapsed().as_secs_f64() < 30.0);
    let out = lightcone(&[
        "lesson",
        "tests/lessons/endless_setup.py",
        "--hook-limit",
        "1",
    ]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("TimeoutError") && stderr.contains("in setup"),
        "{stderr}"
    );
}
