//! `lightcone render SCENE --at T --observer NAME -o out.png [--size WxH]
//! [--view seen|truth]`: a headless image of what an observer sees.

use std::path::Path;
use std::process::ExitCode;

use lightcone_engine::scene;

use lightcone_render::frame::ViewKind;
use lightcone_render::{gpu, headless};

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

/// Renders and writes the PNG.
pub fn run(
    path: &Path,
    at: f64,
    observer: Option<&str>,
    out: &Path,
    size: &str,
    view: ViewKind,
) -> ExitCode {
    let fail = |msg: String| {
        crate::errln!("{msg}");
        ExitCode::FAILURE
    };
    if !at.is_finite() {
        return fail(format!("--at {at}: give a finite board time in seconds"));
    }
    let (width, height) = match parse_size(size) {
        Ok(s) => s,
        Err(e) => return fail(e),
    };
    if let Err(e) = crate::output::not_the_input(out, path) {
        return fail(e);
    }
    let scene = match scene::load(path) {
        Ok(s) => s,
        Err(e) => return fail(e.to_string()),
    };
    let index = match observer_index(&scene, path, observer) {
        Ok(i) => i,
        Err(e) => return fail(e),
    };
    let gpu = match gpu::headless() {
        Ok(g) => g,
        Err(e) => return fail(e),
    };
    match headless::render_scene(&gpu, &scene, at, index, view, width, height)
        .and_then(|img| img.save_png(out))
    {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => fail(e),
    }
}

/// Index of the observer `name` in `scene` (the first when `None`), or a
/// message naming the file and the observers it has.
pub fn observer_index(
    scene: &lightcone_engine::scene::Scene,
    path: &Path,
    name: Option<&str>,
) -> Result<usize, String> {
    let Some(name) = name else {
        return Ok(0);
    };
    scene
        .observers
        .iter()
        .position(|o| o.name == name)
        .ok_or_else(|| {
            let names: Vec<_> = scene.observers.iter().map(|o| o.name.as_str()).collect();
            format!(
                "{}: no observer named \"{name}\"; the scene has: {}",
                path.display(),
                names.join(", ")
            )
        })
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
