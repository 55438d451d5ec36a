//! The board read and struck by the names a lesson (or a Python script)
//! uses: pucks, observers and effects by name, board times checked to be
//! in the computed past. Shared by the world's operations and Python's
//! `Simulation`, so both refuse the same inputs with the same words.

use glam::DVec3;
use lightcone_engine::physics::Billiard;
use lightcone_engine::report::ObserveReport;
use lightcone_engine::scene::{Effect, Effects, Scene};
use lightcone_engine::spacetime::simultaneity_slope;
use serde::Serialize;

use crate::error::{ErrorKind, WorldError, WorldResult};

/// The effect whose key is `key` (`"light_delay"`, …).
pub fn effect(key: &str) -> WorldResult<Effect> {
    Effect::ALL
        .iter()
        .copied()
        .find(|e| e.key() == key)
        .ok_or_else(|| {
            let names: Vec<&str> = Effect::ALL.iter().map(|e| e.key()).collect();
            WorldError::value(format!("unknown effect {key:?}; use one of {names:?}"))
        })
}

/// `shown` for `None`, else exactly the effects named in `list`.
pub fn effects_from(shown: Effects, list: Option<Vec<String>>) -> WorldResult<Effects> {
    match list {
        None => Ok(shown),
        Some(list) => {
            let mut fx = Effects::NONE;
            for key in list {
                fx.set(effect(&key)?, true);
            }
            Ok(fx)
        }
    }
}

/// The index of puck `name`.
pub fn puck_index(billiard: &Billiard, name: &str) -> WorldResult<usize> {
    billiard.index_of(name).ok_or_else(|| {
        let names: Vec<&str> = (0..billiard.len()).map(|i| billiard.name(i)).collect();
        WorldError::new(
            ErrorKind::Key,
            format!("no puck named {name:?}; the scene has {names:?}"),
        )
    })
}

/// The index of observer `name` (`None`: the first, 0).
pub fn observer_index(scene: &Scene, name: Option<&str>) -> WorldResult<usize> {
    match name {
        None => Ok(0),
        Some(name) => scene
            .observers
            .iter()
            .position(|o| o.name == name)
            .ok_or_else(|| {
                let names: Vec<&str> = scene.observers.iter().map(|o| o.name.as_str()).collect();
                WorldError::new(
                    ErrorKind::Key,
                    format!("no observer named {name:?}; the scene has {names:?}"),
                )
            }),
    }
}

/// A history horizon (`Simulation(scene, history=…)`): `None` (the
/// whole run kept) or a finite number of board seconds ≥ 0.
pub fn history_horizon(history: Option<f64>) -> WorldResult<Option<f64>> {
    match history {
        Some(h) if !(h.is_finite() && h >= 0.0) => Err(WorldError::value(format!(
            "history: give a finite number of seconds ≥ 0, or None (got {h})"
        ))),
        h => Ok(h),
    }
}

/// `t` if it is finite.
pub fn finite_time(t: f64) -> WorldResult<f64> {
    if t.is_finite() {
        Ok(t)
    } else {
        Err(WorldError::value(format!(
            "t = {t}: give a finite board time"
        )))
    }
}

/// Board time `at` (default `now`), refused if it is after `now` (s).
pub fn past_time(at: Option<f64>, now: f64) -> WorldResult<f64> {
    let t = finite_time(at.unwrap_or(now))?;
    if t > now + 1e-12 {
        return Err(WorldError::new(
            ErrorKind::NotComputed,
            format!(
                "t = {t} s is after the board time reached ({now} s): the future is not computed yet"
            ),
        ));
    }
    Ok(t)
}

/// Strikes puck `name` at board time `t`: its proper velocity γβ grows by
/// `du` (dimensionless, board frame).
pub fn impulse(billiard: &mut Billiard, name: &str, t: f64, du: (f64, f64)) -> WorldResult<()> {
    let i = puck_index(billiard, name)?;
    if !(du.0.is_finite() && du.1.is_finite()) {
        return Err(WorldError::value(format!(
            "impulse {du:?} on {name:?}: give finite numbers"
        )));
    }
    billiard
        .apply_impulse(i, t, DVec3::new(du.0, du.1, 0.0))
        .map_err(|e| WorldError::value(e.to_string()))
}

/// The proper velocity γβ of puck `name` at board time `t`, (x, y).
pub fn velocity(billiard: &Billiard, name: &str, t: f64) -> WorldResult<(f64, f64)> {
    let i = puck_index(billiard, name)?;
    let u = billiard.worldline(i).proper_velocity_at(t);
    Ok((u.0.x, u.0.y))
}

/// What observer `observer` (default: the first) sees at board time `t`
/// with `effects`: the report `lightcone observe` prints.
pub fn observation(
    scene: &Scene,
    billiard: &Billiard,
    t: f64,
    observer: Option<&str>,
    vertices: bool,
    effects: Effects,
) -> WorldResult<ObserveReport> {
    let index = observer_index(scene, observer)?;
    lightcone_render::observe::report(scene, billiard, index, t, effects, vertices)
        .ok_or_else(|| WorldError::new(ErrorKind::Runtime, format!("observer {index} saw nothing")))
}

/// A puck's rest-frame line of simultaneity on the board, through its event
/// at one board time: `{"puck", "event": {"t", "position"}, "slope"}`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SimultaneityLine {
    /// The puck whose frame it is.
    pub puck: String,
    /// Its event at the board time asked for: board time s, position m.
    pub event: SimultaneityEvent,
    /// dt/dx and dt/dy of the line, s/m: u / (γ c) (see
    /// `spacetime::simultaneity_slope`).
    pub slope: [f64; 2],
}

/// See [`SimultaneityLine::event`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SimultaneityEvent {
    /// Board time, s.
    pub t: f64,
    /// Position on the cloth, m.
    pub position: [f64; 2],
}

/// The line of simultaneity of puck `name`'s rest frame through its event
/// at board time `t`.
pub fn simultaneity(
    scene: &Scene,
    billiard: &Billiard,
    name: &str,
    t: f64,
) -> WorldResult<SimultaneityLine> {
    let i = puck_index(billiard, name)?;
    let w = billiard.worldline(i);
    let e = w.event_at(t);
    let slope = simultaneity_slope(w.proper_velocity_at(t), scene.c);
    Ok(SimultaneityLine {
        puck: name.to_owned(),
        event: SimultaneityEvent {
            t: e.t,
            position: [e.position.x, e.position.y],
        },
        slope: [slope.x, slope.y],
    })
}

/// The space-time diagram of `scene` for `observer` (default: the first)
/// at board time `t`, `size` px, with board `axis` across and puck
/// `frame`'s lines of simultaneity (drawn on the CPU).
pub fn diagram(
    scene: &Scene,
    billiard: &Billiard,
    t: f64,
    observer: Option<&str>,
    size: (u32, u32),
    axis: &str,
    frame: Option<&str>,
) -> WorldResult<lightcone_render::headless::Image> {
    use lightcone_render::diagram::{self, Axis, Options};
    let axis = Axis::parse(axis).map_err(WorldError::value)?;
    if size.0 == 0 || size.1 == 0 || size.0 > 16384 || size.1 > 16384 {
        return Err(WorldError::value(format!(
            "size {size:?}: 1 to 16384 pixels a side"
        )));
    }
    let index = observer_index(scene, observer)?;
    let frame = frame.map(|f| puck_index(billiard, f)).transpose()?;
    Ok(diagram::draw_with(scene, billiard, index, t, size, Options { axis, frame }).image)
}
