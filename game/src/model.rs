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
use lightcone_engine::ecs::systems::optics::eye_at;
use lightcone_engine::ecs::{Apparent, Entity, Simulation, Vantage};
use lightcone_engine::optics::{Emission, Eye, Seen};
use lightcone_engine::physics::{Billiard, CollisionKind};
use lightcone_engine::scene::{Effect, Effects, Scene};
use lightcone_engine::spacetime::{Event, ProperVelocity};
use lightcone_engine::worldline::Worldline;

use lightcone_render::frame::{Camera, ViewKind, ViewMeshes};

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

/// The eye the player flies: a position at the current board time, a
/// proper velocity, and where it looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlyingEye {
    /// Eye position now (at [`GameState::live_time`]), board frame, m.
    pub position: DVec3,
    /// Proper velocity.
    pub u: ProperVelocity,
    /// Heading about z, radians (0 looks along +x).
    pub yaw: f64,
    /// Elevation, radians (negative looks down).
    pub pitch: f64,
}

impl FlyingEye {
    /// Unit viewing direction, board axes.
    pub fn forward(&self) -> DVec3 {
        DVec3::new(
            self.pitch.cos() * self.yaw.cos(),
            self.pitch.cos() * self.yaw.sin(),
            self.pitch.sin(),
        )
    }
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

/// Drawings over the views that show the physics (keys 7, 8, 9).
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

/// Whose eye a picture looks through.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EyeChoice {
    /// The eye the player looks through ([`GameState::observer`]: the
    /// free eye, or the scene observer chosen in the panel).
    Current,
    /// The free eye ("you").
    You,
    /// The scene's observer `i`.
    Scene(usize),
}

/// One picture of the window: an eye, and what it shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pane {
    /// Whose eye.
    pub eye: EyeChoice,
    /// Seen (the effects on) or the truth.
    pub kind: ViewKind,
}

impl Pane {
    /// Parses a comma-separated list of pictures, shown side by side:
    /// each `seen` or `truth` (through the eye looked through), `you` or
    /// an observer's name (what that eye sees), or `EYE:seen`,
    /// `EYE:truth`. E.g. `seen,truth`, or `you,observer` for two eyes.
    pub fn parse_list(spec: &str, scene: &Scene) -> Result<Vec<Pane>, String> {
        let kind = |k: &str| match k {
            "seen" => Ok(ViewKind::Seen),
            "truth" => Ok(ViewKind::Truth),
            other => Err(format!("--views: {other:?} is not seen or truth")),
        };
        let eye = |e: &str| {
            if e == "you" {
                return Ok(EyeChoice::You);
            }
            scene
                .observers
                .iter()
                .position(|o| o.name == e)
                .map(EyeChoice::Scene)
                .ok_or_else(|| {
                    let names: Vec<&str> =
                        scene.observers.iter().map(|o| o.name.as_str()).collect();
                    format!(
                        "--views: no eye {e:?} (you, or an observer of the scene: {})",
                        names.join(", ")
                    )
                })
        };
        let mut out = Vec::new();
        for item in spec.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let pane = match item.split_once(':') {
                Some((e, k)) => Pane {
                    eye: eye(e.trim())?,
                    kind: kind(k.trim())?,
                },
                None => match kind(item) {
                    Ok(k) => Pane {
                        eye: EyeChoice::Current,
                        kind: k,
                    },
                    Err(_) => Pane {
                        eye: eye(item)?,
                        kind: ViewKind::Seen,
                    },
                },
            };
            out.push(pane);
        }
        if out.is_empty() {
            return Err("--views: give at least one picture (e.g. seen,truth)".into());
        }
        if out.len() > 8 {
            return Err("--views: at most 8 pictures".into());
        }
        Ok(out)
    }
}

/// Which view entity of the game's simulation a picture is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ViewKey {
    /// A desktop picture: the eye (`None`: the free eye) and its kind.
    Desktop(Option<usize>, ViewKind),
    /// The CAVE's stereo eye `k` (what it sees, with the game's effects).
    Stereo(usize),
}

/// One puck as a view sees it: for clocks, labels and picking.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PuckCentre {
    /// The puck.
    pub puck: usize,
    /// Emission event of its centre (mid-height).
    pub emission: Emission,
    /// Where its centre is seen (relative to the eye).
    pub seen: Seen,
    /// The time its clock shows in the picture, s.
    pub clock: f64,
}

/// Everything the game keeps between frames.
pub struct GameState {
    /// The scene as loaded (its `c` may be changed by the slider).
    pub scene: Scene,
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
    /// The free eye now (at the live board time).
    pub eye: FlyingEye,
    /// `Some(i)`: look through the scene's observer `i` instead.
    pub observer: Option<usize>,
    /// While replaying, the free eye watches the past from where it is
    /// now (the paper's "replay and move"), instead of showing what it saw
    /// then; set when the eye is moved during a replay, cleared live.
    pub replay_and_move: bool,
    /// A stroke being aimed.
    pub cue: Option<Cue>,
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
/// default views: the game makes its own) and the free eye `eye`, whose
/// worldline starts at board time `t`.
fn simulation(scene: &Scene, eye: &FlyingEye, t: f64) -> (Simulation, Entity, Vec<Entity>) {
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
        Worldline::new(Event::new(t, eye.position), eye.u, scene.c),
        eye.forward(),
    );
    (sim, you, observers)
}

impl GameState {
    /// A game on `scene`, starting at board time 0 looking through its first
    /// observer's eye (which the player may then fly).
    pub fn new(scene: Scene) -> Self {
        let eye = Self::eye_at_observer(&scene, 0);
        let (mut sim, you, observers) = simulation(&scene, &eye, 0.0);
        Self {
            meshes: ViewMeshes::new(&mut sim),
            sim,
            you,
            observers,
            stereo: Vec::new(),
            views: Vec::new(),
            effects: scene.effects,
            scene,
            live_time: 0.0,
            view_time: 0.0,
            paused: false,
            time_scale: 1.0,
            view: ViewMode::Seen,
            panes: None,
            eye,
            observer: None,
            replay_and_move: false,
            cue: None,
            message: String::new(),
            framing: Framing::Fit,
            zoom: 1.0,
            follow: None,
            intro: false,
            show: Overlays::default(),
            scene_menu: Default::default(),
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

    /// The free eye at rest where observer `i` of `scene` stands at t = 0,
    /// looking where it looks.
    fn eye_at_observer(scene: &Scene, i: usize) -> FlyingEye {
        let o = &scene.observers[i.min(scene.observers.len() - 1)];
        let f = (o.target(scene.table.size) - o.position).normalize_or(DVec3::Y);
        FlyingEye {
            position: o.position,
            u: ProperVelocity::ZERO,
            yaw: f.y.atan2(f.x),
            pitch: f.z.clamp(-1.0, 1.0).asin(),
        }
    }

    /// Back to the default view: the camera fitted to the table, no zoom,
    /// following nothing; the free eye back where the scene's first
    /// observer stands, at rest.
    pub fn reset_view(&mut self) {
        self.framing = Framing::Fit;
        self.zoom = 1.0;
        self.follow = None;
        if self.observer.is_none() {
            self.eye = Self::eye_at_observer(&self.scene, 0);
        }
    }

    /// Zooms by `factor` (> 1 in), within 0.2–50×.
    pub fn zoom_by(&mut self, factor: f64) {
        if factor.is_finite() && factor > 0.0 {
            self.zoom = (self.zoom * factor).clamp(0.2, 50.0);
        }
    }

    /// Takes the free eye over from the scene observer looked through (same
    /// place, velocity and direction as in the picture), so the player can
    /// move it.
    fn take_over(&mut self) {
        if let Some(i) = self.observer.take()
            && i < self.scene.observers.len()
            && let Some(w) = self
                .observers
                .get(i)
                .and_then(|&o| self.sim.observer_worldline(o))
        {
            let st = w.state_at(self.view_time);
            let o = &self.scene.observers[i];
            let f = (o.target(self.scene.table.size) - o.position).normalize_or(DVec3::Y);
            self.eye = FlyingEye {
                position: st.position,
                u: st.u,
                yaw: f.y.atan2(f.x),
                pitch: f.z.clamp(-1.0, 1.0).asin(),
            };
        }
    }

    /// The point orbits turn about: the followed puck (where it is now) or
    /// the table's centre.
    pub fn orbit_target(&self) -> DVec3 {
        match self.follow {
            Some(i) if i < self.physics().len() => {
                self.physics().worldline(i).position_at(self.view_time)
            }
            _ => (self.scene.table.size / 2.0).extend(0.0),
        }
    }

    /// Orbits the free eye about [`Self::orbit_target`]: `yaw` radians about
    /// the vertical, `pitch` radians of elevation (kept between 3° and
    /// 89.9°), at the same distance. The camera then frames the table.
    pub fn orbit(&mut self, yaw: f64, pitch: f64) {
        if !(yaw.is_finite() && pitch.is_finite()) {
            return;
        }
        self.take_over();
        let target = self.orbit_target();
        let d = self.eye.position - target;
        let r = d.length().max(0.1);
        let horizontal = d.truncate().length();
        let azimuth = if horizontal > 1e-9 {
            d.y.atan2(d.x)
        } else {
            -std::f64::consts::FRAC_PI_2
        } + yaw;
        let elevation = (d.z / r).clamp(-1.0, 1.0).asin() + pitch;
        let elevation = elevation.clamp(3f64.to_radians(), 89.9f64.to_radians());
        self.eye.position = target
            + r * DVec3::new(
                elevation.cos() * azimuth.cos(),
                elevation.cos() * azimuth.sin(),
                elevation.sin(),
            );
        let f = (target - self.eye.position).normalize_or(DVec3::Y);
        self.eye.yaw = f.y.atan2(f.x);
        self.eye.pitch = f.z.clamp(-1.0, 1.0).asin();
        self.framing = Framing::Fit;
    }

    /// The free eye at rest straight above the table's centre, high enough
    /// to see it all with a 60° field of view; the camera frames the table.
    pub fn top_view(&mut self) {
        self.observer = None;
        let size = self.scene.table.size;
        let half = (size.x / 1.6).max(size.y) / 2.0 + 0.1;
        let height = half / (std::f64::consts::FRAC_PI_6).tan() * 1.1;
        self.eye = FlyingEye {
            position: (size / 2.0).extend(height),
            u: ProperVelocity::ZERO,
            yaw: std::f64::consts::FRAC_PI_2,
            pitch: -std::f64::consts::FRAC_PI_2 + 1e-6,
        };
        self.framing = Framing::Fit;
        self.zoom = 1.0;
    }

    /// Right-drag: turns the free eye (taking it over from a scene
    /// observer) and frees the camera from the table.
    pub fn look(&mut self, dyaw: f64, dpitch: f64) {
        let start = self.forward();
        self.take_over();
        if self.framing == Framing::Fit {
            // Start from where the fitted camera looks.
            let f = start.normalize_or(DVec3::Y);
            self.eye.yaw = f.y.atan2(f.x);
            self.eye.pitch = f.z.clamp(-1.0, 1.0).asin();
            self.framing = Framing::Look;
        }
        self.eye.yaw += dyaw;
        self.eye.pitch = (self.eye.pitch + dpitch).clamp(-1.5, 1.5);
    }

    /// Where the first picture's camera looked at the last frame (the
    /// free eye's direction before any frame).
    pub fn forward(&self) -> DVec3 {
        self.views
            .iter()
            .find(|(k, _)| matches!(k, ViewKey::Desktop(..)))
            .and_then(|&(_, v)| self.sim.camera(v))
            .map_or_else(|| self.eye.forward(), |c| c.forward)
    }

    /// Whether the picture is a replay of the past (not live).
    pub fn replaying(&self) -> bool {
        self.view_time < self.live_time
    }

    /// Advances by `real_dt` seconds of wall-clock time: the board clock by
    /// `real_dt × time_scale` unless paused or replaying, the flying eye with
    /// its velocity over the same board time (a replay plays the past
    /// forward; the eye's own now stays at the live time).
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
            self.eye.position += self.eye.u.velocity(self.scene.c) * dt;
        }
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

    /// Accelerates the flying eye: adds `du` to its proper velocity (thrust
    /// of any size never reaches c). While paused or replaying, moves it
    /// by `step` metres instead (a frozen picture has no board time to fly
    /// in).
    pub fn thrust(&mut self, du: DVec3, step: DVec3) {
        if self.paused || self.replaying() {
            self.eye.position += step;
        } else if du.is_finite() {
            self.eye.u = ProperVelocity(self.eye.u.0 + du);
            self.steer_you();
        }
    }

    /// Stops the flying eye.
    pub fn halt(&mut self) {
        self.eye.u = ProperVelocity::ZERO;
        self.steer_you();
    }

    /// A kink on the free eye's worldline at the live time: from now on it
    /// moves with its new velocity (a velocity change, not a jump).
    fn steer_you(&mut self) {
        let t = self.live_time;
        let _ = self.sim.steer_observer(self.you, t, self.eye.u);
    }

    /// Writes the free eye's moves since the last frame on its worldline,
    /// at the live board time: a kink when only its velocity changed, a
    /// jump when it was put somewhere (orbit, reset, a tracked pose, a
    /// step while paused). A jump during a replay switches the free eye's
    /// pictures to "replay and move".
    fn sync_eye(&mut self) {
        let t = self.live_time;
        let Some(w) = self.sim.observer_worldline(self.you) else {
            return;
        };
        let st = w.state_at(t);
        let tol = 1e-9 * (1.0 + self.eye.position.length());
        if (st.position - self.eye.position).length() > tol {
            if self.replaying() {
                self.replay_and_move = true;
            }
            // Never fails: the live time never goes back (a restart makes
            // a new simulation) and the eye's state is finite.
            let _ = self
                .sim
                .place_observer(self.you, t, self.eye.position, self.eye.u);
        } else if st.u != self.eye.u {
            let _ = self.sim.steer_observer(self.you, t, self.eye.u);
        }
        if let Some(w) = self.sim.observer_worldline(self.you) {
            self.eye.position = w.position_at(t);
        }
        self.sim.forget_observer_before(self.you, t - REPLAY_WINDOW);
    }

    /// The free eye's vantage: on its worldline (live, and in a replay:
    /// what it saw then), or watching the past from where it is now.
    fn you_vantage(&self) -> Vantage {
        if self.replaying() && self.replay_and_move {
            Vantage::ReplayAndMove {
                now: self.live_time,
            }
        } else {
            Vantage::OnWorldline
        }
    }

    /// The scene observer a pane's eye is (`None`: the free eye).
    fn resolve(&self, eye: EyeChoice) -> Option<usize> {
        let n = self.observers.len();
        match eye {
            EyeChoice::Current => self.observer.filter(|&i| i < n),
            EyeChoice::You => None,
            EyeChoice::Scene(i) => Some(i).filter(|&i| i < n),
        }
    }

    /// The eye looked through now (a scene observer's or the free one), as
    /// the pictures of the next frame see from.
    pub fn eye(&self) -> Eye {
        let (observer, vantage) = match self.resolve(EyeChoice::Current) {
            Some(i) => (self.observers[i], Vantage::OnWorldline),
            None => (self.you, self.you_vantage()),
        };
        match self.sim.observer_worldline(observer) {
            Some(w) => eye_at(w, vantage, self.view_time),
            None => Eye {
                event: Event::new(self.view_time, self.eye.position),
                u: self.eye.u,
            },
        }
    }

    /// The pictures the window shows side by side, left to right.
    pub fn pane_list(&self) -> Vec<Pane> {
        if let Some(p) = &self.panes {
            return p.clone();
        }
        let pane = |kind| Pane {
            eye: EyeChoice::Current,
            kind,
        };
        match self.view {
            ViewMode::Seen => vec![pane(ViewKind::Seen)],
            ViewMode::Truth => vec![pane(ViewKind::Truth)],
            ViewMode::Split => vec![pane(ViewKind::Truth), pane(ViewKind::Seen)],
        }
    }

    /// Chooses a view mode (seen, truth, split), ending any `--views`.
    pub fn set_view(&mut self, mode: ViewMode) {
        self.view = mode;
        self.panes = None;
    }

    fn key(&self, pane: Pane) -> ViewKey {
        ViewKey::Desktop(self.resolve(pane.eye), pane.kind)
    }

    /// The view entity of a picture (after [`Self::run_frame`] made it).
    pub fn view_of(&self, pane: Pane) -> Option<Entity> {
        let key = self.key(pane);
        self.views.iter().find(|(k, _)| *k == key).map(|&(_, v)| v)
    }

    /// The view entity for `key`, made if missing.
    fn view_for(&mut self, key: ViewKey) -> Entity {
        if let Some(&(_, v)) = self.views.iter().find(|(k, _)| *k == key) {
            return v;
        }
        let (name, observer) = match key {
            ViewKey::Desktop(eye, kind) => {
                let (who, observer) = match eye {
                    Some(i) => (self.scene.observers[i].name.clone(), self.observers[i]),
                    None => ("you".to_owned(), self.you),
                };
                let what = match kind {
                    ViewKind::Seen => "seen",
                    ViewKind::Truth => "truth",
                };
                (format!("{who}: {what}"), observer)
            }
            ViewKey::Stereo(k) => (format!("CAVE eye {k}"), self.stereo[k]),
        };
        let v = self.sim.add_view(
            &name,
            observer,
            Effects::NONE,
            lightcone_engine::ecs::Framing::default(),
            Vantage::OnWorldline,
        );
        self.views.push((key, v));
        v
    }

    /// Sets a view's effects, framing (for a viewport of `aspect`) and
    /// vantage from the game's state.
    fn configure(&mut self, key: ViewKey, view: Entity, aspect: f64) {
        use lightcone_engine::ecs::Framing as Aim;
        let (effects, vantage) = match key {
            ViewKey::Desktop(eye, kind) => (
                kind.effects(self.effects),
                match eye {
                    Some(_) => Vantage::OnWorldline,
                    None => self.you_vantage(),
                },
            ),
            ViewKey::Stereo(_) => (
                self.effects,
                Vantage::ReplayAndMove {
                    now: self.live_time,
                },
            ),
        };
        if self.sim.view_effects(view) != Some(effects) {
            for e in Effect::ALL {
                self.sim.set_view_effect(view, e, effects.is_on(e));
            }
        }
        let framing = match self.framing {
            Framing::Look => Aim::Look {
                forward: self.eye.forward(),
                fovy: std::f64::consts::FRAC_PI_3,
                zoom: self.zoom,
            },
            Framing::Fit => Aim::Fit {
                aspect,
                zoom: self.zoom,
                follow: self.follow,
            },
        };
        self.sim.set_framing(view, framing);
        self.sim.set_vantage(view, vantage);
    }

    /// Runs one frame of the simulation's schedule at the board time shown,
    /// for the pictures `panes` (each with its viewport's width / height):
    /// their view entities are made or kept, the others (desktop) dropped.
    /// Returns each picture's view entity; read it with [`Self::apparent`]
    /// and [`Self::camera`].
    pub fn run_frame(&mut self, panes: &[(Pane, f64)]) -> Vec<Entity> {
        self.sync_eye();
        let keys: Vec<(ViewKey, f64)> = panes.iter().map(|&(p, a)| (self.key(p), a)).collect();
        self.drop_views(|k| matches!(k, ViewKey::Desktop(..)) && !keys.iter().any(|(q, _)| q == k));
        let mut out = Vec::with_capacity(keys.len());
        for &(key, aspect) in &keys {
            let v = self.view_for(key);
            self.configure(key, v, aspect);
            out.push(v);
        }
        let t = self.view_time;
        self.sim.advance_to(t);
        out
    }

    /// Runs one frame for the CAVE: one view per stereo eye, at the board
    /// positions `eyes` now, moving with the free eye's velocity, watching
    /// the board time shown. Returns each eye's view entity.
    pub fn run_stereo(&mut self, eyes: &[DVec3]) -> Vec<Entity> {
        self.sync_eye();
        let t = self.live_time;
        while self.stereo.len() < eyes.len() {
            let k = self.stereo.len();
            let o = self.sim.add_observer(
                &format!("CAVE eye {k}"),
                Worldline::new(
                    Event::new(t, DVec3::ZERO),
                    ProperVelocity::ZERO,
                    self.scene.c,
                ),
                DVec3::Y,
            );
            self.stereo.push(o);
        }
        let n = eyes.len();
        self.drop_views(|k| matches!(k, ViewKey::Stereo(i) if *i >= n));
        let mut out = Vec::with_capacity(n);
        for (k, &p) in eyes.iter().enumerate() {
            let o = self.stereo[k];
            let _ = self.sim.place_observer(o, t, p, self.eye.u);
            self.sim.forget_observer_before(o, t);
            let key = ViewKey::Stereo(k);
            let v = self.view_for(key);
            self.configure(key, v, 1.0);
            out.push(v);
        }
        let t = self.view_time;
        self.sim.advance_to(t);
        out
    }

    fn drop_views(&mut self, drop: impl Fn(&ViewKey) -> bool) {
        let (gone, kept): (Vec<_>, Vec<_>) = self.views.drain(..).partition(|(k, _)| drop(k));
        self.views = kept;
        for (_, v) in gone {
            self.sim.remove_view(v);
        }
    }

    /// What `view` saw at the last frame.
    pub fn apparent(&self, view: Entity) -> Option<&Apparent> {
        self.sim.apparent(view)
    }

    /// The camera of `view` at the last frame.
    pub fn camera(&self, view: Entity) -> Option<Camera> {
        self.sim.camera(view).map(Camera::from)
    }

    /// The effects `view` has.
    pub fn view_effects(&self, view: Entity) -> Effects {
        self.sim.view_effects(view).unwrap_or(Effects::NONE)
    }

    /// Every puck's centre as `view` saw it at the last frame, with the
    /// time its clock shows: what clocks, labels and picking read.
    pub fn centres(&self, view: Entity) -> Vec<PuckCentre> {
        let Some(apparent) = self.apparent(view) else {
            return Vec::new();
        };
        apparent
            .bodies
            .iter()
            .filter_map(|b| match b.body {
                lightcone_engine::ecs::BodyRef::Puck(i) => {
                    let k = b.centre();
                    Some(PuckCentre {
                        puck: i,
                        emission: *b.emissions.get(k)?,
                        seen: *b.seen.get(k)?,
                        clock: b.seen_proper_time,
                    })
                }
                lightcone_engine::ecs::BodyRef::Fixture(_) => None,
            })
            .collect()
    }

    /// Runs a frame of the seen picture of the eye looked through (a
    /// 16:9 viewport) and returns its view: for headless users (benches,
    /// tests).
    pub fn run_seen(&mut self) -> Entity {
        let pane = Pane {
            eye: EyeChoice::Current,
            kind: ViewKind::Seen,
        };
        self.run_frame(&[(pane, 16.0 / 9.0)])[0]
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
            .map_err(|e| e.to_string())
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
        let (sim, you, observers) = simulation(&self.scene, &self.eye, 0.0);
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
            CollisionKind::PuckPuck => format!("t = {:.3} s: {} hit {}", c.t, names[0], names[1]),
            CollisionKind::Cushion(k) => {
                format!("t = {:.3} s: {} hit cushion {}", c.t, names[0], k.name())
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn game() -> GameState {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../assets/scenes/paper_carom.toml");
        GameState::new(lightcone_engine::scene::load(&path).unwrap())
    }

    #[test]
    fn time_runs_pauses_and_replays() {
        let mut g = game();
        g.step(0.5);
        g.time_scale = 2.0;
        g.step(0.5);
        assert!((g.live_time - 1.5).abs() < 1e-12);
        g.replay_to(0.4);
        assert!(g.paused && g.replaying());
        g.step(1.0);
        assert_eq!(g.view_time, 0.4); // paused
        g.paused = false;
        g.step(0.1);
        assert!((g.view_time - 0.6).abs() < 1e-12); // replay plays forward
        assert!((g.live_time - 1.5).abs() < 1e-12);
        g.go_live();
        assert!(!g.replaying());
    }

    #[test]
    fn no_stroke_reaches_c_and_replays_refuse_strokes() {
        let mut g = game();
        let after = g.aim(1, DVec2::new(-1e9, 0.0));
        assert!(
            (after.speed_deficit() * 2.0 * after.0.length_squared() - 1.0).abs()
                < 1.0 / after.0.length_squared()
        ); // 1 − |β| ≈ 1/(2u²), to 3/(4u²)
        assert!((after.0.x - MAX_STROKE).abs() < 1e-12);
        g.strike().unwrap();
        g.step(0.1);
        assert!(g.physics().worldline(1).proper_velocity_at(g.live_time).0.x > 9.0);
        g.replay_to(0.05);
        g.aim(0, DVec2::new(1.0, 0.0));
        assert!(g.strike().is_err());
    }

    #[test]
    fn thrust_never_reaches_c_and_flies_the_eye() {
        let mut g = game();
        for _ in 0..1000 {
            g.thrust(DVec3::new(1e6, 0.0, 0.0), DVec3::ZERO);
        }
        assert!(
            (g.eye.u.speed_deficit() * 2.0 * g.eye.u.0.length_squared() - 1.0).abs()
                < 1.0 / g.eye.u.0.length_squared()
        ); // 1 − |β| ≈ 1/(2u²), to 3/(4u²)
        let x0 = g.eye.position.x;
        g.step(0.01);
        assert!((g.eye.position.x - x0 - g.eye.u.velocity(g.scene.c).x * 0.01).abs() < 1e-12);
        g.halt();
        assert_eq!(g.eye.u, ProperVelocity::ZERO);
    }

    #[test]
    fn changing_c_keeps_each_pucks_proper_velocity_in_metres_per_second() {
        let mut g = game();
        let before: Vec<DVec3> = g.scene.pucks.iter().map(|p| p.u.0 * g.scene.c).collect();
        g.restart_with_c(1e6);
        for (p, b) in g.scene.pucks.iter().zip(&before) {
            assert!((p.u.0 * 1e6 - *b).length() < 1e-12 * (1.0 + b.length()));
        }
        // Slow light on the cloth: below √(R μ g) ≈ 0.245 m/s a puck would
        // not fit inside the braking's Rindler horizon; refused, with the
        // reason shown, and the game keeps its scene.
        g.restart_with_c(0.01);
        assert_eq!(g.scene.c, 1e6);
        assert!(g.message.contains("c must be above"), "{}", g.message);
        // Frictionless, slow light: the same momentum, never c.
        g.scene.table.friction = 0.0;
        g.restart_with_c(0.01);
        assert!(
            (g.scene.pucks[0].u.speed_deficit() * 2.0 * g.scene.pucks[0].u.0.length_squared()
                - 1.0)
                .abs()
                < 1.0 / g.scene.pucks[0].u.0.length_squared()
        ); // 1 − |β| ≈ 1/(2u²), to 3/(4u²)
        assert!((g.scene.pucks[0].u.0 * 0.01 - before[0]).length() < 1e-12);
    }

    #[test]
    fn changing_c_restarts() {
        let mut g = game();
        g.step(1.0);
        g.restart_with_c(3.0);
        assert_eq!(g.physics().c(), 3.0);
        assert_eq!(g.live_time, 0.0);
        g.restart_with_c(-1.0);
        assert_eq!(g.physics().c(), 3.0);
        assert!(!g.message.is_empty());
    }

    /// The pictures of `a` and `b` agree to `tol` (m): same eye, same bodies,
    /// every point seen at the same place.
    fn same_picture(a: &Apparent, b: &Apparent, tol: f64) {
        let (ea, eb) = (a.eye.unwrap(), b.eye.unwrap());
        assert!((ea.event.position - eb.event.position).length() < tol);
        assert_eq!(ea.event.t, eb.event.t);
        assert_eq!(a.bodies.len(), b.bodies.len());
        for (x, y) in a.bodies.iter().zip(&b.bodies) {
            assert_eq!(x.body, y.body);
            assert_eq!(x.seen.len(), y.seen.len());
            for (p, q) in x.seen.iter().zip(&y.seen) {
                assert!(
                    (p.position - q.position).length() < tol,
                    "{:?}: {} vs {}",
                    x.body,
                    p.position,
                    q.position
                );
                assert!((p.doppler - q.doppler).abs() < tol);
            }
            assert!((x.seen_proper_time - y.seen_proper_time).abs() < tol);
        }
    }

    #[test]
    fn a_replay_shows_what_the_flying_eye_saw_then() {
        let mut g = game();
        for e in Effect::ALL {
            g.effects.set(e, true);
        }
        // Frames of 1/60 s; the eye thrusts, then is orbited (a jump).
        let frame = |g: &mut GameState| {
            g.step(1.0 / 60.0);
            g.run_seen()
        };
        for _ in 0..12 {
            g.thrust(DVec3::new(0.05, 0.02, 0.0), DVec3::ZERO);
            frame(&mut g);
        }
        let v = frame(&mut g);
        let t1 = g.live_time;
        let live = g.apparent(v).unwrap().clone();
        assert!(live.eye.unwrap().u.0.length() > 0.5);
        // The next thrust must come a frame later: a thrust at the live time
        // puts a kink at exactly t1, and at a kink the worldline gives the
        // later segment's velocity, which the picture taken at t1 (before
        // the thrust) did not have.
        frame(&mut g);
        for _ in 0..20 {
            g.thrust(DVec3::new(-0.04, 0.03, 0.01), DVec3::ZERO);
            frame(&mut g);
        }
        g.orbit(0.4, 0.1);
        for _ in 0..10 {
            frame(&mut g);
        }
        g.replay_to(t1);
        let v = g.run_seen();
        same_picture(&live, g.apparent(v).unwrap(), 1e-12);
        // Moving the eye during the replay watches the past from where it
        // now is ("replay and move"): another picture of the same time.
        g.thrust(DVec3::ZERO, DVec3::new(0.0, 0.0, 0.3));
        let v = g.run_seen();
        let moved = g.apparent(v).unwrap();
        assert!(g.replay_and_move);
        assert_eq!(moved.eye.unwrap().event.t, t1);
        assert!(
            (moved.eye.unwrap().event.position - live.eye.unwrap().event.position).length() > 0.1
        );
        g.go_live();
        assert!(!g.replay_and_move);
    }

    #[test]
    fn the_window_sees_what_headless_render_and_observe_see() {
        // The window's picture through the scene's observer, after a run of
        // frames, against a fresh simulation advanced straight to that time
        // (the path of `lightcone render` and `observe`).
        let mut g = game();
        g.observer = Some(0);
        for _ in 0..45 {
            g.step(1.0 / 60.0);
            g.run_seen();
        }
        let v = g.run_seen();
        let (sim, view) = lightcone_render::frame::scene_view(
            &g.scene,
            0,
            g.view_time,
            ViewKind::Seen,
            16.0 / 9.0,
        );
        same_picture(g.apparent(v).unwrap(), sim.apparent(view).unwrap(), 1e-12);
    }

    #[test]
    fn several_pictures_run_in_one_frame_each_with_its_eye_and_effects() {
        let mut g = game();
        g.panes = Some(Pane::parse_list("seen,truth,you:truth", &g.scene).unwrap());
        g.step(0.5);
        let panes: Vec<(Pane, f64)> = g.pane_list().into_iter().map(|p| (p, 1.0)).collect();
        let views = g.run_frame(&panes);
        assert_eq!(views.len(), 3);
        // The free eye looked through: "truth" and "you: truth" are one view.
        assert_eq!(views[1], views[2]);
        assert_eq!(g.view_effects(views[0]), g.effects);
        assert_eq!(g.view_effects(views[1]), ViewKind::Truth.effects(g.effects));
        assert!(Pane::parse_list("nobody", &g.scene).is_err());
        assert!(Pane::parse_list("you:sideways", &g.scene).is_err());
        // Fewer pictures drop the others' views.
        let one = g.run_frame(&panes[..1]);
        assert_eq!(g.sim.views(), &one[..]);
    }
}
