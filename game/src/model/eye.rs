//! The free eye ("you"): its state is its observer's worldline (where it
//! is and how fast it moves, at every board time), and [`FlyingEye`] keeps
//! only where it looks. Every move (thrust, halt, orbit, a view from
//! above, taking over a scene observer, a tracked pose) is a kink or a
//! jump written on that worldline at the live board time.

use glam::DVec3;
use lightcone_engine::ecs::Vantage;
use lightcone_engine::ecs::systems::optics::eye_at;
use lightcone_engine::optics::Eye;
use lightcone_engine::scene::Scene;
use lightcone_engine::spacetime::{Event, ProperVelocity};

use super::{EyeChoice, Framing, GameState, REPLAY_WINDOW, ViewKey};

/// Where the eye the player flies looks (where it is and how it moves is
/// its worldline's: [`GameState::eye_position`], [`GameState::eye_velocity`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlyingEye {
    /// Heading about z, radians (0 looks along +x).
    pub yaw: f64,
    /// Elevation, radians (negative looks down).
    pub pitch: f64,
}

impl FlyingEye {
    /// Looking along `f` (board axes; need not be unit).
    pub fn along(f: DVec3) -> Self {
        let f = f.normalize_or(DVec3::Y);
        Self {
            yaw: f.y.atan2(f.x),
            pitch: f.z.clamp(-1.0, 1.0).asin(),
        }
    }

    /// Unit viewing direction, board axes.
    pub fn forward(&self) -> DVec3 {
        DVec3::new(
            self.pitch.cos() * self.yaw.cos(),
            self.pitch.cos() * self.yaw.sin(),
            self.pitch.sin(),
        )
    }
}

/// Where observer `i` of `scene` stands at t = 0 (board frame, m), and
/// where it looks.
pub(super) fn at_observer(scene: &Scene, i: usize) -> (DVec3, FlyingEye) {
    let o = &scene.observers[i.min(scene.observers.len() - 1)];
    (
        o.position,
        FlyingEye::along(o.target(scene.table.size) - o.position),
    )
}

impl GameState {
    /// The free eye's position at the live board time (board frame, m):
    /// its worldline's event then.
    pub fn eye_position(&self) -> DVec3 {
        // The game made the free eye's observer, and never removes it.
        self.sim
            .observer_worldline(self.you)
            .map_or(DVec3::ZERO, |w| w.position_at(self.live_time))
    }

    /// The free eye's proper velocity at the live board time (after a kink
    /// at that time, the new one).
    pub fn eye_velocity(&self) -> ProperVelocity {
        self.sim
            .observer_worldline(self.you)
            .map_or(ProperVelocity::ZERO, |w| {
                w.proper_velocity_at(self.live_time)
            })
    }

    /// Puts the free eye at `position` moving with `u` from the live board
    /// time on (a tracked pose, an orbit, a reset): a jump on its worldline
    /// when it is put somewhere else (during a replay, its pictures then
    /// watch the past from where it now is: "replay and move"), a kink
    /// when only its velocity changes, nothing when neither does.
    pub fn move_eye(&mut self, position: DVec3, u: ProperVelocity) {
        let t = self.live_time;
        let Some(w) = self.sim.observer_worldline(self.you) else {
            return;
        };
        let st = w.state_at(t);
        let tol = 1e-9 * (1.0 + position.length());
        if (st.position - position).length() > tol {
            if self.replaying() {
                self.replay_and_move = true;
            }
            // Fails only for a state that is not finite (refused): the
            // live time never goes back (a restart makes a new
            // simulation).
            let _ = self.sim.place_observer(self.you, t, position, u);
        } else if st.u != u {
            self.steer_eye(u);
        }
    }

    /// A kink on the free eye's worldline at the live time: from now on it
    /// moves with proper velocity `u` (a velocity change, not a jump).
    fn steer_eye(&mut self, u: ProperVelocity) {
        let t = self.live_time;
        let _ = self.sim.steer_observer(self.you, t, u);
    }

    /// Forgets the free eye's worldline older than the replay window, as
    /// the physics forgets the pucks'.
    pub(super) fn forget_old_eye(&mut self) {
        let t = self.live_time - REPLAY_WINDOW;
        self.sim.forget_observer_before(self.you, t);
    }

    /// Back to the default view: the camera fitted to the table, no zoom,
    /// following nothing; the free eye back where the scene's first
    /// observer stands, at rest.
    pub fn reset_view(&mut self) {
        self.framing = Framing::Fit;
        self.zoom = 1.0;
        self.follow = None;
        if self.observer.is_none() {
            let (position, look) = at_observer(&self.scene, 0);
            self.eye = look;
            self.move_eye(position, ProperVelocity::ZERO);
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
            self.eye = FlyingEye::along(o.target(self.scene.table.size) - o.position);
            self.move_eye(st.position, st.u);
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
        let d = self.eye_position() - target;
        let r = d.length().max(0.1);
        let horizontal = d.truncate().length();
        let azimuth = if horizontal > 1e-9 {
            d.y.atan2(d.x)
        } else {
            -std::f64::consts::FRAC_PI_2
        } + yaw;
        let elevation = (d.z / r).clamp(-1.0, 1.0).asin() + pitch;
        let elevation = elevation.clamp(3f64.to_radians(), 89.9f64.to_radians());
        let position = target
            + r * DVec3::new(
                elevation.cos() * azimuth.cos(),
                elevation.cos() * azimuth.sin(),
                elevation.sin(),
            );
        self.eye = FlyingEye::along(target - position);
        self.move_eye(position, self.eye_velocity());
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
            yaw: std::f64::consts::FRAC_PI_2,
            pitch: -std::f64::consts::FRAC_PI_2 + 1e-6,
        };
        self.move_eye((size / 2.0).extend(height), ProperVelocity::ZERO);
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
            self.eye = FlyingEye::along(start);
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

    /// Accelerates the flying eye: a kink adding `du` to its proper
    /// velocity (thrust of any size never reaches c). While paused or
    /// replaying, moves it by `step` metres instead (a frozen picture has
    /// no board time to fly in).
    pub fn thrust(&mut self, du: DVec3, step: DVec3) {
        let u = self.eye_velocity();
        if self.paused || self.replaying() {
            self.move_eye(self.eye_position() + step, u);
        } else if du.is_finite() {
            self.steer_eye(ProperVelocity(u.0 + du));
        }
    }

    /// Stops the flying eye.
    pub fn halt(&mut self) {
        self.steer_eye(ProperVelocity::ZERO);
    }

    /// The free eye's vantage: on its worldline (live, and in a replay:
    /// what it saw then), or watching the past from where it is now.
    pub(super) fn you_vantage(&self) -> Vantage {
        if self.replaying() && self.replay_and_move {
            Vantage::ReplayAndMove {
                now: self.live_time,
            }
        } else {
            Vantage::OnWorldline
        }
    }

    /// The scene observer a pane's eye is (`None`: the free eye).
    pub(super) fn resolve(&self, eye: EyeChoice) -> Option<usize> {
        let n = self.observers.len();
        match eye {
            EyeChoice::Current => self.observer.filter(|&i| i < n),
            EyeChoice::You => None,
            EyeChoice::Scene(i) => Some(i).filter(|&i| i < n),
        }
    }

    /// The eye looked through now (a scene observer's or the free one), as
    /// the pictures of the next frame see from: its observer's worldline
    /// at the board time shown.
    pub fn eye(&self) -> Eye {
        let (observer, vantage) = match self.resolve(EyeChoice::Current) {
            Some(i) => (self.observers[i], Vantage::OnWorldline),
            None => (self.you, self.you_vantage()),
        };
        match self.sim.observer_worldline(observer) {
            Some(w) => eye_at(w, vantage, self.view_time),
            // Never: the game made every observer it looks through.
            None => Eye {
                event: Event::new(self.view_time, self.eye_position()),
                u: self.eye_velocity(),
            },
        }
    }
}
