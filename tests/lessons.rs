//! Every shipped lesson (`scripts/lessons/*.py`) run headless through the
//! game's embedded interpreter (`lightcone lesson`): it must finish, and
//! every physics claim it checks must hold. Broken lessons must fail with
//! their traceback, in the terminal and on screen, without a crash.

mod common;
/// Hostile lessons: claims kept, floods, the sandbox.
#[path = "lessons/safety.rs"]
mod safety;

use std::path::Path;
use std::process::Output;

use std::time::{Duration, Instant};

use common::{cloth_pixels, lightcone, play_under_xvfb, play_under_xvfb_with, repo};
use lightcone::lesson::Isolation;
use lightcone::lesson::remote::FRAME_BUDGET;
use lightcone::lesson::{LessonHost, headless};
use lightcone_render::headless::Image;

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
        "relative_simultaneity",
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
fn a_thread_that_raises_stops_the_lesson_with_its_traceback() {
    let (outcome, code, _, stderr) = lesson_outcome("tests/lessons/broken_thread.py", &[]);
    assert_ne!(code, Some(0), "{stderr}");
    let error = outcome["error"].as_str().expect("an error");
    assert!(
        error.contains("in the lesson's thread 'counter'"),
        "{error}"
    );
    assert!(
        error.contains("broken_thread.py\", line 12, in count_down"),
        "{error}"
    );
    assert!(error.contains("KeyError: 'right'"), "{error}");
}

#[test]
fn lesson_rejects_bad_arguments_and_missing_files() {
    let out = lightcone(&["lesson", "no/such/lesson.py"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("no such lesson file"));
    // A directory named like a lesson is said to be one.
    let dir = std::env::temp_dir().join(format!("lc-dir-lesson-{}.py", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = lightcone(&["lesson", dir.to_str().unwrap()]);
    let _ = std::fs::remove_dir(&dir);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("is a directory, not a lesson file"));
    // A file whose name starts with `-`, given after `--`, runs (its
    // process once took the name for an option).
    let dir = std::env::temp_dir().join(format!("lc-dash-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(
        repo().join("scripts/lessons/cushion.py"),
        dir.join("-dash.py"),
    )
    .unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_lightcone"))
        .args(["lesson", "--until", "0.2", "--", "-dash.py"])
        .current_dir(&dir)
        .output()
        .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(String::from_utf8_lossy(&out.stdout).starts_with("== -dash.py"));
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

/// Pixels of the traceback's pink (255, 110–170, 110–170: green and blue
/// alike) in the right-hand third of the window. The panel's chart line is
/// amber (255, 200, 80), and its anti-aliased edges are not pink: blue
/// stays well below green there.
fn traceback_pixels(img: &Image) -> usize {
    let w = img.width as usize;
    img.rgba
        .chunks(4)
        .enumerate()
        .filter(|(i, p)| {
            i % w > w * 2 / 3
                && p[0] > 200
                && p[1] > 80
                && p[1] < 190
                && p[2] > 80
                && p[2] < 190
                && (i32::from(p[1]) - i32::from(p[2])).abs() < 25
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

/// Runs `lightcone lesson LESSON --json ARGS`: its outcome, exit status
/// and wall-clock seconds.
fn lesson_outcome(lesson: &str, args: &[&str]) -> (serde_json::Value, Option<i32>, f64, String) {
    let start = std::time::Instant::now();
    let mut all = vec!["lesson", lesson, "--json"];
    all.extend_from_slice(args);
    let out = lightcone(&all);
    let seconds = start.elapsed().as_secs_f64();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let outcome = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{lesson}: not JSON ({e}):\n{stderr}"));
    (outcome, out.status.code(), seconds, stderr)
}

#[test]
fn every_misbehaving_lesson_is_stopped_within_its_limit_with_its_reason() {
    // (lesson, exit status, what the error says)
    let cases: &[(&str, i32, &[&str])] = &[
        (
            "swallow_exception",
            3,
            &["TimeoutError", "except Exception"],
        ),
        (
            "swallow_base_exception",
            3,
            &["TimeoutError", "except BaseException"],
        ),
        ("sleeps", 3, &["TimeoutError", "time.sleep(60)"]),
        ("waits_for_input", 3, &["TimeoutError", "input("]),
        ("reads_a_socket", 3, &["TimeoutError", "worker.join()"]),
        (
            "long_builtin",
            3,
            &["more than 1 s", "could not be interrupted"],
        ),
        ("exits", 1, &["SystemExit", "cannot end the game"]),
        ("forks", 1, &["PermissionError", "may not start processes"]),
        (
            "signals_the_game",
            1,
            &["PermissionError", "may not signal the game"],
        ),
        ("crashes", 4, &["SIGSEGV", "in on_frame"]),
        (
            "exits_for_real",
            4,
            &["exited with status 3", "in on_frame"],
        ),
        ("memory_bomb", 1, &["MemoryError", "in on_frame"]),
    ];
    let limit = 1.0;
    // What starting a lesson costs, to subtract from the timings.
    let (_, status, baseline, stderr) =
        lesson_outcome("scripts/lessons/cushion.py", &["--until", "0.1"]);
    assert_eq!(status, Some(0), "{stderr}");
    // Two at a time: each waits out its limit.
    for pair in cases.chunks(2) {
        let runs: Vec<_> = pair
            .iter()
            .map(|(name, _, _)| {
                let path = format!("tests/lessons/{name}.py");
                std::thread::spawn(move || {
                    lesson_outcome(&path, &["--hook-limit", "1", "--memory-limit", "384"])
                })
            })
            .collect();
        for ((name, status, says), run) in pair.iter().zip(runs) {
            let (outcome, code, seconds, stderr) = run.join().unwrap();
            let error = outcome["error"]
                .as_str()
                .unwrap_or_else(|| panic!("{name}: no error\n{stderr}"));
            for s in *says {
                assert!(error.contains(s), "{name}: {s:?} not in\n{error}");
            }
            assert_eq!(code, Some(*status), "{name}: {error}");
            // Within the limit and a margin: a hook that is not stopped
            // runs 60 s or for ever; the margin covers a loaded machine
            // (the memory bomb's allocations once took over 2 s there).
            assert!(
                seconds - baseline < limit + 3.0,
                "{name}: stopped after {seconds:.2} s (starting takes {baseline:.2} s)"
            );
            // The state before the misbehaviour is kept: one frame ran.
            assert!(outcome["t"].as_f64().unwrap() > 0.0, "{name}: {outcome}");
            println!(
                "{name}: stopped in {:.2} s with status {status}",
                seconds - baseline
            );
        }
    }
}

/// A lesson that never finishes and never reaches `--until` (time slowed
/// to 1e-12) is stopped at `--time-limit`, with its claims kept and a
/// message that says why; it ran for ever before.
#[test]
fn a_lesson_that_never_ends_is_stopped_at_its_time_limit() {
    let (outcome, code, seconds, stderr) =
        lesson_outcome("tests/lessons/never_ends.py", &["--time-limit", "3"]);
    assert_eq!(code, Some(3), "{stderr}");
    let error = outcome["error"].as_str().unwrap_or_default();
    assert!(
        error.contains("without finishing or reaching --until") && error.contains("--time-limit"),
        "{outcome}"
    );
    assert_eq!(outcome["claims"][0]["claim"], "it started", "{outcome}");
    assert!(outcome["frames"].as_u64().unwrap_or(0) > 0, "{outcome}");
    assert!((3.0..20.0).contains(&seconds), "{seconds} s");
    assert!(stderr.contains("never_ends.py stopped"), "{stderr}");
}

#[test]
fn lesson_takes_several_files() {
    let out = lightcone(&[
        "lesson",
        "scripts/lessons/cushion.py",
        "tests/lessons/broken_setup.py",
        "scripts/lessons/contraction.py",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let outcomes: Vec<serde_json::Value> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).expect("one JSON outcome a line"))
        .collect();
    assert_eq!(outcomes.len(), 3);
    assert!(outcomes[0]["error"].is_null() && outcomes[2]["error"].is_null());
    assert!(
        outcomes[1]["error"]
            .as_str()
            .unwrap()
            .contains("this lesson is broken")
    );
    assert!(
        outcomes[2]["file"]
            .as_str()
            .unwrap()
            .ends_with("contraction.py")
    );
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

#[test]
fn in_the_window_a_lesson_that_crashes_blocks_or_swallows_its_stop_leaves_the_game_running() {
    let dir = std::env::temp_dir().join(format!("lightcone-lesson-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let env = [
        ("LIGHTCONE_HOOK_LIMIT", "1"),
        ("LIGHTCONE_MEMORY_LIMIT", "384"),
    ];
    // (lesson, what the panel and stderr say). A C call that never
    // returns used to end the game with status 3; a segfault, with
    // SIGSEGV. The lesson runs in its own process now: the game takes its
    // screenshot (frames went on being drawn) and exits 0.
    // Frames enough for the hook that cannot be interrupted to be stopped
    // before the screenshot: its limit (1 s) and the kill after it (0.5 s),
    // past the lesson's start, in 30 frames only while frames took 60 ms
    // (a faster window took its screenshot before the stop).
    for (lesson, says, frames) in [
        ("crashes", "crashed (SIGSEGV", 30),
        ("long_builtin", "could not be interrupted", 200),
    ] {
        let (out, img) = play_under_xvfb_with(
            &["play", &format!("tests/lessons/{lesson}.py")],
            &dir.join(format!("window-{lesson}.png")),
            frames,
            &env,
        );
        let stderr = String::from_utf8_lossy(&out.stderr);
        let img = img.unwrap_or_else(|| panic!("{lesson}: the game did not survive:\n{stderr}"));
        assert!(stderr.contains(says), "{lesson}: {says:?} not in\n{stderr}");
        assert!(
            traceback_pixels(&img) > 200,
            "{lesson}: no reason on screen"
        );
        assert!(
            cloth_pixels(&img) > 1280 * 720 / 20,
            "{lesson}: no table on screen"
        );
    }
}

/// How the window runs lessons: in their own process, started from the
/// game's binary, with a 384 MiB address space.
fn isolation() -> Isolation {
    Isolation {
        exe: env!("CARGO_BIN_EXE_lightcone").into(),
        memory_mb: 384,
    }
}

/// What the window's frame loop saw while driving a lesson at 60 fps for
/// `seconds`: the error shown, the longest frame (ms), the frames drawn,
/// the board time kept.
struct WindowRun {
    error: Option<String>,
    longest_ms: f64,
    frames: u32,
    t: f64,
    running: bool,
}

/// Drives `lesson` as the window does (`LessonHost::after_step` once a
/// frame; board time waits while a hook is out), with a hook limit of 1 s.
fn drive_window_host(lesson: &str, seconds: f64) -> WindowRun {
    let path = repo().join(lesson);
    let (mut host, mut game) = LessonHost::load_isolated_with_limit(
        &path,
        Duration::from_secs(1),
        lightcone::lesson::empty_game,
        isolation(),
    )
    .unwrap();
    assert!(host.error.is_none(), "{lesson}: {:?}", host.error);
    let frame = Duration::from_secs_f64(1.0 / 60.0);
    let start = Instant::now();
    let mut longest = Duration::ZERO;
    let mut frames = 0;
    while start.elapsed().as_secs_f64() < seconds {
        let t0 = Instant::now();
        host.serve(&mut game, FRAME_BUDGET);
        let before = game.live_time;
        if !host.busy() {
            game.step(frame.as_secs_f64());
        }
        host.after_step(&mut game, before);
        host.serve(&mut game, Duration::ZERO);
        let took = t0.elapsed();
        longest = longest.max(took);
        frames += 1;
        std::thread::sleep(frame.saturating_sub(took));
    }
    WindowRun {
        error: host.error.clone(),
        longest_ms: longest.as_secs_f64() * 1e3,
        frames,
        t: game.live_time,
        running: host.running(),
    }
}

#[test]
fn in_the_window_no_misbehaving_hook_ends_the_game_or_stops_its_frames() {
    // (lesson, what the reason says): exits with status 3 (past the
    // guard on os._exit, and through it), a segfault through ctypes, a
    // memory bomb, an endless loop inside `except BaseException`, a
    // 60 s sleep, a C builtin that never returns, garbage on the channel
    // to the game.
    let cases: &[(&str, &[&str])] = &[
        ("exits_for_real", &["in on_frame", "exited with status 3"]),
        ("exits", &["SystemExit", "cannot end the game"]),
        ("crashes", &["in on_frame", "SIGSEGV"]),
        ("memory_bomb", &["in on_frame", "MemoryError"]),
        (
            "swallow_base_exception",
            &["TimeoutError", "except BaseException"],
        ),
        ("sleeps", &["TimeoutError", "time.sleep(60)"]),
        (
            "long_builtin",
            &["more than 1 s", "could not be interrupted"],
        ),
        (
            "sends_garbage",
            &["misbehaved", "does not understand", "was stopped"],
        ),
    ];
    // All at once (each waits out its limit): each has its own process.
    let runs: Vec<_> = cases
        .iter()
        .map(|(name, _)| {
            let lesson = format!("tests/lessons/{name}.py");
            std::thread::spawn(move || drive_window_host(&lesson, 3.0))
        })
        .collect();
    for ((name, says), run) in cases.iter().zip(runs) {
        let run = run.join().unwrap();
        let error = run
            .error
            .unwrap_or_else(|| panic!("{name}: no reason shown"));
        for s in *says {
            assert!(error.contains(s), "{name}: {s:?} not in\n{error}");
        }
        assert!(!run.running, "{name}: hooks stop");
        // The state before the misbehaviour is kept: one frame ran.
        assert!(run.t > 0.0, "{name}: board time {}", run.t);
        // The frame loop went on: ~180 frames in 3 s, none held for long
        // (the frame budget is 10 ms; the margin is for 8 lessons at once
        // on a loaded 2-core machine).
        assert!(run.frames > 60, "{name}: only {} frames", run.frames);
        assert!(
            run.longest_ms < 300.0,
            "{name}: a frame took {:.0} ms",
            run.longest_ms
        );
        println!(
            "{name}: {} frames, longest {:.1} ms",
            run.frames, run.longest_ms
        );
    }
}

#[test]
fn every_lesson_behaves_the_same_in_its_own_process() {
    for lesson in lessons() {
        let path = repo().join(&lesson);
        let limit = Duration::from_secs(10);
        let here = headless::run(&path, 600.0, 30.0, limit).unwrap();
        let there = headless::run_isolated(&path, 600.0, 30.0, limit, isolation()).unwrap();
        assert!(there.error.is_none(), "{lesson}: {:?}", there.error);
        let json = |o: &headless::Outcome| serde_json::to_value(o).unwrap();
        assert_eq!(json(&here), json(&there), "{lesson}");
    }
}

/// The cost of one hook call across processes (the call, the hook's
/// requests answered on the game, its end), measured on hooks that read
/// the board time from the snapshot, and that also ask for `state()`: the
/// figures in BENCHMARKS.md. At 60 fps (a call every 16.7 ms, so each
/// round trip wakes both processes) and back to back.
#[test]
fn a_hook_call_in_its_own_process_costs_well_under_a_frame() {
    let dir = std::env::temp_dir().join(format!("lightcone-cost-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, body) in [("t", "seen = world.t"), ("state", "seen = world.state().t")] {
        let path = dir.join(format!("cost_{name}.py"));
        std::fs::write(
            &path,
            format!(
                "import lightcone\n\
                 def setup(world):\n\
                 \x20   s = lightcone.Scene(title='cost')\n\
                 \x20   s.add_puck('a', (0.5, 0.71), beta=(0.5, 0.0))\n\
                 \x20   world.start(s)\n\
                 def on_frame(world, t):\n\
                 \x20   world.n = getattr(world, 'n', 0) + 1\n\
                 \x20   {body}\n\
                 \x20   if seen != t or world.n == 1650:\n\
                 \x20       world.check('calls', seen == t, str(world.n))\n"
            ),
        )
        .unwrap();
        let (mut host, mut game) = LessonHost::load_isolated_with_limit(
            &path,
            Duration::from_secs(10),
            lightcone::lesson::empty_game,
            isolation(),
        )
        .unwrap();
        assert!(host.error.is_none(), "{:?}", host.error);
        for (pace, calls) in [
            (Some(Duration::from_secs_f64(1.0 / 60.0)), 150),
            (None, 1500),
        ] {
            // As the window's frame: take the ends of last frame's hooks,
            // step, send this frame's hooks, draw (a sleep here), answer
            // what the lesson asked meanwhile. Timed: the game's own
            // time in the three lesson calls.
            let mut times = Vec::new();
            // Until `calls` frames moved board time (each sent one hook);
            // on a loaded machine a frame may find its hook not done yet
            // within the budget, and board time waits that frame.
            let (mut steps, mut frames) = (0, 0);
            while steps < calls && frames < 20 * calls {
                frames += 1;
                let start = Instant::now();
                host.serve(&mut game, FRAME_BUDGET);
                let before = game.live_time;
                let served = start.elapsed();
                if !host.busy() {
                    game.step(1e-4);
                    steps += 1;
                }
                let start = Instant::now();
                host.after_step(&mut game, before);
                let sent = start.elapsed();
                if let Some(p) = pace {
                    // Drawing: the game's thread is busy meanwhile.
                    let until = Instant::now() + p / 2;
                    while Instant::now() < until {
                        std::hint::spin_loop();
                    }
                }
                let start = Instant::now();
                host.serve(&mut game, Duration::ZERO);
                let took = served + sent + start.elapsed();
                times.push(took.as_secs_f64() * 1e6);
                if let Some(p) = pace {
                    std::thread::sleep(p / 2);
                }
            }
            host.settle(&mut game);
            assert_eq!(steps, calls, "{frames} frames");
            assert!(host.error.is_none(), "{:?}", host.error);
            times.sort_by(f64::total_cmp);
            let at = |q: f64| times[((times.len() - 1) as f64 * q) as usize];
            let pace = if pace.is_some() {
                "60 fps"
            } else {
                "back to back"
            };
            println!(
                "hook call in its own process ({name}, {pace}): p50 {:.1} µs, p99 {:.1} µs, max {:.1} µs ({calls} calls, {} frames waited)",
                at(0.5),
                at(0.99),
                at(1.0),
                frames - calls
            );
            // Loose, for a shared machine: the goal (BENCHMARKS.md) is 100 µs.
            assert!(at(0.5) < 5000.0, "p50 {} µs", at(0.5));
        }
        // One claim, at the last call: every call saw its t as world.t.
        let claims = host.with_ui(|ui| ui.claims.clone());
        assert_eq!(claims.len(), 1, "{claims:?}");
        assert!(claims[0].ok && claims[0].detail == "1650", "{claims:?}");
    }
}

#[test]
fn in_the_window_a_reload_after_a_crash_starts_a_new_process() {
    let dir = std::env::temp_dir().join(format!("lightcone-reload-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("reload.py");
    let lesson = |on_frame: &str| {
        format!(
            "import ctypes, lightcone\n\
             def setup(world):\n\
             \x20   s = lightcone.Scene(title='reload')\n\
             \x20   s.add_puck('a', (0.5, 0.71), beta=(0.5, 0.0))\n\
             \x20   world.start(s)\n\
             def on_frame(world, t):\n\
             \x20   {on_frame}\n"
        )
    };
    std::fs::write(&path, lesson("ctypes.string_at(0)")).unwrap();
    let (mut host, mut game) = LessonHost::load_isolated_with_limit(
        &path,
        Duration::from_secs(2),
        lightcone::lesson::empty_game,
        isolation(),
    )
    .unwrap();
    assert_eq!(game.scene.title, "reload");
    let step = |host: &mut LessonHost, game: &mut lightcone::model::GameState| {
        let before = game.live_time;
        game.paused = false;
        game.step(0.05);
        host.after_step(game, before);
        host.settle(game);
    };
    step(&mut host, &mut game);
    let error = host.error.clone().expect("the crash is reported");
    assert!(error.contains("SIGSEGV"), "{error}");
    assert!(!host.running());
    // Fixed and reloaded (F5, or the saved file): a new process runs it.
    std::fs::write(&path, lesson("world.check('ran', world.t == t)")).unwrap();
    host.reload(&mut game);
    host.settle(&mut game);
    assert!(host.error.is_none(), "{:?}", host.error);
    assert_eq!(game.live_time, 0.0, "the lesson's new game");
    for _ in 0..3 {
        step(&mut host, &mut game);
    }
    assert!(host.running(), "{:?}", host.error);
    let claims = host.with_ui(|ui| ui.claims.clone());
    assert_eq!(claims.len(), 3);
    assert!(claims.iter().all(|c| c.ok));
    assert_eq!(host.loads, 2);
}

#[test]
fn in_the_window_the_world_is_a_lightcone_world() {
    let dir = std::env::temp_dir().join(format!("lightcone-isinstance-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("isinstance.py");
    std::fs::write(
        &path,
        r#"import os, tempfile
import lightcone
def setup(world):
    world.check('setup', isinstance(world, lightcone.World), type(world).__name__)
    s = lightcone.Scene(title='isinstance')
    s.add_puck('a', (0.5, 0.71), beta=(0.5, 0.0))
    world.start(s)
def on_frame(world, t):
    world.check('on_frame', isinstance(world, lightcone.World), repr(world))
    world.check('not a scene', not isinstance(world, lightcone.Scene))
    f = world.diagram(os.path.join(tempfile.gettempdir(), 'd.png'), size=(200, 150))
    world.check('a diagram saved by the lesson', (f.width, f.height) == (200, 150))
    try:
        world.diagram('d.png')
        denied = False
    except OSError:
        denied = True
    world.check('not beside the lesson: its sandbox writes only its own folder', denied)
    world.finish()
"#,
    )
    .unwrap();
    let (mut host, mut game) = LessonHost::load_isolated_with_limit(
        &path,
        Duration::from_secs(5),
        lightcone::lesson::empty_game,
        isolation(),
    )
    .unwrap();
    let before = game.live_time;
    game.paused = false;
    game.step(0.05);
    host.after_step(&mut game, before);
    host.settle(&mut game);
    assert!(host.error.is_none(), "{:?}", host.error);
    let claims = host.with_ui(|ui| ui.claims.clone());
    assert_eq!(claims.len(), 5, "{claims:?}");
    assert!(claims.iter().all(|c| c.ok), "{claims:?}");
    // Saved by the lesson's own (sandboxed) process, never by the game:
    // nothing was written beside the lesson.
    assert!(!dir.join("d.png").exists());
}

/// The lesson template on the README's front page ("A lesson in 20 lines",
/// under *Teachers start here*) runs as printed: it finishes, its claim
/// holds, and the headless run answers its question with the text of the
/// right choice (`ask`'s `answer=` is an index, `on_answer` gets the text).
/// A teacher copies this block first, so it must never rot.
#[test]
fn the_readme_lesson_template_runs_as_printed() {
    let readme = std::fs::read_to_string(repo().join("README.md")).unwrap();
    let section = readme
        .split("### A lesson in 20 lines")
        .nth(1)
        .expect("README.md has the section \"A lesson in 20 lines\"");
    let code = section
        .split("```python\n")
        .nth(1)
        .and_then(|s| s.split("\n```").next())
        .expect("the section holds a ```python block");
    let lines = code.lines().count();
    assert!(lines <= 25, "the template is {lines} lines, not about 20");
    let dir = std::env::temp_dir().join(format!("lightcone-readme-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("head_on.py");
    std::fs::write(&path, code).unwrap();
    let out = lightcone(&["lesson", path.to_str().unwrap(), "--json"]);
    let _ = std::fs::remove_dir_all(&dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "the README's lesson failed:\n{stderr}"
    );
    let outcome: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(outcome["error"].is_null(), "{}", outcome["error"]);
    assert!(outcome["finished"].is_string(), "{outcome}");
    let claims = outcome["claims"].as_array().expect("claims");
    assert!(!claims.is_empty(), "{outcome}");
    assert!(
        claims.iter().all(|c| c["ok"].as_bool() == Some(true)),
        "{outcome}"
    );
    assert_eq!(
        outcome["answers"],
        serde_json::json!([["Which moves after?", "b"]]),
        "{outcome}"
    );
}

/// The window's scene menu opens lessons as `lightcone play LESSON.py`
/// does, through the same calls as the window (`UiAction::apply`, then
/// the lesson host's `act`, then its frames): a shipped lesson (from its
/// built-in copy), then a lesson typed in the path field in its place,
/// then a scene, which ends the lesson. About 1 s: two lesson processes.
#[test]
fn the_scene_menu_starts_a_lesson_replaces_it_and_a_scene_ends_it() {
    use lightcone::model::GameState;
    use lightcone::play::actions::UiAction;
    use lightcone::play::lesson_host::HostedLesson;
    use lightcone::play::scene_menu::Choice;
    let mut state = GameState::new(lightcone::assets::default_scene().unwrap());
    let mut hosted = HostedLesson::new(None, Ok(isolation()));
    let act = |hosted: &mut HostedLesson, state: &mut GameState, action: UiAction| {
        if let Some(back) = action.apply(state) {
            hosted.act(back, state);
        }
    };
    // Frames (as the window's) until the lesson's setup has built its game.
    let frames_until = |hosted: &mut HostedLesson, state: &mut GameState, title: &str| {
        let start = Instant::now();
        while state.scene.title != title {
            assert!(start.elapsed() < Duration::from_secs(20), "no {title:?}");
            hosted.step(state, 1.0 / 60.0, Instant::now());
            hosted.after_draw(state);
            std::thread::sleep(Duration::from_millis(5));
        }
    };
    let i = lightcone::assets::LESSONS
        .iter()
        .position(|(n, _)| *n == "cushion.py")
        .expect("cushion.py is a shipped lesson");
    act(&mut hosted, &mut state, UiAction::SceneMenu);
    act(&mut hosted, &mut state, UiAction::Open(Choice::Lesson(i)));
    assert!(!state.scene_menu.open, "the menu closes");
    frames_until(&mut hosted, &mut state, "Cushion reflection");
    let host = hosted.host.as_ref().expect("a lesson runs");
    assert_eq!(host.name(), "(built in) cushion.py");
    assert!(host.running() && host.error.is_none(), "{:?}", host.error);
    // Its question is on the panel.
    let asked = host.with_ui(|ui| ui.question.as_ref().map(|q| q.text.clone()));
    let asked = asked.expect("the lesson asks first");
    assert!(asked.contains("angle it came in"), "{asked}");
    // Another lesson, typed in the field, replaces it.
    let typed = repo().join("scripts/lessons/simultaneity.py");
    state.scene_menu.path = typed.display().to_string();
    act(&mut hosted, &mut state, UiAction::Open(Choice::Typed));
    frames_until(&mut hosted, &mut state, "Apparent simultaneity");
    let host = hosted.host.as_ref().expect("a lesson runs");
    assert_eq!(host.path(), typed.as_path());
    assert!(host.running() && host.error.is_none(), "{:?}", host.error);
    // A scene ends it.
    act(&mut hosted, &mut state, UiAction::Open(Choice::Scene(0)));
    assert!(hosted.host.is_none(), "opening a scene ends the lesson");
    assert_eq!(
        state.scene.title,
        lightcone::assets::default_scene().unwrap().title
    );
    // A lesson that is not there: said in the menu, the game goes on.
    state.scene_menu.path = "no/such/lesson.py".to_owned();
    act(&mut hosted, &mut state, UiAction::Open(Choice::Typed));
    assert!(hosted.host.is_none());
    let e = state.scene_menu.error.clone().expect("an error");
    assert!(e.contains("no such lesson file"), "{e}");
}
