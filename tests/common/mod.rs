//! Helpers shared by the end-to-end tests (each test binary uses a part).
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::Mutex;

use lightcone_render::headless::Image;

/// The repository root.
pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Runs `lightcone ARGS` from the repository root.
pub fn lightcone(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lightcone"))
        .args(args)
        .current_dir(repo())
        .output()
        .expect("the lightcone binary runs")
}

/// One Xvfb at a time: `xvfb-run -a` can hand two concurrent runs the same
/// display number.
pub static XVFB: Mutex<()> = Mutex::new(());

/// Runs `lightcone ARGS --screenshot SHOT --frames FRAMES` under Xvfb
/// (1280×720) and loads the screenshot (`None` if the game failed).
pub fn play_under_xvfb(args: &[&str], shot: &Path, frames: u32) -> (Output, Option<Image>) {
    play_under_xvfb_with(args, shot, frames, &[])
}

/// [`play_under_xvfb`] with environment variables `env` set.
pub fn play_under_xvfb_with(
    args: &[&str],
    shot: &Path,
    frames: u32,
    env: &[(&str, &str)],
) -> (Output, Option<Image>) {
    play_on_screen(args, shot, frames, env, "1280x720x24")
}

/// [`play_under_xvfb_with`] on an Xvfb screen of `screen` (`WxHxDEPTH`),
/// for windows beside the main one (CAVE outputs).
pub fn play_on_screen(
    args: &[&str],
    shot: &Path,
    frames: u32,
    env: &[(&str, &str)],
    screen: &str,
) -> (Output, Option<Image>) {
    let _one = XVFB.lock().unwrap_or_else(|e| e.into_inner());
    let out = Command::new("xvfb-run")
        .envs(env.iter().copied())
        .args(["-a", "-s", &format!("-screen 0 {screen}")])
        .arg(env!("CARGO_BIN_EXE_lightcone"))
        .args(args)
        .arg("--screenshot")
        .arg(shot)
        .args(["--frames", &frames.to_string()])
        .current_dir(repo())
        .output()
        .expect("xvfb-run runs (apt-get install xvfb xauth; .ci/run installs them)");
    let img = out
        .status
        .success()
        .then(|| Image::load_png(shot).expect("the screenshot loads"));
    (out, img)
}

/// Pixels of the table's green cloth.
pub fn cloth_pixels(img: &Image) -> usize {
    img.rgba
        .chunks(4)
        .filter(|p| p[1] > 70 && p[1] > p[0] + 40 && p[1] > p[2] + 25)
        .count()
}
