//! The default scene and CAVE description, built into the binary so that
//! `lightcone play`, `check` and `cave` work from any folder (and after
//! `cargo install`), not only from the checkout.

use lightcone_engine::scene::{self, Scene, SceneErrors};
use lightcone_tracker::cave::CaveConfig;

/// The text of `assets/scenes/paper_carom.toml`, the default scene.
pub const DEFAULT_SCENE_TOML: &str = include_str!("../../assets/scenes/paper_carom.toml");

/// The name the built-in scene goes by in messages and summaries.
pub const DEFAULT_SCENE_NAME: &str = "(built in) paper_carom.toml";

/// Every shipped scene (`assets/scenes/*.toml`), built in: the window's
/// scene menu offers them. A test checks that the list matches the folder.
pub const SCENES: &[(&str, &str)] = &[
    ("paper_carom.toml", DEFAULT_SCENE_TOML),
    (
        "parallel_tracks.toml",
        include_str!("../../assets/scenes/parallel_tracks.toml"),
    ),
    (
        "ten_pucks.toml",
        include_str!("../../assets/scenes/ten_pucks.toml"),
    ),
    (
        "cushion_095.toml",
        include_str!("../../assets/scenes/cushion_095.toml"),
    ),
    (
        "simultaneity.toml",
        include_str!("../../assets/scenes/simultaneity.toml"),
    ),
    (
        "newton.toml",
        include_str!("../../assets/scenes/newton.toml"),
    ),
    ("ultra.toml", include_str!("../../assets/scenes/ultra.toml")),
    (
        "contraction.toml",
        include_str!("../../assets/scenes/contraction.toml"),
    ),
    ("flyby.toml", include_str!("../../assets/scenes/flyby.toml")),
    (
        "wigner_box.toml",
        include_str!("../../assets/scenes/wigner_box.toml"),
    ),
];

/// Every shipped lesson (`scripts/lessons/*.py`), built in: the window's
/// scene menu offers them (it writes the chosen one to a private temporary
/// folder and runs it as `lightcone play LESSON.py` would). A test checks
/// that the list matches the folder.
pub const LESSONS: &[(&str, &str)] = &[
    (
        "aberration.py",
        include_str!("../../scripts/lessons/aberration.py"),
    ),
    (
        "approach_recede.py",
        include_str!("../../scripts/lessons/approach_recede.py"),
    ),
    ("clocks.py", include_str!("../../scripts/lessons/clocks.py")),
    (
        "collision_angle.py",
        include_str!("../../scripts/lessons/collision_angle.py"),
    ),
    (
        "contraction.py",
        include_str!("../../scripts/lessons/contraction.py"),
    ),
    (
        "cushion.py",
        include_str!("../../scripts/lessons/cushion.py"),
    ),
    (
        "friction.py",
        include_str!("../../scripts/lessons/friction.py"),
    ),
    ("gas.py", include_str!("../../scripts/lessons/gas.py")),
    (
        "relative_simultaneity.py",
        include_str!("../../scripts/lessons/relative_simultaneity.py"),
    ),
    (
        "simultaneity.py",
        include_str!("../../scripts/lessons/simultaneity.py"),
    ),
    (
        "wigner_rotation.py",
        include_str!("../../scripts/lessons/wigner_rotation.py"),
    ),
];

/// A shipped lesson's title: the first line of its docstring (empty when
/// it has none).
pub fn lesson_title(text: &str) -> &str {
    text.trim_start()
        .strip_prefix("\"\"\"")
        .and_then(|s| s.lines().next())
        .map_or("", |l| {
            l.trim().trim_end_matches("\"\"\"").trim_end_matches('.')
        })
}

/// The built-in scene `name` (a file name of [`SCENES`]).
pub fn shipped_scene(name: &str) -> Option<Result<Scene, SceneErrors>> {
    SCENES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(n, text)| scene::parse(text, &format!("(built in) {n}")))
}

/// The built-in scene at `path` (`assets/scenes/NAME.toml`, as the
/// checkout names it), so that `lightcone bench` runs from any folder;
/// errors name the scene.
pub fn shipped_at(path: &str) -> Result<Scene, String> {
    let name = path.trim_start_matches("assets/scenes/");
    match shipped_scene(name) {
        Some(scene) => scene.map_err(|e| e.to_string()),
        None => Err(format!("{path}: not a shipped scene")),
    }
}

/// The text of `assets/cave.toml`, the default CAVE.
pub const DEFAULT_CAVE_TOML: &str = include_str!("../../assets/cave.toml");

/// The default scene (the paper's carom shot).
pub fn default_scene() -> Result<Scene, SceneErrors> {
    scene::parse(DEFAULT_SCENE_TOML, DEFAULT_SCENE_NAME)
}

/// The default CAVE (three walls and a floor, see `assets/cave.toml`).
pub fn default_cave() -> Result<CaveConfig, String> {
    CaveConfig::from_toml_str(DEFAULT_CAVE_TOML).map_err(|e| format!("(built in) cave.toml: {e}"))
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_built_in_assets_are_valid() {
        assert!(super::default_scene().is_ok());
        assert!(super::default_cave().is_ok());
    }

    #[test]
    fn every_shipped_lesson_is_built_in() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scripts/lessons");
        let mut files: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".py"))
            .collect();
        files.sort();
        let built_in: Vec<String> = super::LESSONS.iter().map(|(n, _)| n.to_string()).collect();
        assert_eq!(
            files, built_in,
            "assets.rs LESSONS must list scripts/lessons, sorted"
        );
        let approach = super::LESSONS
            .iter()
            .find(|(n, _)| *n == "approach_recede.py")
            .unwrap();
        assert_eq!(
            super::lesson_title(approach.1),
            "Apparent acceleration and deceleration (the paper's §4.3)"
        );
        assert_eq!(super::lesson_title("x = 1\n"), "");
    }

    #[test]
    fn every_shipped_scene_is_built_in_and_valid() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes");
        let mut files: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".toml"))
            .collect();
        files.sort();
        let mut built_in: Vec<String> = super::SCENES.iter().map(|(n, _)| n.to_string()).collect();
        built_in.sort();
        assert_eq!(files, built_in, "assets.rs SCENES must list assets/scenes");
        for (name, _) in super::SCENES {
            let scene = super::shipped_scene(name).unwrap();
            assert!(
                scene.is_ok(),
                "{name}: {:?}",
                scene.err().map(|e| e.to_string())
            );
        }
    }
}
