//! Lessons from strangers (issue 34): what a lesson claimed survives its
//! process, what it sends is bounded, and its process is sandboxed.

use std::io::Read;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use super::common::repo;
use super::lesson_outcome;

/// A claim reaches `--json` when it is made: a hook that claims and then
/// is killed at its time limit inside one C call, or aborts its process,
/// keeps every claim (they came only when the hook returned, so both were
/// lost).
#[test]
fn claims_made_before_the_process_dies_are_kept() {
    let runs: Vec<_> = [
        ("claims_then_hangs", 3, "could not be interrupted"),
        ("claims_then_aborts", 4, "SIGABRT"),
    ]
    .into_iter()
    .map(|(name, status, says)| {
        let run = std::thread::spawn(move || {
            lesson_outcome(&format!("tests/lessons/{name}.py"), &["--hook-limit", "1"])
        });
        (name, status, says, run)
    })
    .collect();
    for (name, status, says, run) in runs {
        let (outcome, code, _, stderr) = run.join().unwrap();
        assert_eq!(code, Some(status), "{name}: {outcome}\n{stderr}");
        let error = outcome["error"].as_str().unwrap_or_default();
        assert!(error.contains(says), "{name}: {says:?} not in {error}");
        let claims: Vec<&str> = outcome["claims"]
            .as_array()
            .expect("claims")
            .iter()
            .map(|c| c["claim"].as_str().unwrap_or_default())
            .collect();
        let expected: &[&str] = if name == "claims_then_hangs" {
            &["claimed in setup", "claimed before the C call"]
        } else {
            &["claimed before the crash"]
        };
        assert_eq!(claims, expected, "{name}: {outcome}");
    }
}

/// Runs `lightcone ARGS` (or, with `exe`, that program) from the
/// repository root, reading its `/proc/PID/status` every 5 ms: its output
/// and its peak resident memory (`VmHWM`, the kernel's own high-water
/// mark), MiB.
fn run_measuring_peak(
    exe: Option<&std::path::Path>,
    args: &[&str],
    env: &[(&str, &str)],
) -> (std::process::Output, f64) {
    let exe = exe.map_or_else(
        || std::path::PathBuf::from(env!("CARGO_BIN_EXE_lightcone")),
        |p| p.to_path_buf(),
    );
    let mut child = Command::new(exe)
        .args(args)
        .envs(env.iter().copied())
        .current_dir(repo())
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("it starts");
    let status = format!("/proc/{}/status", child.id());
    let drain = |mut from: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut all = Vec::new();
            let _ = from.read_to_end(&mut all);
            all
        })
    };
    let stdout = drain(Box::new(child.stdout.take().unwrap()));
    let stderr = drain(Box::new(child.stderr.take().unwrap()));
    let mut peak_kb = 0u64;
    let exit = loop {
        if let Ok(text) = std::fs::read_to_string(&status)
            && let Some(kb) = text
                .lines()
                .find_map(|l| l.strip_prefix("VmHWM:"))
                .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        {
            peak_kb = peak_kb.max(kb);
        }
        if let Some(exit) = child.try_wait().unwrap() {
            break exit;
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let output = std::process::Output {
        status: exit,
        stdout: stdout.join().unwrap(),
        stderr: stderr.join().unwrap(),
    };
    (output, peak_kb as f64 / 1024.0)
}

/// The flood lessons and what stops each: `world.check` refuses the
/// 10 001st claim, and any claim over 4 KiB (one of 1 MiB a call took the
/// window's game to gigabytes); a lesson that prints more than 16 MiB (here without a
/// newline), writes 1.5 GB with no newline into its channel, or forges
/// 20 000 claims into it past `world.check` is stopped by the process
/// that reads it.
const FLOODS: [(&str, i32, &str); 5] = [
    ("floods_claims", 1, "at most 10000 claims"),
    ("floods_big_claims", 1, "give at most 4096"),
    ("floods_prints", 4, "printed more than 16 MiB"),
    ("floods_its_pipe", 4, "a line longer than 16 MiB"),
    ("forges_claims", 4, "made more than 10000 claims"),
];

/// Headless: each flood is stopped with its reason, and `lightcone
/// lesson` (the parent that reads the lesson's process) stays under
/// 500 MB (a 1.5 GB line with no newline took it to 1.5 GB).
#[test]
fn a_flooding_lesson_is_stopped_and_the_runner_stays_small() {
    for pair in FLOODS.chunks(2) {
        let runs: Vec<_> = pair
            .iter()
            .map(|&(name, status, says)| {
                let run = std::thread::spawn(move || {
                    let lesson = format!("tests/lessons/{name}.py");
                    let start = Instant::now();
                    let (out, peak) = run_measuring_peak(
                        None,
                        &["lesson", &lesson, "--json", "--hook-limit", "20"],
                        &[],
                    );
                    (out, peak, start.elapsed())
                });
                (name, status, says, run)
            })
            .collect();
        for (name, status, says, run) in runs {
            let (out, peak, took) = run.join().unwrap();
            let stderr = String::from_utf8_lossy(&out.stderr);
            let tail: String = stderr
                .chars()
                .rev()
                .take(2000)
                .collect::<Vec<_>>()
                .into_iter()
                .rev()
                .collect();
            let outcome: serde_json::Value = serde_json::from_slice(&out.stdout)
                .unwrap_or_else(|e| panic!("{name}: not JSON ({e}): {tail}"));
            let error = outcome["error"].as_str().unwrap_or_default();
            assert!(error.contains(says), "{name}: {says:?} not in {error}");
            assert_eq!(out.status.code(), Some(status), "{name}: {error}");
            let claims = outcome["claims"].as_array().map_or(0, Vec::len);
            assert!(claims <= 10_000, "{name}: {claims} claims kept");
            // What the lesson printed went through, up to the bound only.
            assert!(
                stderr.len() < (17 << 20),
                "{name}: {} bytes on stderr",
                stderr.len()
            );
            assert!(peak < 500.0, "{name}: the runner peaked at {peak:.0} MB");
            assert!(took < Duration::from_secs(60), "{name}: took {took:?}");
            println!("{name}: stopped in {took:.1?}, runner peak {peak:.0} MB: {error}");
        }
    }
}

/// Not a check by itself: the process that
/// `in_the_window_a_flooding_lesson_is_stopped_and_the_game_stays_small`
/// starts (this test binary, for this test alone) to drive one flood
/// lesson as the window does, so that the game's memory is measured on
/// its own; it prints what the frame loop saw. Without
/// `LIGHTCONE_FLOOD_PROBE` it does nothing.
#[test]
fn window_flood_probe() {
    let Ok(lesson) = std::env::var("LIGHTCONE_FLOOD_PROBE") else {
        return;
    };
    let run = super::drive_window_host(&lesson, 6.0);
    println!(
        "PROBE {}",
        serde_json::json!({
            "error": run.error,
            "frames": run.frames,
            "longest_ms": run.longest_ms,
            "running": run.running,
        })
    );
}

/// In the window: each flood stops the lesson with its reason, the frame
/// loop goes on drawing, and the game's process stays under 500 MB (a
/// claims flood took the window's game to 2 GB and stopped its drawing).
#[test]
fn in_the_window_a_flooding_lesson_is_stopped_and_the_game_stays_small() {
    let exe = std::env::current_exe().unwrap();
    // The game answers a hook's requests within each frame's budget, so
    // the claims floods meet their hook's time limit (1 s here) before
    // `world.check`'s bounds: either stops them.
    let window = [
        ("floods_claims", 0, "TimeoutError|at most 10000 claims"),
        ("floods_big_claims", 0, "TimeoutError|give at most 4096"),
        FLOODS[2],
        FLOODS[3],
    ];
    // One at a time: each frame is timed.
    for pair in window.chunks(1) {
        let runs: Vec<_> = pair
            .iter()
            .map(|&(name, _, says)| {
                let exe = exe.clone();
                let run = std::thread::spawn(move || {
                    let lesson = format!("tests/lessons/{name}.py");
                    run_measuring_peak(
                        Some(&exe),
                        &["safety::window_flood_probe", "--exact", "--nocapture"],
                        &[("LIGHTCONE_FLOOD_PROBE", &lesson)],
                    )
                });
                (name, says, run)
            })
            .collect();
        for (name, says, run) in runs {
            let (out, peak) = run.join().unwrap();
            let stdout = String::from_utf8_lossy(&out.stdout);
            let probe: serde_json::Value = stdout
                .lines()
                .find_map(|l| l.strip_prefix("PROBE "))
                .and_then(|l| serde_json::from_str(l).ok())
                .unwrap_or_else(|| panic!("{name}: the probe said nothing:\n{stdout}"));
            let error = probe["error"].as_str().unwrap_or_default();
            assert!(
                says.split('|').any(|s| error.contains(s)),
                "{name}: {says:?} not in {error}"
            );
            assert_eq!(probe["running"], false, "{name}: hooks stop");
            let frames = probe["frames"].as_u64().unwrap_or(0);
            let longest = probe["longest_ms"].as_f64().unwrap_or(f64::MAX);
            assert!(frames > 120, "{name}: only {frames} frames in 6 s");
            // (The frame budget is 10 ms; the margin is for a machine
            // loaded by other builds.)
            assert!(longest < 400.0, "{name}: a frame took {longest:.0} ms");
            assert!(peak < 500.0, "{name}: the game peaked at {peak:.0} MB");
            println!("{name}: {frames} frames, longest {longest:.1} ms, game peak {peak:.0} MB");
        }
    }
}

/// The hostile lessons the sandbox refuses (`lesson::sandbox`), past the
/// audit hook or through it, and what the reason says.
const HOSTILE: [(&str, &str); 9] = [
    ("forks", "may not start processes"),
    ("signals_the_game", "may not signal the game"),
    ("posix_spawns", "Operation not permitted"),
    (
        "ctypes_kills",
        "kill(parent, SIGKILL) refused: Operation not permitted",
    ),
    ("ctypes_forks", "fork() refused: Operation not permitted"),
    ("ctypes_execs", "execv refused: Operation not permitted"),
    ("opens_a_socket", "Operation not permitted"),
    ("writes_outside", "written.txt: Permission denied"),
    ("reads_secrets", "secret.txt: Permission denied"),
];

/// Processes whose command line names `needle` (the lesson's file, or a
/// `sleep 60` a lesson would have started).
fn running_with(needle: &str) -> Vec<String> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir("/proc").into_iter().flatten().flatten() {
        let Ok(cmdline) = std::fs::read(entry.path().join("cmdline")) else {
            continue;
        };
        let cmdline = String::from_utf8_lossy(&cmdline).replace('\0', " ");
        if cmdline.contains(needle) {
            found.push(format!(
                "{}: {cmdline}",
                entry.file_name().to_string_lossy()
            ));
        }
    }
    found
}

/// A folder outside the lesson's with a file in it, for the lessons that
/// try to read or write there.
fn outside() -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("lightcone-outside-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("secret.txt"), "a teacher's secret").unwrap();
    dir
}

/// Headless and in the window: each hostile lesson is refused with its
/// reason, the game (the runner, the test's own process in the window)
/// goes on, the outcome is printed, nothing the lesson started is left
/// running, and nothing was written outside its temporary folder.
#[test]
fn the_sandbox_refuses_every_hostile_lesson() {
    let dir = outside();
    // SAFETY: set before any thread of this test reads them; the lessons'
    // processes inherit them.
    unsafe {
        std::env::set_var("LIGHTCONE_TEST_OUTSIDE", &dir);
        std::env::set_var("LIGHTCONE_TEST_SECRET", dir.join("secret.txt"));
    }
    for (name, says) in HOSTILE {
        let (outcome, code, _, stderr) =
            lesson_outcome(&format!("tests/lessons/{name}.py"), &["--hook-limit", "2"]);
        let error = outcome["error"].as_str().unwrap_or_default();
        assert!(
            error.contains(says),
            "{name}: {says:?} not in {error}\n{stderr}"
        );
        assert_eq!(code, Some(1), "{name}: {error}");
        assert!(
            outcome["t"].as_f64().unwrap_or(0.0) > 0.0,
            "{name}: {outcome}"
        );
        println!(
            "{name} (headless): refused: {}",
            error.lines().last().unwrap_or("")
        );
    }
    // Two at a time: a lesson's process that starts late on a loaded
    // machine meets its setup's 1 s limit.
    for pair in HOSTILE.chunks(2) {
        let runs: Vec<_> = pair
            .iter()
            .map(|&(name, says)| {
                let lesson = format!("tests/lessons/{name}.py");
                let run = std::thread::spawn(move || super::drive_window_host(&lesson, 2.0));
                (name, says, run)
            })
            .collect();
        for (name, says, run) in runs {
            let run = run.join().unwrap();
            let error = run.error.unwrap_or_default();
            assert!(
                error.contains(says),
                "{name} (window): {says:?} not in {error}"
            );
            assert!(!run.running, "{name}: hooks stop");
            assert!(run.t > 0.0, "{name}: board time {}", run.t);
            println!("{name} (window): refused");
        }
    }
    for needle in HOSTILE
        .iter()
        .map(|(name, _)| format!("tests/lessons/{name}.py"))
        .chain(["sleep 60".to_owned()])
    {
        let left = running_with(&needle);
        assert!(left.is_empty(), "left running: {left:?}");
    }
    assert!(!dir.join("written.txt").exists());
    assert!(
        !repo()
            .join("tests/lessons/written_by_a_lesson.txt")
            .exists()
    );
    let _ = std::fs::remove_dir_all(&dir);
}
