//! The game's state and rules, independent of the window: board time and
//! replay, the cue, the observer's flight, the effect toggles.

use glam::{DVec2, DVec3};
use lightcone_engine::optics::view::{self, Method};
use lightcone_engine::optics::{Emission, Eye, Seen};
use lightcone_engine::physics::{Billiard, CollisionKind};
use lightcone_engine::scene::{Effects, Scene};
use lightcone_engine::spacetime::{Event, ProperVelocity};

use crate::render::frame::{Camera, SceneMeshes};

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
}

/// Largest cue stroke, as a proper-velocity change (γβ): β ≈ 0.995.
pub const MAX_STROKE: f64 = 10.0;

impl GameState {
    /// A game on `scene`, starting at board time 0 looking through its first
    /// observer's eye (which the player may then fly).
    pub fn new(scene: Scene) -> Self {
        let o = &scene.observers[0];
        let f = (o.look_at - o.position).normalize_or(DVec3::Y);
        let eye = FlyingEye {
            position: o.position,
            u: ProperVelocity::ZERO,
            yaw: f.y.atan2(f.x),
            pitch: f.z.asin(),
        };
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
        }
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

    /// The eye and camera to draw with.
    pub fn eye_and_camera(&self) -> (Eye, Camera) {
        match self.observer {
            Some(i) if i < self.scene.observers.len() => {
                crate::render::frame::eye_of(&self.scene, i, self.view_time)
            }
            _ => (
                Eye {
                    event: Event::new(self.view_time, self.eye.position),
                    u: self.eye.u,
                },
                Camera {
                    forward: self.eye.forward(),
                    fovy: std::f64::consts::FRAC_PI_3,
                },
            ),
        }
    }

    /// The apparent centre (mid-height) of every puck as seen with
    /// `effects`, for clocks and picking.
    pub fn apparent_centres(&self, effects: &Effects) -> Vec<(Emission, Seen)> {
        let (eye, _) = self.eye_and_camera();
        let heights: Vec<f64> = self.scene.pucks.iter().map(|p| p.height).collect();
        (0..self.billiard.len())
            .map(|i| {
                let (mut e, mut s) = (Vec::new(), Vec::new());
                let offset = [DVec3::new(0.0, 0.0, heights[i] / 2.0)];
                view::emissions(
                    &self.billiard,
                    i,
                    &offset,
                    &eye,
                    effects,
                    Method::Exact,
                    &mut e,
                );
                view::seen(&eye, self.billiard.c(), effects, &e, &mut s);
                (e[0], s[0])
            })
            .collect()
    }

    /// Aims a stroke on `puck`: a pull of `pull` (board-plane direction and
    /// length in units of γβ) gives an impulse the opposite way, capped at
    /// [`MAX_STROKE`]. Returns the puck's velocity after the stroke.
    pub fn aim(&mut self, puck: usize, pull: DVec2) -> ProperVelocity {
        let mut du = -pull.extend(0.0);
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

    /// Restarts the scene with a new speed of light (m/s).
    pub fn restart_with_c(&mut self, c: f64) {
        if !(c.is_finite() && c > 0.0) {
            self.message = format!("c = {c} is not a positive speed");
            return;
        }
        self.scene.c = c;
        self.billiard = replay_billiard(&self.scene);
        self.live_time = 0.0;
        self.view_time = 0.0;
        self.cue = None;
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
