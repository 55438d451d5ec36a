//! `lightcone link FILE [--base URL]`: the link that opens a scene file
//! (`#scene=…`) or a lesson (`#lesson=…`) in the browser build (see
//! [`crate::links`]), for a teacher to share. The file is checked first: a
//! scene as `lightcone check` does, a lesson for Python syntax, so a broken
//! file is never shared.

use std::io::Read as _;
use std::path::Path;
use std::process::ExitCode;

use lightcone_engine::scene;

use crate::links;
use crate::output;

/// Where the README serves the browser build (`python3 -m http.server -d
/// web/dist`).
pub const DEFAULT_BASE: &str = "http://localhost:8000/";

/// Prints the link of `path` under `base`. Exit 1 with `check`'s located
/// errors for a bad scene, the syntax error of a lesson that does not
/// compile, a file too large for a link, or a base that is not a web
/// address.
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
    let page = ["http://", "https://", "file://"]
        .iter()
        .find_map(|scheme| base.strip_prefix(scheme));
    if !page.is_some_and(|rest| !rest.is_empty() && !rest.contains(char::is_whitespace))
        || base.contains(['?', '#'])
    {
        return Err(format!(
            "--base {base}: not the address of a page (http://, https:// or file://, no spaces, no ? or #)"
        ));
    }
    // Read once, and no more than a link carries (a pipe can be read only
    // once; a file may change between two reads).
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(links::MAX_TEXT as u64 + 1).read_to_end(&mut bytes))
        .map_err(|e| format!("{name}: cannot read: {e}"))?;
    if bytes.len() > links::MAX_TEXT {
        return Err(format!(
            "{name}: more than the {} MiB a link may carry",
            links::MAX_TEXT >> 20
        ));
    }
    let text = scene::utf8(&bytes, &name).map_err(|e| e.to_string())?;
    if links::Kind::of_file(&name) == links::Kind::Lesson {
        crate::lesson::check_syntax(&name, text)?;
    } else {
        // Checked as `lightcone check` checks it, errors located.
        scene::parse(text, &name).map_err(|e| e.to_string())?;
    }
    Ok(links::file_link(base, &name, text))
}
