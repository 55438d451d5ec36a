//! `cargo install` gives a working program (issue 15): its own test binary,
//! because the install may relink `target/release/lightcone`, which the
//! other end-to-end tests run; cargo runs test binaries one at a time, so
//! none of them runs meanwhile.

mod common;

use common::repo;

/// `cargo install --path game --root TMP`, then `TMP/bin/lightcone check`
/// with no arguments, run from another folder. The install shares this
/// build's target folder, so it only links what the tests already built;
/// if it still has to compile (a cold cache: many minutes on two cores)
/// it is stopped after four minutes and the test relies on
/// `the_default_scene_is_built_in` (the same binary, copied) instead.
#[test]
fn cargo_install_gives_a_working_program() {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};
    let exe = std::path::PathBuf::from(env!("CARGO_BIN_EXE_lightcone"));
    let Some(target) = exe.parent().and_then(|p| p.parent()) else {
        return;
    };
    let dir = std::env::temp_dir().join(format!("lightcone-install-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned());
    let mut child = Command::new(cargo)
        .args([
            "install",
            "--locked",
            "--offline",
            "--path",
            "game",
            "--root",
        ])
        .arg(&dir)
        .arg("--target-dir")
        .arg(target)
        .current_dir(repo())
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("cargo runs");
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > Duration::from_secs(240) {
            let _ = child.kill();
            let _ = child.wait();
            eprintln!("cargo install did not finish in 4 minutes (a cold build): not checked here");
            let _ = std::fs::remove_dir_all(&dir);
            return;
        }
        std::thread::sleep(Duration::from_millis(200));
    };
    let mut stderr = String::new();
    if let Some(mut e) = child.stderr.take() {
        let _ = std::io::Read::read_to_string(&mut e, &mut stderr);
    }
    assert!(status.success(), "cargo install failed: {stderr}");
    let elsewhere = dir.join("elsewhere");
    std::fs::create_dir_all(&elsewhere).unwrap();
    let out = Command::new(dir.join("bin").join("lightcone"))
        .arg("check")
        .current_dir(&elsewhere)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("paper_carom.toml: ok"), "{stdout}");
    let _ = std::fs::remove_dir_all(&dir);
}
