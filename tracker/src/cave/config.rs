//! The CAVE file (TOML): its walls, video outputs and the tracker's
//! placement, validated, each error naming its field.
//!
//! # Config format (TOML)
//!
//! ```toml
//! # Interocular distance in metres (optional, default 0.064).
//! eye_separation = 0.064
//!
//! # How tracker space sits in board space (optional table; defaults shown).
//! [tracker]
//! origin = [0.0, 0.0, 0.0]  # board-space position of the tracker origin
//! yaw_deg = 0.0             # rotation about board +z, degrees
//! scale = 1.0               # board units per tracker metre
//! up_axis = "y"             # tracker axis that points up: "y" or "z"
//!
//! # One table per projection surface, corners in tracker space (metres),
//! # as seen by a viewer standing inside the CAVE.
//! [[wall]]
//! name = "front"
//! lower_left  = [-1.5, 0.0, -1.5]
//! lower_right = [ 1.5, 0.0, -1.5]
//! upper_left  = [-1.5, 2.5, -1.5]
//! pixels = [1920, 1600]     # projector resolution, width x height
//!
//! # Optional: one table per video output (projector) the game drives with
//! # a borderless window of its own. A wall no output names is drawn tiled
//! # in the main window (the desktop preview).
//! [[output]]
//! name = "front-left"       # optional, default "<wall>" or "<wall>-<eye>"
//! wall = "front"
//! eye = "left"              # "mono" (default: between the eyes), "left",
//!                           # "right", or both eyes in one output:
//!                           # "side-by-side" (left eye left) or
//!                           # "top-bottom" (left eye on top)
//! monitor = "DP-1"          # full screen on this monitor, or instead
//! # region = [0, 0, 1920, 1600]  # x, y, width, height in desktop pixels
//! ```
//!
//! Walls must be rectangles (edges at 90° within 0.5°) with non-zero size;
//! names must be unique. Unknown keys are errors (typos would otherwise be
//! silently ignored). Every error names the offending field, e.g.
//! ``wall[2] ("floor").upper_left: must be finite``.
//!
//! The file `cave.toml` at the crate root describes a 3 m × 3 m × 2.5 m CAVE
//! with front, left and right walls and a floor.

use glam::{DMat4, DQuat, DVec3};
use serde::Deserialize;
use std::path::Path;
use thiserror::Error;

use super::board::{TrackerToBoard, UpAxis};
use super::projection::{DEFAULT_EYE_SEPARATION, ProjectionError, Wall, stereo_eyes};

/// Largest allowed deviation of a wall's corner angle from 90°, radians.
const RECTANGLE_TOLERANCE_RAD: f64 = 0.5 * std::f64::consts::PI / 180.0;

/// Errors loading or validating a CAVE config.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CaveConfigError {
    /// The file could not be read.
    #[error("cannot read CAVE config {path}: {message}")]
    Io {
        /// Path given.
        path: String,
        /// OS error.
        message: String,
    },
    /// TOML syntax or type error; toml's message names the key and line.
    #[error("CAVE config: {0}")]
    Toml(String),
    /// A value parsed but is not acceptable.
    #[error("CAVE config: {field}: {message}")]
    Field {
        /// Dotted path of the field, e.g. `wall[1] ("left").pixels`.
        field: String,
        /// What is wrong.
        message: String,
    },
}

/// A validated CAVE description.
#[derive(Debug, Clone, PartialEq)]
pub struct CaveConfig {
    /// Interocular distance, metres.
    pub eye_separation: f64,
    /// Tracker → board placement.
    pub tracker: TrackerToBoard,
    /// Projection surfaces, in file order.
    pub walls: Vec<Wall>,
    /// Video outputs, each showing one wall in a window of its own, in file
    /// order (none: every wall tiled in the main window).
    pub outputs: Vec<Output>,
    /// The file it was read from ([`Self::from_path`]), for messages; `None`
    /// for a description given as text.
    pub source: Option<std::path::PathBuf>,
}

/// Which eye (or eyes) an output shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputEyes {
    /// Between the eyes (no stereo).
    Mono,
    /// The left eye only (its own projector, or one of a pair).
    Left,
    /// The right eye only.
    Right,
    /// Both, the left eye in the left half.
    SideBySide,
    /// Both, the left eye in the top half.
    TopBottom,
}

impl OutputEyes {
    /// The name in the file.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Mono => "mono",
            Self::Left => "left",
            Self::Right => "right",
            Self::SideBySide => "side-by-side",
            Self::TopBottom => "top-bottom",
        }
    }
}

/// Where an output's window goes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Placement {
    /// Borderless full screen on the monitor of this name (as the window
    /// system names it).
    Monitor(String),
    /// A borderless window over this rectangle of the desktop: x, y (top
    /// left), width, height, pixels.
    Region([i32; 2], [u32; 2]),
}

/// One video output: a wall, an eye or a stereo pair, and a place.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Output {
    /// Unique name (screenshots are saved as `FILE.<name>.png`).
    pub name: String,
    /// Index into [`CaveConfig::walls`].
    pub wall: usize,
    /// Which eyes, and how a stereo pair shares the output.
    pub eyes: OutputEyes,
    /// Where its window goes.
    pub placement: Placement,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCave {
    eye_separation: Option<f64>,
    tracker: Option<RawTracker>,
    #[serde(default)]
    wall: Vec<RawWall>,
    #[serde(default)]
    output: Vec<RawOutput>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawOutput {
    name: Option<String>,
    wall: String,
    eye: Option<String>,
    monitor: Option<String>,
    region: Option<[i64; 4]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTracker {
    origin: Option<[f64; 3]>,
    yaw_deg: Option<f64>,
    scale: Option<f64>,
    up_axis: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawWall {
    name: String,
    lower_left: [f64; 3],
    lower_right: [f64; 3],
    upper_left: [f64; 3],
    pixels: [u32; 2],
}

/// Checks `[[output]]` number `i` against the walls.
fn output(i: usize, o: RawOutput, walls: &[Wall]) -> Result<Output, CaveConfigError> {
    let wall = walls.iter().position(|w| w.name == o.wall).ok_or_else(|| {
        let names: Vec<&str> = walls.iter().map(|w| w.name.as_str()).collect();
        field_err(
            format!("output[{i}].wall"),
            format!(
                "no wall is named {:?} (walls: {})",
                o.wall,
                names.join(", ")
            ),
        )
    })?;
    let eyes = match o.eye.as_deref().unwrap_or("mono") {
        "mono" => OutputEyes::Mono,
        "left" => OutputEyes::Left,
        "right" => OutputEyes::Right,
        "side-by-side" => OutputEyes::SideBySide,
        "top-bottom" => OutputEyes::TopBottom,
        other => {
            return Err(field_err(
                format!("output[{i}].eye"),
                format!(
                    "{other:?} is not \"mono\", \"left\", \"right\", \"side-by-side\" or \"top-bottom\""
                ),
            ));
        }
    };
    let placement = match (o.monitor, o.region) {
        (Some(m), None) if !m.trim().is_empty() => Placement::Monitor(m),
        (Some(_), None) => {
            return Err(field_err(
                format!("output[{i}].monitor"),
                "must not be empty",
            ));
        }
        (None, Some([x, y, w, h])) => {
            let fits = |v: i64| (-65_536..=65_536).contains(&v);
            if !(fits(x) && fits(y) && (1..=16_384).contains(&w) && (1..=16_384).contains(&h)) {
                return Err(field_err(
                    format!("output[{i}].region"),
                    format!(
                        "[{x}, {y}, {w}, {h}] must be x, y within ±65536 and a width and \
                         height from 1 to 16384 pixels"
                    ),
                ));
            }
            Placement::Region([x as i32, y as i32], [w as u32, h as u32])
        }
        (Some(_), Some(_)) => {
            return Err(field_err(
                format!("output[{i}]"),
                "give `monitor` or `region`, not both",
            ));
        }
        (None, None) => {
            return Err(field_err(
                format!("output[{i}]"),
                "needs `monitor = \"NAME\"` or `region = [x, y, width, height]`",
            ));
        }
    };
    let name = match o.name {
        Some(n) if n.trim().is_empty() => {
            return Err(field_err(format!("output[{i}].name"), "must not be empty"));
        }
        Some(n) => n,
        None => match eyes {
            OutputEyes::Mono | OutputEyes::SideBySide | OutputEyes::TopBottom => o.wall,
            OutputEyes::Left | OutputEyes::Right => format!("{}-{}", o.wall, eyes.name()),
        },
    };
    Ok(Output {
        name,
        wall,
        eyes,
        placement,
    })
}

fn field_err(field: impl Into<String>, message: impl Into<String>) -> CaveConfigError {
    CaveConfigError::Field {
        field: field.into(),
        message: message.into(),
    }
}

impl CaveConfig {
    /// Parses and validates TOML text.
    pub fn from_toml_str(text: &str) -> Result<Self, CaveConfigError> {
        let raw: RawCave =
            toml::from_str(text).map_err(|e| CaveConfigError::Toml(e.to_string()))?;

        let eye_separation = raw.eye_separation.unwrap_or(DEFAULT_EYE_SEPARATION);
        if !(eye_separation.is_finite() && (0.0..=0.5).contains(&eye_separation)) {
            return Err(field_err(
                "eye_separation",
                format!("{eye_separation} is not a distance in metres between 0 and 0.5"),
            ));
        }

        let mut tracker = TrackerToBoard::default();
        if let Some(t) = raw.tracker {
            if let Some(o) = t.origin {
                let o = DVec3::from_array(o);
                if !o.is_finite() {
                    return Err(field_err("tracker.origin", "must be finite"));
                }
                tracker.origin = o;
            }
            if let Some(y) = t.yaw_deg {
                if !y.is_finite() {
                    return Err(field_err("tracker.yaw_deg", "must be finite"));
                }
                tracker.yaw_deg = y;
            }
            if let Some(s) = t.scale {
                if !(s.is_finite() && s > 0.0) {
                    return Err(field_err("tracker.scale", format!("{s} must be > 0")));
                }
                tracker.scale = s;
            }
            if let Some(u) = t.up_axis {
                tracker.up_axis = match u.as_str() {
                    "y" | "Y" => UpAxis::Y,
                    "z" | "Z" => UpAxis::Z,
                    other => {
                        return Err(field_err(
                            "tracker.up_axis",
                            format!("{other:?} is not \"y\" or \"z\""),
                        ));
                    }
                };
            }
        }

        if raw.wall.is_empty() {
            return Err(field_err("wall", "at least one [[wall]] table is required"));
        }
        let mut walls: Vec<Wall> = Vec::with_capacity(raw.wall.len());
        for (i, w) in raw.wall.into_iter().enumerate() {
            let label = format!("wall[{i}] ({:?})", w.name);
            if w.name.trim().is_empty() {
                return Err(field_err(format!("wall[{i}].name"), "must not be empty"));
            }
            if walls.iter().any(|o| o.name == w.name) {
                return Err(field_err(format!("{label}.name"), "duplicate wall name"));
            }
            let corner = |name: &str, v: [f64; 3]| {
                let p = DVec3::from_array(v);
                if p.is_finite() {
                    Ok(p)
                } else {
                    Err(field_err(format!("{label}.{name}"), "must be finite"))
                }
            };
            let wall = Wall {
                lower_left: corner("lower_left", w.lower_left)?,
                lower_right: corner("lower_right", w.lower_right)?,
                upper_left: corner("upper_left", w.upper_left)?,
                pixels: w.pixels,
                name: w.name,
            };
            if wall.width() < 1e-6 {
                return Err(field_err(
                    format!("{label}.lower_right"),
                    "coincides with lower_left (zero width)",
                ));
            }
            if wall.height() < 1e-6 {
                return Err(field_err(
                    format!("{label}.upper_left"),
                    "coincides with lower_left (zero height)",
                ));
            }
            let angle = wall.right().angle_between(wall.up());
            let dev = (angle - std::f64::consts::FRAC_PI_2).abs();
            if dev.is_nan() || dev > RECTANGLE_TOLERANCE_RAD {
                return Err(field_err(
                    format!("{label}.upper_left"),
                    format!(
                        "wall is not a rectangle: edges meet at {:.2}° (must be 90° ± 0.5°)",
                        angle.to_degrees()
                    ),
                ));
            }
            if wall.pixels[0] == 0 || wall.pixels[1] == 0 {
                return Err(field_err(
                    format!("{label}.pixels"),
                    "width and height must be > 0",
                ));
            }
            walls.push(wall);
        }
        let outputs = raw
            .output
            .into_iter()
            .enumerate()
            .map(|(i, o)| output(i, o, &walls))
            .collect::<Result<Vec<_>, _>>()?;
        for (i, o) in outputs.iter().enumerate() {
            if outputs[..i].iter().any(|p| p.name == o.name) {
                return Err(field_err(
                    format!("output[{i}].name"),
                    format!("{:?} names two outputs: give each its own `name`", o.name),
                ));
            }
        }
        Ok(Self {
            eye_separation,
            tracker,
            walls,
            outputs,
            source: None,
        })
    }

    /// How messages name this description: its file, or "CAVE config".
    #[must_use]
    pub fn label(&self) -> String {
        self.source
            .as_ref()
            .map_or_else(|| "CAVE config".to_owned(), |p| p.display().to_string())
    }

    /// Indices of the walls no output shows (tiled in the main window).
    #[must_use]
    pub fn unmapped_walls(&self) -> Vec<usize> {
        (0..self.walls.len())
            .filter(|&i| self.outputs.iter().all(|o| o.wall != i))
            .collect()
    }

    /// Reads, parses and validates a TOML file.
    pub fn from_path(path: impl AsRef<Path>) -> Result<Self, CaveConfigError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| CaveConfigError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        let mut cave = Self::from_toml_str(&text)?;
        cave.source = Some(path.to_path_buf());
        Ok(cave)
    }

    /// Looks a wall up by name.
    #[must_use]
    pub fn wall(&self, name: &str) -> Option<&Wall> {
        self.walls.iter().find(|w| w.name == name)
    }

    /// Left and right eyes (tracker space) for a head pose, using
    /// [`CaveConfig::eye_separation`].
    #[must_use]
    pub fn eyes(&self, head_position: DVec3, head_orientation: DQuat) -> (DVec3, DVec3) {
        stereo_eyes(head_position, head_orientation, self.eye_separation)
    }

    /// `projection * view * board→tracker`: takes board-space points to clip
    /// space for `wall` seen from `eye` (tracker space). `near`/`far` are
    /// tracker-space metres.
    pub fn view_projection_board(
        &self,
        wall: &Wall,
        eye: DVec3,
        near: f64,
        far: f64,
    ) -> Result<DMat4, ProjectionError> {
        let p = wall.projection(eye, near, far)?;
        Ok(p.view_projection * self.tracker.inverse_matrix())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cave::{TrackerToBoard, UpAxis};

    const EXAMPLE: &str = include_str!("../../../assets/cave.toml");

    fn example() -> CaveConfig {
        CaveConfig::from_toml_str(EXAMPLE).expect("example config parses")
    }

    #[test]
    fn example_file_parses() {
        let c = example();
        assert_eq!(c.eye_separation, 0.064);
        let names: Vec<&str> = c.walls.iter().map(|w| w.name.as_str()).collect();
        assert_eq!(names, ["front", "left", "right", "floor"]);
        // All normals point into the CAVE (towards its centre).
        let centre = DVec3::new(0.0, 1.25, 0.0);
        for w in &c.walls {
            assert!((centre - w.lower_left).dot(w.normal()) > 0.0, "{}", w.name);
        }
        let front = c.wall("front").expect("front");
        assert_eq!((front.width(), front.height()), (3.0, 2.5));
        assert_eq!(front.upper_right(), DVec3::new(1.5, 2.5, -1.5));
        assert!((front.pixel_aspect() - 1.2).abs() < 1e-12);
        assert!(c.wall("ceiling").is_none());
    }

    #[test]
    fn board_view_projection_equals_tracker_one() {
        let mut c = example();
        c.tracker = TrackerToBoard {
            origin: DVec3::new(1.2, 0.6, 0.0),
            yaw_deg: 30.0,
            scale: 0.5,
            up_axis: UpAxis::Y,
        };
        let w = c.wall("left").expect("left").clone();
        let eye = DVec3::new(0.2, 1.6, 0.1);
        let m_board = c.view_projection_board(&w, eye, 0.1, 10.0).expect("vp");
        let m_tracker = w.projection(eye, 0.1, 10.0).expect("vp").view_projection;
        let p = DVec3::new(-1.0, 1.0, 0.5);
        let a = m_board.project_point3(c.tracker.point(p));
        let b = m_tracker.project_point3(p);
        assert!((a - b).length() < 1e-9);
    }

    #[test]
    fn outputs_map_walls_and_eyes_to_windows() {
        let text = format!(
            "{EXAMPLE}\n[[output]]\nwall = \"front\"\neye = \"left\"\nregion = [0, 0, 960, 800]\n\
             [[output]]\nwall = \"front\"\neye = \"right\"\nregion = [960, 0, 960, 800]\n\
             [[output]]\nname = \"floor projector\"\nwall = \"floor\"\neye = \"top-bottom\"\nmonitor = \"HDMI-2\"\n"
        );
        let c = CaveConfig::from_toml_str(&text).expect("outputs parse");
        let names: Vec<&str> = c.outputs.iter().map(|o| o.name.as_str()).collect();
        assert_eq!(names, ["front-left", "front-right", "floor projector"]);
        assert_eq!(c.outputs[1].eyes, OutputEyes::Right);
        assert_eq!(
            c.outputs[1].placement,
            Placement::Region([960, 0], [960, 800])
        );
        assert_eq!(c.outputs[2].wall, 3);
        assert_eq!(c.outputs[2].placement, Placement::Monitor("HDMI-2".into()));
        // Left and right are unmapped: the main window tiles them.
        assert_eq!(c.unmapped_walls(), [1, 2]);
        assert!(example().outputs.is_empty());
        assert_eq!(example().unmapped_walls(), [0, 1, 2, 3]);
        let bad = |output: &str, field: &str, words: &str| {
            let e = CaveConfig::from_toml_str(&format!("{EXAMPLE}\n[[output]]\n{output}"))
                .expect_err(output)
                .to_string();
            assert!(e.contains(field) && e.contains(words), "{output}: {e}");
        };
        bad(
            "wall = \"ceiling\"\nregion = [0, 0, 10, 10]",
            "output[0].wall",
            "front, left, right, floor",
        );
        bad(
            "wall = \"front\"\neye = \"both\"\nregion = [0, 0, 10, 10]",
            "output[0].eye",
            "side-by-side",
        );
        bad("wall = \"front\"", "output[0]", "needs `monitor");
        bad(
            "wall = \"front\"\nmonitor = \"A\"\nregion = [0, 0, 10, 10]",
            "output[0]",
            "not both",
        );
        bad(
            "wall = \"front\"\nregion = [0, 0, 0, 10]",
            "output[0].region",
            "from 1 to 16384",
        );
        bad(
            "wall = \"front\"\nmonitor = \" \"",
            "output[0].monitor",
            "empty",
        );
        bad(
            "wall = \"front\"\nregion = [0, 0, 10, 10]\nscreen = 1",
            "screen",
            "unknown field",
        );
        bad(
            "wall = \"front\"\nregion = [0, 0, 10, 10]\n[[output]]\nwall = \"front\"\nregion = [0, 0, 10, 10]",
            "output[1].name",
            "names two outputs",
        );
    }

    #[test]
    fn config_errors_name_the_field() {
        let wall = |extra: &str| {
            format!(
                "[[wall]]\nname = \"front\"\nlower_left = [-1.5, 0.0, -1.5]\n\
                 lower_right = [1.5, 0.0, -1.5]\nupper_left = [-1.5, 2.5, -1.5]\n\
                 pixels = [1920, 1600]\n{extra}"
            )
        };
        let cases: Vec<(String, &str)> = vec![
            (
                "eye_separation = -1\n".to_string() + &wall(""),
                "eye_separation",
            ),
            (
                "eye_separation = 0.064\n".to_string(),
                "at least one [[wall]]",
            ),
            (
                "[tracker]\nscale = 0\n".to_string() + &wall(""),
                "tracker.scale",
            ),
            (
                "[tracker]\nup_axis = \"x\"\n".to_string() + &wall(""),
                "tracker.up_axis",
            ),
            (
                "[tracker]\nyaw_deg = nan\n".to_string() + &wall(""),
                "tracker.yaw_deg",
            ),
            (
                "[tracker]\norigin = [inf, 0, 0]\n".to_string() + &wall(""),
                "tracker.origin",
            ),
            (
                wall("").replace("[1920, 1600]", "[0, 1600]"),
                "wall[0] (\"front\").pixels",
            ),
            (
                wall("").replace("[-1.5, 2.5, -1.5]", "[-1.0, 2.5, -1.5]"),
                "wall[0] (\"front\").upper_left: wall is not a rectangle",
            ),
            (
                wall("").replace(
                    "lower_right = [1.5, 0.0, -1.5]",
                    "lower_right = [-1.5, 0.0, -1.5]",
                ),
                "wall[0] (\"front\").lower_right",
            ),
            (
                wall("").replace("[-1.5, 0.0, -1.5]\nlower", "[nan, 0.0, -1.5]\nlower"),
                "wall[0] (\"front\").lower_left: must be finite",
            ),
            (wall("") + &wall(""), "wall[1] (\"front\").name: duplicate"),
            (
                wall("").replace("name = \"front\"", "name = \"\""),
                "wall[0].name",
            ),
            // Type / syntax errors come from toml and quote the key.
            (
                wall("").replace("[-1.5, 0.0, -1.5]\nlower", "[-1.5, 0.0]\nlower"),
                "lower_left",
            ),
            (wall("").replace("pixels = [1920, 1600]", ""), "pixels"),
            (wall("colour = 3\n"), "colour"),
            (wall("").replace("[1920, 1600]", "[-5, 1600]"), "pixels"),
        ];
        for (text, want) in cases {
            let err = CaveConfig::from_toml_str(&text)
                .expect_err(&text)
                .to_string();
            assert!(
                err.contains(want),
                "config:\n{text}\nerror: {err}\nwanted: {want}"
            );
        }
        let err = CaveConfig::from_path("/nonexistent/cave.toml").expect_err("io");
        assert!(err.to_string().contains("/nonexistent/cave.toml"));
    }

    #[test]
    fn defaults_apply() {
        let text = "[[wall]]\nname = \"w\"\nlower_left = [0,0,0]\nlower_right = [1,0,0]\n\
                    upper_left = [0,1,0]\npixels = [10, 10]\n";
        let c = CaveConfig::from_toml_str(text).expect("minimal config");
        assert_eq!(c.eye_separation, DEFAULT_EYE_SEPARATION);
        assert_eq!(c.tracker, TrackerToBoard::default());
    }
}
