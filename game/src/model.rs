//! The game's state and rules, independent of the window: board time and
//! replay, the cue, the observer's flight, the effect toggles.

use glam::{DVec2, DVec3};
use lightcone_engine::optics::view::{self, Method};
use lightcone_engine::optics::{Emission, Eye, Seen};
use lightcone_engine::physics::{Billiard, CollisionKind};
use lightcone_engine::scene::{Effects, Scene};
use lightcone_engine::spacetime::{Event, ProperVelocity};

use lightcone_render::frame::{Camera, SceneMeshes};

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
    /// Eye position at [`GameState::view_time`], board frame, m.
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

/// Margin kept around the fitted table, as a fraction of the view's
/// half-size.
pub const FIT_MARGIN: f64 = 0.08;

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

/// The billiard of a scene, keeping [`REPLAY_WINDOW`] of history.
fn replay_billiard(scene: &lightcone_engine::scene::Scene) -> Billiard {
    let mut billiard = Billiard::from_scene(scene);
    billiard.set_history(Some(REPLAY_WINDOW));
    billiard
}

/// Everything the game keeps between frames.
pub struct GameState {
    /// The scene as loaded (its `c` may be changed by the slider).
    pub scene: Scene,
    /// The physics.
    pub billiard: Billiard,
    /// Meshes for drawing.
    pub meshes: SceneMeshes,
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
    /// The free eye.
    pub eye: FlyingEye,
    /// `Some(i)`: look through the scene's observer `i` instead.
    pub observer: Option<usize>,
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
}

/// Largest cue stroke, as a proper-velocity change (γβ): β ≈ 0.995.
pub const MAX_STROKE: f64 = 10.0;

impl GameState {
    /// A game on `scene`, starting at board time 0 looking through its first
    /// observer's eye (which the player may then fly).
    pub fn new(scene: Scene) -> Self {
        let eye = Self::eye_at_observer(&scene, 0);
        Self {
            billiard: replay_billiard(&scene),
            meshes: SceneMeshes::new(&scene),
            effects: scene.effects,
            scene,
            live_time: 0.0,
            view_time: 0.0,
            paused: false,
            time_scale: 1.0,
            view: ViewMode::Seen,
            eye,
            observer: None,
            cue: None,
            message: String::new(),
            framing: Framing::Fit,
            zoom: 1.0,
            follow: None,
            intro: false,
            show: Overlays::default(),
            scene_menu: Default::default(),
        }
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
    /// place, velocity and direction), so the player can move it.
    fn take_over(&mut self) {
        if let Some(i) = self.observer.take()
            && i < self.scene.observers.len()
        {
            let (eye, _) = lightcone_render::frame::eye_of(&self.scene, i, self.view_time);
            let o = &self.scene.observers[i];
            let f = (o.target(self.scene.table.size) - o.position).normalize_or(DVec3::Y);
            self.eye = FlyingEye {
                position: eye.event.position,
                u: eye.u,
                yaw: f.y.atan2(f.x),
                pitch: f.z.clamp(-1.0, 1.0).asin(),
            };
        }
    }

    /// The point orbits turn about: the followed puck (where it is now) or
    /// the table's centre.
    pub fn orbit_target(&self) -> DVec3 {
        match self.follow {
            Some(i) if i < self.billiard.len() => {
                self.billiard.worldline(i).position_at(self.view_time)
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
        self.take_over();
        if self.framing == Framing::Fit {
            // Start from where the fitted camera looks.
            let (_, cam) = self.eye_and_camera(1.0);
            let f = cam.forward.normalize_or(DVec3::Y);
            self.eye.yaw = f.y.atan2(f.x);
            self.eye.pitch = f.z.clamp(-1.0, 1.0).asin();
            self.framing = Framing::Look;
        }
        self.eye.yaw += dyaw;
        self.eye.pitch = (self.eye.pitch + dpitch).clamp(-1.5, 1.5);
    }

    /// Whether the picture is a replay of the past (not live).
    pub fn replaying(&self) -> bool {
        self.view_time < self.live_time
    }

    /// Advances by `real_dt` seconds of wall-clock time: the board clock by
    /// `real_dt × time_scale` unless paused or replaying, the flying eye with
    /// its velocity over the same board time.
    pub fn step(&mut self, real_dt: f64) {
        if self.paused || !real_dt.is_finite() || real_dt <= 0.0 {
            return;
        }
        let dt = real_dt * self.time_scale;
        if self.replaying() {
            self.view_time = (self.view_time + dt).min(self.live_time);
        } else {
            self.live_time += dt;
            self.billiard.advance_to(self.live_time);
            self.view_time = self.live_time;
        }
        self.eye.position += self.eye.u.velocity(self.scene.c) * dt;
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
        }
    }

    /// Stops the flying eye.
    pub fn halt(&mut self) {
        self.eye.u = ProperVelocity::ZERO;
    }

    /// The eye looked through now: a scene observer's or the free one.
    pub fn eye(&self) -> Eye {
        match self.observer {
            Some(i) if i < self.scene.observers.len() => {
                lightcone_render::frame::eye_of(&self.scene, i, self.view_time).0
            }
            _ => Eye {
                event: Event::new(self.view_time, self.eye.position),
                u: self.eye.u,
            },
        }
    }

    /// The eye and the camera to draw a view of `aspect` (width / height)
    /// with: fitted to the table (and turned to the followed puck), or
    /// where the free eye looks; zoomed.
    pub fn eye_and_camera(&self, aspect: f64) -> (Eye, Camera) {
        let eye = self.eye();
        let camera = match self.framing {
            Framing::Look => lightcone_render::camera::zoomed(
                self.eye.forward(),
                std::f64::consts::FRAC_PI_3,
                self.zoom,
            ),
            Framing::Fit => {
                let c = self.scene.c;
                let points: Vec<DVec3> = lightcone_render::camera::table_corners(
                    self.scene.table.size,
                    lightcone_render::frame::CUSHION_HEIGHT,
                    lightcone_render::frame::CUSHION_WIDTH,
                )
                .into_iter()
                .map(|p| eye.see_static(p, c, self.effects.aberration).position)
                .collect();
                let mut cam = lightcone_render::camera::fit(&points, aspect, FIT_MARGIN, self.zoom);
                if let Some(i) = self.follow.filter(|&i| i < self.billiard.len()) {
                    let (_, seen) = self.apparent_centre(&eye, &self.effects, i);
                    if seen.position.length() > 1e-9 {
                        cam.forward = seen.position.normalize();
                    }
                }
                cam
            }
        };
        (eye, camera)
    }

    /// The apparent centre (mid-height) of every puck as seen with
    /// `effects`, for clocks and picking.
    pub fn apparent_centres(&self, effects: &Effects) -> Vec<(Emission, Seen)> {
        let eye = self.eye();
        (0..self.billiard.len())
            .map(|i| self.apparent_centre(&eye, effects, i))
            .collect()
    }

    /// The apparent centre (mid-height) of puck `i` as `eye` sees it with
    /// `effects`.
    pub fn apparent_centre(&self, eye: &Eye, effects: &Effects, i: usize) -> (Emission, Seen) {
        let height = self.scene.pucks.get(i).map_or(0.0, |p| p.height);
        let (mut e, mut s) = (Vec::new(), Vec::new());
        let offset = [DVec3::new(0.0, 0.0, height / 2.0)];
        view::emissions(
            &self.billiard,
            i,
            &offset,
            eye,
            effects,
            Method::Exact,
            &mut e,
        );
        view::seen(eye, self.billiard.c(), effects, &e, &mut s);
        (e[0], s[0])
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
        ProperVelocity(self.billiard.worldline(puck).velocity_at(self.live_time).0 + du)
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
        self.billiard
            .apply_impulse(cue.puck, self.live_time, cue.du)
            .map_err(|e| e.to_string())
    }

    /// Restarts the scene with a new speed of light (m/s), each puck (and
    /// observer) keeping its proper velocity in m/s, `γ v`: its momentum
    /// (see [`Scene::with_c`]). Raising c tends to Newton.
    pub fn restart_with_c(&mut self, c: f64) {
        match self.scene.with_c(c) {
            Ok(scene) => self.scene = scene,
            Err(e) => {
                self.message = e;
                return;
            }
        }
        self.billiard = replay_billiard(&self.scene);
        self.live_time = 0.0;
        self.view_time = 0.0;
        self.cue = None;
    }

    /// Starts the scene again from board time 0 (same c, same eye).
    pub fn restart(&mut self) {
        self.restart_with_c(self.scene.c);
    }

    /// A line about the latest collision shown (at or before the view time).
    pub fn last_collision(&self) -> Option<String> {
        let c = self
            .billiard
            .collisions()
            .iter()
            .rev()
            .find(|c| c.t <= self.view_time)?;
        let names: Vec<&str> = c.pucks.iter().map(|p| self.billiard.name(p.puck)).collect();
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
        assert!(after.speed_deficit() > 0.0);
        assert!((after.0.x - MAX_STROKE).abs() < 1e-12);
        g.strike().unwrap();
        g.step(0.1);
        assert!(g.billiard.worldline(1).velocity_at(g.live_time).0.x > 9.0);
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
        assert!(g.eye.u.speed_deficit() > 0.0);
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
        // Slow light: the same momentum, never c.
        g.restart_with_c(0.01);
        assert!(g.scene.pucks[0].u.speed_deficit() > 0.0);
        assert!((g.scene.pucks[0].u.0 * 0.01 - before[0]).length() < 1e-12);
    }

    #[test]
    fn changing_c_restarts() {
        let mut g = game();
        g.step(1.0);
        g.restart_with_c(3.0);
        assert_eq!(g.billiard.c(), 3.0);
        assert_eq!(g.live_time, 0.0);
        g.restart_with_c(-1.0);
        assert_eq!(g.billiard.c(), 3.0);
        assert!(!g.message.is_empty());
    }
}
