//! `lightcone record SCENE|LESSON.py --until T [--fps F] [--size WxH]
//! [--observer NAME] [--view seen|truth|split | --views LIST] [--effects
//! LIST] [--top] [--no-overlays] -o out.gif|out.mp4|DIR/`: the game's
//! pictures from board time 0 to `T`, frame after frame, with the window's
//! overlays, drawn as `lightcone render` draws one
//! ([`crate::play::slide`]), for a teacher's slides.
//!
//! The output is chosen by `-o`: a `.gif` (the `gif` crate: each frame
//! quantised to its own 256-colour palette, looping), an `.mp4` (the frames
//! piped as raw RGBA into `ffmpeg`, which must be installed: H.264 or
//! whatever its default MP4 encoder is, yuv420p), or a directory (a path
//! ending in `/`, or an existing directory): `frame_00000.png`, … .

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};

use lightcone_render::headless::Image;

use crate::play::slide::Slide;

/// Most frames one recording makes (`--until` × `--fps`): a recording
/// must end on a desk (100 000 frames at 1280×720 are 370 GB of pixels).
pub const MAX_FRAMES: f64 = 100_000.0;

/// Where the frames go.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Output {
    /// An animated GIF.
    Gif(PathBuf),
    /// An MP4 video, encoded by ffmpeg.
    Mp4(PathBuf),
    /// A PNG per frame in this directory.
    Pngs(PathBuf),
}

/// Reads `-o`: `.gif`, `.mp4`, or a directory (ending in `/`, or existing).
/// For clap: anything else is a usage error.
pub fn output(text: &str) -> Result<Output, String> {
    let path = PathBuf::from(text);
    if text.ends_with('/') || path.is_dir() {
        return Ok(Output::Pngs(path));
    }
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
    {
        Some(e) if e == "gif" => Ok(Output::Gif(path)),
        Some(e) if e == "mp4" => Ok(Output::Mp4(path)),
        _ => Err(
            "give a .gif or .mp4 file, or a directory ending in / for a PNG sequence".to_owned(),
        ),
    }
}

/// Frames per second: 1 to 120.
pub fn fps(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(f) if (1.0..=120.0).contains(&f) => Ok(f),
        _ => Err("give a frame rate from 1 to 120 frames per second".to_owned()),
    }
}

/// What `record` was asked for.
pub struct Request<'a> {
    /// The scene file.
    pub scene: &'a Path,
    /// Last board time, s.
    pub until: f64,
    /// Frames per board second.
    pub fps: f64,
    /// `WxH`.
    pub size: &'a str,
    /// How the pictures look (and the observer looked through).
    pub looks: super::looks::Looks,
    /// With the window's overlays or bare.
    pub overlays: crate::play::slide::Overlays,
    /// Where to.
    pub out: Output,
}

/// A sink for frames.
enum Sink {
    Gif(gif::Encoder<std::io::BufWriter<std::fs::File>>, u16),
    Mp4(std::process::Child, PathBuf),
    Pngs(PathBuf, usize),
}

fn cannot_write(path: &Path, e: impl std::fmt::Display) -> String {
    format!("{}: cannot write: {e}", path.display())
}

impl Sink {
    fn open(out: &Output, width: u32, height: u32, fps: f64) -> Result<Self, String> {
        match out {
            Output::Gif(path) => {
                let (w, h) = (
                    u16::try_from(width).map_err(|_| "GIF frames are at most 65535 px wide")?,
                    u16::try_from(height).map_err(|_| "GIF frames are at most 65535 px high")?,
                );
                let file = std::fs::File::create(path).map_err(|e| cannot_write(path, e))?;
                let mut enc = gif::Encoder::new(std::io::BufWriter::new(file), w, h, &[])
                    .map_err(|e| cannot_write(path, e))?;
                enc.set_repeat(gif::Repeat::Infinite)
                    .map_err(|e| cannot_write(path, e))?;
                // GIF delays are in hundredths of a second.
                let delay = (100.0 / fps).round().clamp(1.0, 65535.0) as u16;
                Ok(Self::Gif(enc, delay))
            }
            Output::Mp4(path) => {
                let child = Command::new("ffmpeg")
                    .args(["-hide_banner", "-loglevel", "error", "-y"])
                    .args(["-f", "rawvideo", "-pix_fmt", "rgba"])
                    .args(["-s", &format!("{width}x{height}")])
                    .args(["-r", &fps.to_string()])
                    .args(["-i", "-"])
                    // yuv420p (what players expect) needs even sides.
                    .args(["-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"])
                    .args(["-pix_fmt", "yuv420p"])
                    .arg(path)
                    .stdin(Stdio::piped())
                    .stdout(Stdio::null())
                    .stderr(Stdio::inherit())
                    .spawn()
                    .map_err(|e| {
                        if e.kind() == std::io::ErrorKind::NotFound {
                            format!(
                                "{}: writing .mp4 needs ffmpeg, which is not installed (on PATH): \
                                 install it (apt-get install ffmpeg), or record to a .gif or a directory/",
                                path.display()
                            )
                        } else {
                            format!("{}: cannot start ffmpeg: {e}", path.display())
                        }
                    })?;
                Ok(Self::Mp4(child, path.clone()))
            }
            Output::Pngs(dir) => {
                std::fs::create_dir_all(dir).map_err(|e| cannot_write(dir, e))?;
                Ok(Self::Pngs(dir.clone(), 0))
            }
        }
    }

    fn push(&mut self, image: &mut Image) -> Result<(), String> {
        match self {
            Self::Gif(enc, delay) => {
                // Speed 10: gif's default trade-off of palette quality
                // against time (1 is best and slowest, 30 fastest).
                let mut f = gif::Frame::from_rgba_speed(
                    image.width as u16,
                    image.height as u16,
                    &mut image.rgba,
                    10,
                );
                f.delay = *delay;
                enc.write_frame(&f)
                    .map_err(|e| format!("GIF: cannot write: {e}"))
            }
            Self::Mp4(child, path) => {
                let stdin = child
                    .stdin
                    .as_mut()
                    .ok_or_else(|| format!("{}: ffmpeg's input is closed", path.display()))?;
                stdin
                    .write_all(&image.rgba)
                    .map_err(|e| format!("{}: ffmpeg stopped taking frames: {e}", path.display()))
            }
            Self::Pngs(dir, n) => {
                let path = dir.join(format!("frame_{:05}.png", *n));
                *n += 1;
                image.save_png(&path)
            }
        }
    }

    fn finish(self) -> Result<(), String> {
        match self {
            Self::Gif(enc, _) => {
                let mut w = enc
                    .into_inner()
                    .map_err(|e| format!("GIF: cannot write: {e}"))?;
                w.flush().map_err(|e| format!("GIF: cannot write: {e}"))
            }
            Self::Mp4(mut child, path) => {
                drop(child.stdin.take());
                let status = child
                    .wait()
                    .map_err(|e| format!("{}: ffmpeg: {e}", path.display()))?;
                if status.success() {
                    Ok(())
                } else {
                    Err(format!(
                        "{}: ffmpeg failed ({status}); its message is above",
                        path.display()
                    ))
                }
            }
            Self::Pngs(..) => Ok(()),
        }
    }
}

/// Records; exit 0, 1 (bad scene, unknown observer, a failed write, no
/// graphics adapter, no ffmpeg for .mp4) or 2 (more than [`MAX_FRAMES`]).
pub fn run(req: Request<'_>) -> ExitCode {
    let fail = |msg: String| {
        crate::errln!("{msg}");
        ExitCode::FAILURE
    };
    let count = (req.until * req.fps + 1e-9).floor() + 1.0;
    if !(count.is_finite() && count <= MAX_FRAMES) {
        crate::errln!(
            "error: --until {} at --fps {} makes {count:e} frames: record at most {MAX_FRAMES:e} (a shorter time or a lower rate)",
            req.until,
            req.fps
        );
        return ExitCode::from(2);
    }
    let count = count as u64;
    let (width, height) = match super::render::parse_size(req.size) {
        Ok(s) => s,
        Err(e) => return fail(e),
    };
    let (Output::Gif(file) | Output::Mp4(file) | Output::Pngs(file)) = &req.out;
    if let Err(e) = crate::output::not_the_input(file, req.scene) {
        return fail(e);
    }
    let (mut game, mut lesson) = match super::looks::open_at(req.scene, req.looks, 0.0) {
        Ok(g) => g,
        Err(e) => return fail(e),
    };
    let gpu = match lightcone_render::gpu::headless() {
        Ok(g) => g,
        Err(e) => return fail(e),
    };
    let mut sink = match Sink::open(&req.out, width, height, req.fps) {
        Ok(s) => s,
        Err(e) => return fail(e),
    };
    // The window's pictures and overlays, frame after frame.
    let mut slide = Slide::new(&gpu, width, height);
    let progress = crate::progress::steps(count, "record");
    for k in 0..count {
        let t = k as f64 / req.fps;
        progress.step(&format!("t = {t:.3} s"));
        let moved = super::looks::go_to(&mut game, lesson.as_mut(), req.scene, t);
        let pushed = moved
            .and_then(|()| slide.draw(&gpu, &mut game, req.overlays))
            .and_then(|mut image| sink.push(&mut image));
        if let Err(e) = pushed {
            progress.finish();
            return fail(e);
        }
        progress.inc();
    }
    progress.finish();
    super::looks::say_if_failed(lesson.as_ref(), req.scene);
    match sink.finish() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => fail(e),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn output_kind_follows_the_name() {
        assert_eq!(output("a.gif"), Ok(Output::Gif("a.gif".into())));
        assert_eq!(output("b.MP4"), Ok(Output::Mp4("b.MP4".into())));
        assert_eq!(output("frames/"), Ok(Output::Pngs("frames/".into())));
        assert!(output("movie.avi").unwrap_err().contains(".gif or .mp4"));
        assert!(output("noext").is_err());
        assert!(fps("0").is_err() && fps("nan").is_err() && fps("121").is_err());
        assert_eq!(fps("25"), Ok(25.0));
    }
}
