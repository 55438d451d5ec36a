//! `lightcone render SCENE|LESSON.py --at T [--observer NAME] -o out.png
//! [--size WxH] [--view seen|truth|split | --views LIST] [--effects LIST]
//! [--top] [--no-overlays]`: a headless image of the game's pictures, with
//! the window's overlays, drawn by the window's own code
//! ([`crate::play::slide`]).

use std::path::Path;
use std::process::ExitCode;

use lightcone_render::gpu;

use super::looks::{Looks, open_at, say_if_failed};
use crate::play::slide::{Overlays, Slide};

/// Parses `WxH` for a picture drawn on the GPU (`render`, `record`): each
/// side from 1 to 16 384 px and the readback within wgpu's buffer.
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = parse_sides(s)?;
    // The picture is read back in one buffer, rows padded to 256 bytes
    // (64 pixels), which wgpu caps at 256 MiB.
    if u64::from(w.next_multiple_of(64)) * 4 * u64::from(h) > MAX_READBACK {
        return Err(format!(
            "--size {s}: at most 67 108 864 pixels in all, counting the width rounded up \
             to a multiple of 64 (e.g. 8192x8192 or 16384x4096): the picture is read back \
             in one buffer of at most 256 MiB"
        ));
    }
    Ok((w, h))
}

/// Parses `WxH` with each side from 1 to 16 384 px (`diagram`, drawn on
/// the CPU).
pub fn parse_sides(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("--size {s}: give WIDTHxHEIGHT, e.g. 1280x720"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<u32>()
            .ok()
            .filter(|n| (1..=16384).contains(n))
    };
    match (parse(w), parse(h)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => Err(format!(
            "--size {s}: width and height must be whole numbers from 1 to 16384"
        )),
    }
}

/// wgpu's largest buffer by default, bytes: the readback of a picture.
const MAX_READBACK: u64 = 1 << 28;

/// What `render` was asked for.
pub struct Request<'a> {
    /// The scene file (TOML) or lesson (`.py`).
    pub path: &'a Path,
    /// Board time, s.
    pub at: f64,
    /// The PNG to write.
    pub out: &'a Path,
    /// `WxH`.
    pub size: &'a str,
    /// How the pictures look.
    pub looks: Looks,
    /// With the window's overlays or bare.
    pub overlays: Overlays,
}

/// Renders and writes the PNG; exit 0, or 1 with a message (a bad scene,
/// lesson, observer or list, no graphics adapter, a failed write).
pub fn run(req: Request<'_>) -> ExitCode {
    match render(req) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            crate::errln!("{e}");
            ExitCode::FAILURE
        }
    }
}

fn render(req: Request<'_>) -> Result<(), String> {
    if !req.at.is_finite() {
        return Err(format!(
            "--at {}: give a finite board time in seconds",
            req.at
        ));
    }
    let (width, height) = parse_size(req.size)?;
    crate::output::not_the_input(req.out, req.path)?;
    let sidecar = layout_path(req.out)?;
    if let Some(sidecar) = &sidecar {
        crate::output::not_the_input(sidecar, req.path)?;
    }
    // The lesson's process (if any) ends with its host, after the picture.
    let (mut game, lesson) = open_at(req.path, req.looks, req.at)?;
    let gpu = gpu::headless()?;
    let mut slide = Slide::new(&gpu, width, height);
    slide
        .draw(&gpu, &mut game, req.overlays)?
        .save_png(req.out)?;
    // Beside the picture, where its views, pucks and labels are, as
    // `play --screenshot` writes it.
    let size = (width as f32, height as f32);
    let drawn = slide.drawn();
    if let Some(sidecar) = &sidecar {
        crate::play::screenshot::save_layout(
            &game,
            None,
            slide.area(),
            None,
            sidecar,
            size,
            &drawn,
        )
        .map_err(|e| format!("the layout beside the picture: {e}"))?;
    }
    say_if_failed(lesson.as_ref(), req.path);
    Ok(())
}

/// Where the layout sidecar of a picture written to `out` goes: `out`
/// with the extension `.json`, or `None` when `out` is not a file (a
/// picture sent to `/dev/null` or a pipe has no layout beside it). A
/// sidecar path taken by a directory is refused before anything is drawn.
fn layout_path(out: &Path) -> Result<Option<std::path::PathBuf>, String> {
    if std::fs::metadata(out).is_ok_and(|m| !m.is_file()) {
        return Ok(None);
    }
    let sidecar = out.with_extension("json");
    if sidecar.is_dir() {
        return Err(format!(
            "{}: is a directory; `render` writes the picture's layout there (beside {}): choose another -o",
            sidecar.display(),
            out.display()
        ));
    }
    Ok(Some(sidecar))
}

#[cfg(test)]
mod tests {
    use super::{parse_sides, parse_size};

    /// Sizes the readback buffer can hold are taken, larger ones refused
    /// with a message (they once panicked inside wgpu).
    #[test]
    fn a_size_beyond_the_readback_buffer_is_refused() {
        assert_eq!(parse_size("8192x8192"), Ok((8192, 8192)));
        assert_eq!(parse_size("16384x4096"), Ok((16384, 4096)));
        for big in ["16384x16384", "12000x9000", "16384x4097"] {
            let e = parse_size(big).expect_err(big);
            assert!(e.contains("67 108 864 pixels"), "{e}");
        }
        assert!(parse_size("0x10").is_err());
        // 8193 px rows are padded to 8256: 8193x8191 is under 2^26 pixels
        // but not its readback.
        assert!(parse_size("8193x8191").is_err());
        // The diagram is drawn on the CPU: sides only.
        assert_eq!(parse_sides("16384x8192"), Ok((16384, 8192)));
        assert!(parse_sides("16385x10").is_err());
    }
}
