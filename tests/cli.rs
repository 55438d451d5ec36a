//! End-to-end tests that drive the `lightcone` binary.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn lightcone(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lightcone"))
        .args(args)
        .current_dir(repo())
        .output()
        .expect("the lightcone binary runs")
}

fn shipped_scenes() -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(repo().join("assets/scenes"))
        .expect("assets/scenes exists")
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| format!("assets/scenes/{}", p.file_name().unwrap().to_string_lossy()))
        .collect();
    v.sort();
    v
}

#[test]
fn check_accepts_every_shipped_scene() {
    let scenes = shipped_scenes();
    assert!(scenes.len() >= 5, "{scenes:?}");
    let args: Vec<&str> = std::iter::once("check")
        .chain(scenes.iter().map(String::as_str))
        .collect();
    let out = lightcone(&args);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}\n{}",
        stdout,
        String::from_utf8_lossy(&out.stderr)
    );
    for s in &scenes {
        assert!(
            stdout.contains(&format!("{s}: ok")),
            "{s} missing from:\n{stdout}"
        );
    }
}

#[test]
fn check_summarises_speeds_as_beta_and_gamma() {
    let out = lightcone(&["check", "assets/scenes/paper_carom.toml"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success());
    // white: β = (0.8, 0.12), |β| = 0.8089499366, γ = 1/√(1 − 0.6544) = 1.701035.
    let white = stdout
        .lines()
        .find(|l| l.contains("white"))
        .expect("white listed");
    assert!(white.contains("|β| = 0.808949937"), "{white}");
    assert!(white.contains("γ = 1.701035"), "{white}");
    assert!(stdout.contains("effects on: contraction, light_delay, aberration, time_dilation"));
}

#[test]
fn check_reports_a_bad_scene_with_file_line_and_field() {
    let dir = std::env::temp_dir().join(format!("lightcone-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        "[[puck]]\nname = \"x\"\nposition = [0.5, 0.5]\nbeta = [1.2, 0.0]\n",
    )
    .unwrap();
    let bad = bad.to_string_lossy().into_owned();
    let out = lightcone(&["check", "assets/scenes/paper_carom.toml", &bad]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains(&format!("{bad}:4:8: puck[0].beta:")),
        "{stderr}"
    );
    assert!(stderr.contains("1 of 2 scene(s) have errors"), "{stderr}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn no_arguments_checks_the_default_scene() {
    let out = lightcone(&[]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("paper_carom.toml: ok"));
}
