//! The free eye ("you"): where it looks, and every move of it (thrust,
//! halt, orbit, a view from above, taking over a scene observer) written
//! on its observer's worldline; and the eye looked through now.

use glam::DVec3;
use lightcone_engine::ecs::Vantage;
use lightcone_engine::ecs::systems::optics::eye_at;
use lightcone_engine::optics::Eye;
use lightcone_engine::scene::Scene;
use lightcone_engine::spacetime::{Event, ProperVelocity};

use super::{EyeChoice, Framing, GameState, REPLAY_WINDOW, ViewKey};

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

impl GameState {
    /// The free eye's proper velocity now (at the live board time).
    pub fn eye_velocity(&self) -> ProperVelocity {
        self.eye.u
    }

    /// The free eye at rest where observer `i` of `scene` stands at t = 0,
    /// looking where it looks.
    pub(super) fn eye_at_observer(scene: &Scene, i: usize) -> FlyingEye {
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
    pub(super) fn sync_eye(&mut self) {
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
}
