//! The scene file as written, with the byte span of every value, so that
//! validation can point at the line that holds a wrong number.

use serde::Deserialize;
use toml::Spanned;

use super::{SceneError, SceneErrors};

/// A value with its place in the file.
pub type At<T> = Spanned<T>;

/// Top level of a scene file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    pub title: Option<String>,
    pub description: Option<String>,
    pub c: Option<At<f64>>,
    pub before_start: Option<At<String>>,
    pub table: Option<RawTable>,
    pub physics: Option<RawPhysics>,
    pub effects: Option<RawEffects>,
    pub optics: Option<RawOptics>,
    #[serde(default)]
    pub puck: Vec<At<RawPuck>>,
    #[serde(default)]
    pub observer: Vec<At<RawObserver>>,
}

/// `[table]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawTable {
    pub size: Option<At<Vec<f64>>>,
    pub cushion_restitution: Option<At<f64>>,
}

/// `[physics]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPhysics {
    pub restitution: Option<At<f64>>,
}

/// `[effects]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawEffects {
    pub contraction: Option<bool>,
    pub light_delay: Option<bool>,
    pub aberration: Option<bool>,
    pub doppler: Option<bool>,
    pub searchlight: Option<bool>,
    pub time_dilation: Option<bool>,
}

/// `[optics]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOptics {
    pub method: Option<At<String>>,
    pub history_frames: Option<At<i64>>,
    pub dichotomy_steps: Option<At<i64>>,
    pub interpolate: Option<bool>,
}

/// `[[puck]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPuck {
    pub name: Option<At<String>>,
    pub position: At<Vec<f64>>,
    pub beta: Option<At<Vec<f64>>>,
    pub velocity: Option<At<Vec<f64>>>,
    pub u: Option<At<Vec<f64>>>,
    pub radius: Option<At<f64>>,
    pub height: Option<At<f64>>,
    pub mass: Option<At<f64>>,
    pub color: Option<At<String>>,
}

/// `[[observer]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawObserver {
    pub name: Option<At<String>>,
    pub position: At<Vec<f64>>,
    pub look_at: Option<At<Vec<f64>>>,
    pub beta: Option<At<Vec<f64>>>,
    pub u: Option<At<Vec<f64>>>,
}

/// Parses the TOML, turning syntax and schema errors (unknown key, wrong
/// type, missing field, wrong array length) into a located [`SceneError`].
pub fn parse(text: &str, file: &str) -> Result<RawScene, SceneErrors> {
    toml::from_str(text).map_err(|e| {
        let message = e.message().trim().to_owned();
        let error = match e.span() {
            Some(span) => SceneError::at(file, text, span.start, "", message),
            None => SceneError::whole_file(file, message),
        };
        SceneErrors::single(error)
    })
}
