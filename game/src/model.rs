//! The game's state and rules, independent of the window: board time and
//! replay, the cue, the observer's flight, the effect toggles; and the
//! game's [`Simulation`], whose frame schedule computes every picture the
//! window, the CAVE walls, picking, clocks and lessons show.
//!
//! Every eye is an observer entity with a worldline: the free eye ("you",
//! whose flight, orbits and tracked poses are kinks and jumps on it), each
//! scene observer, and the CAVE's stereo eyes. Every picture is a view
//! entity (observer + effect set + camera): [`GameState::run_frame`] runs
//! the schedule once for all of them, and everything drawn reads the
//! views' `Apparent`.

use glam::{DVec2, DVec3};
use lightcone_engine::ecs::{Entity, Simulation};
use lightcone_engine::physics::{Billiard, CollisionKind};
use lightcone_engine::scene::{Effects, Scene};
use lightcone_engine::spacetime::{Event, ProperVelocity};
use lightcone_engine::worldline::Worldline;

use lightcone_render::frame::ViewMeshes;

mod cue_keys;
mod eye;
mod hints;
mod pane;
#[cfg(test)]
mod tests;
mod views;

pub use eye::FlyingEye;
pub use hints::Stroke;
pub use pane::{EyeChoice, Pane};
pub use views::PuckCentre;
use views::ViewKey;

/// Which pictures are shown.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ViewMode {
    /// What the observer sees.
    Seen,
    /// The board-frame truth.
    Truth,
    /// Truth on the left, seen on the right.
    Split,
}

/// How the camera chooses its direction and field of view.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Framing {
    /// Turned and widened to show the whole table in the view, with a
    /// margin (the default; Home returns to it).
    Fit,
    /// Where the free eye looks (yaw, pitch: right-drag, a tracked head),
    /// with a 60° field of view.
    Look,
}

/// Drawings over the views that show the physics (keys 7, 8, 9, 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Overlays {
    /// Trails: where each puck was seen (solid) and where it was (dotted),
    /// over the last [`TRAIL_S`] seconds of board time.
    pub trails: bool,
    /// A faint ghost of each puck where it is now (board frame) over the
    /// seen picture.
    pub ghost: bool,
    /// Velocity arrows: the board velocity now (truth) or at emission
    /// (seen), the distance covered in half a second.
    pub arrows: bool,
    /// The magnifier: the fastest (or aimed, or followed) puck's body
    /// drawn large from above over its rest outline (key 0;
    /// `play::magnifier`).
    pub magnifier: bool,
    /// The live space-time diagram, in its own window (key Y).
    pub diagram: bool,
    /// The diagram's frame: the puck whose lines of simultaneity it draws
    /// (`None`: only the board's).
    pub diagram_frame: Option<usize>,
    /// The diagram's board axis across.
    pub diagram_axis: lightcone_render::diagram::Axis,
}

/// The menu's own state.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SceneMenu {
    /// Shown.
    pub open: bool,
    /// The highlighted shipped scene (index into [`crate::assets::SCENES`]; the window draws it, `play::scene_menu`).
    pub selected: usize,
    /// The path typed in.
    pub path: String,
    /// Why the last choice could not be opened.
    pub error: Option<String>,
}

impl Default for Overlays {
    fn default() -> Self {
        Self {
            trails: true,
            ghost: true,
            arrows: true,
            magnifier: true,
            diagram: false,
            diagram_frame: None,
            diagram_axis: lightcone_render::diagram::Axis::X,
        }
    }
}

/// How far back trails reach, s of board time.
pub const TRAIL_S: f64 = 3.0;

/// A cue stroke being aimed: which puck, and the impulse so far.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cue {
    /// The puck.
    pub puck: usize,
    /// The proper-velocity change it will get, board frame.
    pub du: DVec3,
}

/// How far back the game keeps the past for replay, s of board time (10
/// minutes): memory stays bounded however long a game runs. The panel shows
/// it, and the replay slider reaches back no further.
pub const REPLAY_WINDOW: f64 = 600.0;

/// Everything the game keeps between frames.
pub struct GameState {
    /// The scene as loaded (its `c` may be changed by the slider).
    pub scene: Scene,
    /// The scene's own `c` (m/s), as the file or lesson gave it: the panel's
    /// *scene's c* button returns to it after the slider moved `scene.c`.
    pub scene_c: f64,
    /// The simulation: the physics, every eye (an observer with a
    /// worldline) and every picture (a view entity); its frame schedule
    /// is the one way to what is seen.
    pub sim: Simulation,
    /// Meshes for drawing the views.
    pub meshes: ViewMeshes,
    /// The free eye's observer entity.
    you: Entity,
    /// The scene observers' entities, in scene order.
    observers: Vec<Entity>,
    /// The CAVE's stereo eyes' observer entities (made when first used).
    stereo: Vec<Entity>,
    /// The view entities alive, by picture.
    views: Vec<(ViewKey, Entity)>,
    /// Board time the physics has reached, s.
    pub live_time: f64,
    /// Board time shown (≤ live time; less while replaying), s.
    pub view_time: f64,
    /// Time stands still.
    pub paused: bool,
    /// Board seconds per real second.
    pub time_scale: f64,
    /// Effects shown in the seen view.
    pub effects: Effects,
    /// Which pictures.
    pub view: ViewMode,
    /// Pictures side by side chosen with `--views`, instead of [`Self::view`]
    /// (until the player or a lesson chooses a view mode).
    pub panes: Option<Vec<Pane>>,
    /// Where the free eye looks (where it is and how it moves are its
    /// observer's worldline: [`Self::eye_position`], [`Self::eye_velocity`]).
    pub eye: FlyingEye,
    /// `Some(i)`: look through the scene's observer `i` instead.
    pub observer: Option<usize>,
    /// While replaying, the free eye watches the past from where it is
    /// now (the paper's "replay and move"), instead of showing what it saw
    /// then; set when the eye is moved during a replay, cleared live.
    pub replay_and_move: bool,
    /// A stroke being aimed.
    pub cue: Option<Cue>,
    /// The last stroke made (for the hint that its light is on its way).
    pub last_stroke: Option<Stroke>,
    /// Something to tell the player (errors, hints).
    pub message: String,
    /// How the camera is aimed.
    pub framing: Framing,
    /// Zoom (mouse wheel): > 1 narrows the field of view.
    pub zoom: f64,
    /// `Some(i)`: the camera keeps puck `i` (where it is seen) in the
    /// middle of the view.
    pub follow: Option<usize>,
    /// What is drawn over the views.
    pub show: Overlays,
    /// The scene's title and description are shown over the table until
    /// the player starts (a scene opened with `play` starts paused on it).
    pub intro: bool,
    /// The scene menu (key M).
    pub scene_menu: SceneMenu,
    /// Where the scene came from (a shipped scene, a file's text), for a
    /// link that opens it again; `None` for a scene made in code.
    pub source: Option<crate::links::SceneSource>,
    /// Which simulation this is: a number no other game or restart in this
    /// process had (a CAVE cluster's master sends a new snapshot when it
    /// changes).
    pub generation: u64,
}

/// A number no earlier call in this process returned.
fn next_generation() -> u64 {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
    NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}

/// Largest cue stroke, as a proper-velocity change (γβ): β ≈ 0.995.
pub const MAX_STROKE: f64 = 10.0;

/// The simulation of `scene` for the game: the physics keeping
/// [`REPLAY_WINDOW`] of history, the scene's observers (without their
/// default views: the game makes its own) and the free eye, whose
/// worldline starts at board time `t` at `position` with proper velocity
/// `u`, looking along `eye`.
fn simulation(
    scene: &Scene,
    (position, u): (DVec3, ProperVelocity),
    eye: &FlyingEye,
    t: f64,
) -> (Simulation, Entity, Vec<Entity>) {
    let mut sim = Simulation::new(scene);
    sim.physics_mut().set_history(Some(REPLAY_WINDOW));
    let defaults: Vec<Entity> = sim.views().to_vec();
    let observers = defaults
        .iter()
        .filter_map(|&v| sim.observer_of(v))
        .collect();
    for v in defaults {
        sim.remove_view(v);
    }
    let you = sim.add_observer(
        "you",
        Worldline::new(Event::new(t, position), u, scene.c),
        eye.forward(),
    );
    (sim, you, observers)
}

/// `Some(0)` when the scene's first observer moves (the window then looks
/// through it), else `None` (the free eye, at rest where it stands).
fn moving_first_observer(scene: &Scene) -> Option<usize> {
    scene
        .observers
        .first()
        .filter(|o| o.u.0.length() > 0.0)
        .map(|_| 0)
}

impl GameState {
    /// How much puck `puck` matters to the player, larger first: the aimed
    /// puck, then the followed one, then `otherwise()` (its speed, in a unit
    /// the caller chooses). Labels and the magnifier rank pucks by it.
    pub fn attention(&self, puck: usize, otherwise: impl FnOnce() -> f64) -> f64 {
        if self.cue.is_some_and(|c| c.puck == puck) {
            f64::INFINITY
        } else if self.follow == Some(puck) {
            f64::MAX
        } else {
            otherwise()
        }
    }

    /// A game on `scene`, starting at board time 0 looking through its first
    /// observer's eye (which the player may then fly).
    pub fn new(scene: Scene) -> Self {
        let (position, eye) = eye::at_observer(&scene, 0);
        let start = (position, ProperVelocity::ZERO);
        let (mut sim, you, observers) = simulation(&scene, start, &eye, 0.0);
        let observer = moving_first_observer(&scene);
        Self {
            meshes: ViewMeshes::new(&mut sim),
            sim,
            you,
            observers,
            stereo: Vec::new(),
            views: Vec::new(),
            effects: scene.effects,
            scene_c: scene.c,
            scene,
            live_time: 0.0,
            view_time: 0.0,
            paused: false,
            time_scale: 1.0,
            view: ViewMode::Seen,
            panes: None,
            eye,
            // A scene whose first observer moves (an eye flying past) is
            // seen through that eye from the start.
            observer,
            replay_and_move: false,
            cue: None,
            last_stroke: None,
            message: String::new(),
            framing: Framing::Fit,
            zoom: 1.0,
            follow: None,
            intro: false,
            show: Overlays::default(),
            scene_menu: Default::default(),
            source: None,
            generation: next_generation(),
        }
    }

    /// The physics (pucks' worldlines, collisions so far).
    pub fn physics(&self) -> &Billiard {
        self.sim.physics()
    }

    /// The physics, to strike a puck or run it ahead.
    pub fn physics_mut(&mut self) -> &mut Billiard {
        self.sim.physics_mut()
    }

    /// Zooms by `factor` (> 1 in), within 0.2–50×.
    pub fn zoom_by(&mut self, factor: f64) {
        if factor.is_finite() && factor > 0.0 {
            self.zoom = (self.zoom * factor).clamp(0.2, 50.0);
        }
    }

    /// Whether the picture is a replay of the past (not live).
    pub fn replaying(&self) -> bool {
        self.view_time < self.live_time
    }

    /// Advances by `real_dt` seconds of wall-clock time: the board clock by
    /// `real_dt × time_scale` unless paused or replaying (a replay plays
    /// the past forward); the free eye moves on its worldline by itself.
    pub fn step(&mut self, real_dt: f64) {
        if self.paused || !real_dt.is_finite() || real_dt <= 0.0 {
            return;
        }
        let dt = real_dt * self.time_scale;
        if self.replaying() {
            self.view_time = (self.view_time + dt).min(self.live_time);
        } else {
            self.live_time += dt;
            let t = self.live_time;
            self.physics_mut().advance_to(t);
            self.view_time = self.live_time;
        }
    }

    /// Goes to board time `t` (s) and pauses there, live: the physics is
    /// run to `t`, and the intro put away. A time before the scene began
    /// (`t` < 0) is shown as a replay of the live edge at 0: what the eye
    /// saw of the pucks before the start (`before_start`).
    pub fn show_at(&mut self, t: f64) {
        if !t.is_finite() {
            return;
        }
        let live = t.max(self.live_time).max(0.0);
        self.physics_mut().advance_to(live);
        self.live_time = live;
        self.view_time = t.min(live);
        self.paused = true;
        self.intro = false;
    }

    /// Shows board time `t` (clamped to [0, live time]) and pauses.
    pub fn replay_to(&mut self, t: f64) {
        if t.is_finite() {
            self.view_time = t.clamp(0.0, self.live_time);
            self.paused = true;
        }
    }

    /// Back to the live edge.
    pub fn go_live(&mut self) {
        self.view_time = self.live_time;
        self.replay_and_move = false;
    }

    /// Aims a stroke on `puck`: a pull of `pull` (board-plane direction, and
    /// length as a proper velocity `γ v` in m/s, so that a stroke means the
    /// same momentum whatever c is) gives an impulse the opposite way,
    /// capped at [`MAX_STROKE`] in γβ. Returns the puck's velocity after the
    /// stroke.
    pub fn aim(&mut self, puck: usize, pull: DVec2) -> ProperVelocity {
        let mut du = -pull.extend(0.0) / self.scene.c;
        if du.length() > MAX_STROKE {
            du = du.normalize() * MAX_STROKE;
        }
        self.cue = Some(Cue { puck, du });
        ProperVelocity(
            self.physics()
                .worldline(puck)
                .proper_velocity_at(self.live_time)
                .0
                + du,
        )
    }

    /// Strikes the aimed stroke at the live board time. Refused while
    /// replaying (the past is not rewritten).
    pub fn strike(&mut self) -> Result<(), String> {
        let Some(cue) = self.cue.take() else {
            return Ok(());
        };
        if self.replaying() {
            return Err("back to live time (press L) to strike: a replay shows the past".into());
        }
        let t = self.live_time;
        self.physics_mut()
            .apply_impulse(cue.puck, t, cue.du)
            .map_err(|e| e.to_string())?;
        self.last_stroke = Some(Stroke {
            puck: cue.puck,
            t,
            position: self.physics().worldline(cue.puck).position_at(t),
        });
        Ok(())
    }

    /// Restarts the scene with a new speed of light (m/s), each puck (and
    /// observer) keeping its proper velocity in m/s, `γ v`: its momentum
    /// (see [`Scene::with_c`]). Raising c tends to Newton.
    pub fn restart_with_c(&mut self, c: f64) {
        match self.scene.with_c(c) {
            Ok(scene) => self.scene = scene,
            Err(e) => {
                self.message = e.to_string();
                return;
            }
        }
        let start = (self.eye_position(), self.eye_velocity());
        let (sim, you, observers) = simulation(&self.scene, start, &self.eye, 0.0);
        self.sim = sim;
        self.generation = next_generation();
        self.you = you;
        self.observers = observers;
        self.stereo.clear();
        self.views.clear();
        self.live_time = 0.0;
        self.view_time = 0.0;
        self.replay_and_move = false;
        self.cue = None;
        self.last_stroke = None;
    }

    /// Starts the scene again from board time 0 (same c, same eye).
    pub fn restart(&mut self) {
        self.restart_with_c(self.scene.c);
    }

    /// A line about the latest collision shown (at or before the view time).
    pub fn last_collision(&self) -> Option<String> {
        let b = self.physics();
        let c = b
            .collisions()
            .iter()
            .rev()
            .find(|c| c.t <= self.view_time)?;
        let names: Vec<&str> = c.pucks.iter().map(|p| b.name(p.puck)).collect();
        Some(match c.kind {
            CollisionKind::PuckPuck if c.simultaneous => {
                let (last, first) = names.split_last()?;
                format!(
                    "t = {:.3} s: {} and {last} met at once",
                    c.t,
                    first.join(", ")
                )
            }
            CollisionKind::PuckPuck => format!("t = {:.3} s: {} hit {}", c.t, names[0], names[1]),
            CollisionKind::Cushion(k) => {
                format!("t = {:.3} s: {} hit cushion {}", c.t, names[0], k.name())
            }
        })
    }
}
