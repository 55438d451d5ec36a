//! `lightcone link SCENE.toml [--base URL]`: the link that opens a scene
//! file in the browser build (`#scene=…`, see [`crate::links`]), for a
//! teacher to share. The scene is checked first, as `lightcone check`
//! does, so a broken file is never shared.

use std::path::Path;
use std::process::ExitCode;

use lightcone_engine::scene;

use crate::links;
use crate::output;

/// Where the README serves the browser build (`python3 -m http.server -d
/// web/dist`).
pub const DEFAULT_BASE: &str = "http://localhost:8000/";

/// Prints the link of `path` under `base`. Exit 1 with `check`'s located
/// errors for a bad scene, a message for a lesson (the browser build does
/// not run lessons yet) or a file too large for a link.
pub fn run(path: &Path, base: &str) -> ExitCode {
    match link(path, base) {
        Ok(link) => match output::print(&format!("{link}\n")) {
            Ok(()) => ExitCode::SUCCESS,
            Err(stop) => stop.exit(),
        },
        Err(e) => {
            crate::errln!("{e}");
            ExitCode::FAILURE
        }
    }
}

/// The link, or why there is none.
fn link(path: &Path, base: &str) -> Result<String, String> {
    let name = path.display().to_string();
    if links::Kind::of_file(&name) == links::Kind::Lesson {
        return Err(format!(
            "{name}: a lesson: the browser build does not run lessons yet; share the file (`lightcone play {name}`)"
        ));
    }
    if !base.starts_with("http://") && !base.starts_with("https://") && !base.starts_with("file://")
    {
        return Err(format!(
            "--base {base}: not the address of a page (http://, https:// or file://)"
        ));
    }
    // `scene::load` bounds the file's size and locates its errors.
    scene::load(path).map_err(|e| e.to_string())?;
    let text = std::fs::read_to_string(path).map_err(|e| format!("{name}: {e}"))?;
    if text.len() > links::MAX_TEXT {
        return Err(format!(
            "{name}: {} bytes, more than the {} a link may carry",
            text.len(),
            links::MAX_TEXT
        ));
    }
    Ok(links::file_link(base, &name, &text))
}
