//! Checks of command-line values, run by clap while it parses: a value
//! that cannot be meant (not finite, a request that could not finish, a
//! file of the wrong kind) is a usage error, exit 2, with a message that
//! says what would be right. Negative numbers are parsed as numbers (never
//! as options) and refused here where they make no sense.

use std::path::PathBuf;

use lightcone_engine::scene::Effects;

/// Largest board time any command accepts, s (about 32 years): the
/// physics keeps its digits there at every scene the engine holds, and a
/// run to it ends.
pub const MAX_TIME: f64 = 1e9;

fn number(text: &str) -> Result<f64, String> {
    text.trim()
        .parse::<f64>()
        .map_err(|_| format!("`{text}` is not a number"))
}

/// A board time from −[`MAX_TIME`] to [`MAX_TIME`] seconds.
pub fn time(text: &str) -> Result<f64, String> {
    let t = number(text)?;
    if t.is_finite() && t.abs() <= MAX_TIME {
        Ok(t)
    } else {
        Err(format!(
            "give a finite board time in seconds, from -{MAX_TIME:e} to {MAX_TIME:e}"
        ))
    }
}

/// A board time from 0 to [`MAX_TIME`] seconds.
pub fn time_from_zero(text: &str) -> Result<f64, String> {
    let t = number(text)?;
    if t.is_finite() && (0.0..=MAX_TIME).contains(&t) {
        Ok(t)
    } else {
        Err(format!(
            "give a finite board time in seconds, from 0 to {MAX_TIME:e}"
        ))
    }
}

/// Frames per second for `lesson`: 1 to 1000.
pub fn fps(text: &str) -> Result<f64, String> {
    let f = number(text)?;
    if (1.0..=1000.0).contains(&f) {
        Ok(f)
    } else {
        Err("give a frame rate from 1 to 1000 frames per second".to_owned())
    }
}

/// A hook time limit: more than 0, at most a day.
pub fn hook_limit(text: &str) -> Result<f64, String> {
    let s = number(text)?;
    if s.is_finite() && s > 0.0 && s <= 86_400.0 {
        Ok(s)
    } else {
        Err("give seconds in (0, 86400]".to_owned())
    }
}

/// An image scale in (0, 4].
pub fn scale(text: &str) -> Result<f64, String> {
    let s = number(text)?;
    if s.is_finite() && s > 0.0 && s <= 4.0 {
        Ok(s)
    } else {
        Err("give a number in (0, 4]".to_owned())
    }
}

/// `WIDTHxHEIGHT` of a picture drawn on the GPU, checked (the text is
/// kept).
pub fn size(text: &str) -> Result<String, String> {
    super::render::parse_size(text).map(|_| text.to_owned())
}

/// `WIDTHxHEIGHT` of a diagram (drawn on the CPU), checked (the text is
/// kept).
pub fn sides(text: &str) -> Result<String, String> {
    super::render::parse_sides(text).map(|_| text.to_owned())
}

/// `x,y,z`, checked (the text is kept).
pub fn head(text: &str) -> Result<String, String> {
    super::cave::parse_head(text).map(|_| text.to_owned())
}

/// An `--effects` list, checked (the text is kept).
pub fn effects(text: &str) -> Result<String, String> {
    super::observe::parse_effects(text, Effects::default()).map(|_| text.to_owned())
}

/// An output picture, written as PNG: a `.png` file, or a name with no
/// extension (`/dev/stdout`); another extension is refused (`-o r.jpg`
/// was written as a PNG named .jpg).
pub fn png_file(text: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(text);
    if path
        .extension()
        .is_none_or(|e| e.eq_ignore_ascii_case("png"))
    {
        Ok(path)
    } else {
        Err(format!(
            "the picture is written as PNG: give a file name ending in .png, not `{text}`"
        ))
    }
}

/// A lesson: a `.py` file.
pub fn lesson_file(text: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(text);
    if path.extension().is_some_and(|e| e == "py") {
        Ok(path)
    } else if path.extension().is_some_and(|e| e == "toml") {
        Err(format!(
            "a lesson is a .py file; `{text}` looks like a scene: try `lightcone play {text}`"
        ))
    } else {
        Err(format!("a lesson is a .py file, not `{text}`"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_with_no_end_are_refused() {
        for bad in ["nan", "inf", "-inf", "1e20", "1e308", "1e9000"] {
            assert!(time(bad).is_err(), "{bad}");
            assert!(time_from_zero(bad).is_err(), "{bad}");
        }
        assert_eq!(time("-1.5"), Ok(-1.5));
        assert!(time_from_zero("-1").is_err());
        assert_eq!(time_from_zero("1e9"), Ok(1e9));
        for bad in ["1e-300", "0", "-30", "nan", "1e6"] {
            assert!(fps(bad).is_err(), "{bad}");
        }
        assert!(lesson_file("scene.toml").unwrap_err().contains(".py file"));
        assert!(lesson_file("lesson.py").is_ok());
        assert!(png_file("r.jpg").unwrap_err().contains(".png"));
        assert!(png_file("r.gif").is_err());
        assert!(png_file("/dev/full").is_ok());
        assert!(png_file("dir/R.PNG").is_ok());
    }
}
