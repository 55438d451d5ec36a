//! Scene observers found by name, for every command that takes `--observer`.

use std::path::Path;

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
