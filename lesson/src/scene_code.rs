//! A scene built in code, as a lesson builds it (`lightcone.Scene(...)`,
//! `add_puck`, `add_observer`, `scene.c = …`): the argument handling of
//! Python's `Scene` class (lightcone-py) and of its stand-in in the
//! browser's worker (`crate::standin`), one implementation for both. The
//! rules themselves are the engine's (`scene::build`, `scene::rules`).

use glam::{DVec2, DVec3};
use lightcone_engine::scene::{self, Scene, rules};
use lightcone_engine::spacetime::ProperVelocity;

use crate::error::WorldResult;

/// `Scene(size, c, title, friction, gravity, description)`: an empty
/// table of `size` m (x, y), light at `c` m/s (`None`: the default).
pub fn new(
    size: (f64, f64),
    c: Option<f64>,
    title: &str,
    friction: f64,
    gravity: f64,
    description: &str,
) -> WorldResult<Scene> {
    let mut s = Scene::empty(DVec2::new(size.0, size.1), c)?;
    s.title = title.to_owned();
    s.description = description.to_owned();
    s.set_friction(friction, gravity)?;
    Ok(s)
}

/// A puck as `add_puck` is given it: its motion by one of `beta` (v/c),
/// `velocity` (m/s) or `u` (proper velocity γβ), or at rest.
pub struct PuckArgs<'a> {
    /// Its name (unique in the scene).
    pub name: &'a str,
    /// Its centre at board time 0, m.
    pub position: (f64, f64),
    /// v/c.
    pub beta: Option<(f64, f64)>,
    /// Proper velocity γβ (dimensionless).
    pub u: Option<(f64, f64)>,
    /// Rest radius, m.
    pub radius: f64,
    /// Height, m.
    pub height: f64,
    /// Rest mass, kg.
    pub mass: f64,
    /// A colour name or `#rrggbb` (`None`: the next default colour).
    pub color: Option<&'a str>,
    /// v, m/s.
    pub velocity: Option<(f64, f64)>,
}

fn planar(v: Option<(f64, f64)>) -> Option<DVec3> {
    v.map(|(x, y)| DVec3::new(x, y, 0.0))
}

/// Adds a puck to `scene` through every rule of a scene file's puck.
pub fn add_puck(scene: &mut Scene, p: &PuckArgs<'_>) -> WorldResult<()> {
    let u = rules::motion(planar(p.beta), planar(p.velocity), planar(p.u), scene.c)
        .map_err(|e| e.of(format!("puck {:?}", p.name)))?;
    let color = match p.color {
        None => scene::Color::default_for(scene.pucks.len()),
        Some(c) => rules::color(c)?,
    };
    scene.add_puck(scene::PuckSpec {
        name: p.name.to_owned(),
        position: DVec2::new(p.position.0, p.position.1),
        u,
        radius: p.radius,
        height: p.height,
        mass: p.mass,
        color,
    })?;
    Ok(())
}

/// Adds an observer `name` with its eye at `position` (m), looking at
/// `look_at` (default: the table's centre), moving at `beta` (v/c).
pub fn add_observer(
    scene: &mut Scene,
    name: &str,
    position: [f64; 3],
    look_at: Option<[f64; 3]>,
    beta: Option<[f64; 3]>,
) -> WorldResult<()> {
    let u = match beta {
        None => ProperVelocity::ZERO,
        Some(b) => {
            rules::from_beta(DVec3::from(b)).map_err(|e| e.of(format!("observer {name:?} beta")))?
        }
    };
    scene.add_observer(scene::ObserverSpec {
        name: name.to_owned(),
        position: DVec3::from(position),
        look_at: look_at.map(DVec3::from),
        u,
    })?;
    Ok(())
}

/// `scene.c = c`: the same scene under light at `c` m/s, each puck's
/// momentum γv kept (so a large c is Newton).
pub fn set_c(scene: &mut Scene, c: f64) -> WorldResult<()> {
    *scene = scene.with_c(c).map_err(|e| e.of("Scene.c"))?;
    Ok(())
}

/// The puck names of `scene`, in order.
#[must_use]
pub fn pucks(scene: &Scene) -> Vec<String> {
    scene.pucks.iter().map(|p| p.name.clone()).collect()
}

/// The observer names of `scene`, in order.
#[must_use]
pub fn observers(scene: &Scene) -> Vec<String> {
    scene.observers.iter().map(|o| o.name.clone()).collect()
}

/// `Scene("title", n pucks, c = … m/s)`.
#[must_use]
pub fn describe(scene: &Scene) -> String {
    format!(
        "Scene({:?}, {} pucks, c = {} m/s)",
        scene.title,
        scene.pucks.len(),
        scene.c
    )
}
