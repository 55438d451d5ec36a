//! The game's pictures as view entities of its simulation: one per pane
//! or CAVE eye, made, configured (effects, framing, vantage) and dropped
//! as the window asks, run by the frame schedule once a frame; and what
//! they saw (apparent bodies, cameras, puck centres) for drawing, clocks
//! and picking.

use glam::DVec3;
use lightcone_engine::ecs::{Apparent, Entity, Vantage};
use lightcone_engine::optics::{Emission, Seen};
use lightcone_engine::scene::Effects;
use lightcone_engine::spacetime::{Event, ProperVelocity};
use lightcone_engine::worldline::Worldline;
use lightcone_render::frame::{Camera, ViewKind};

use super::{EyeChoice, Framing, GameState, Pane, ViewMode};

/// Which view entity of the game's simulation a picture is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum ViewKey {
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

impl GameState {
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
            self.sim.set_view_effects(view, effects);
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
        self.forget_old_eye();
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
        self.forget_old_eye();
        let t = self.live_time;
        let u = self.eye_velocity();
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
            let _ = self.sim.place_observer(o, t, p, u);
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
}
