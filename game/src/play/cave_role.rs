//! The tracked space in the window: a tracked head (`--tracker`) or a CAVE
//! (`--cave`) moves the eye, the keys fly the whole tracked space through
//! the scene, and in a CAVE the stereo eyes are run for the walls and the
//! output windows.

use std::path::Path;
use std::time::Instant;

use glam::{DQuat, DVec3};
use lightcone_engine::ecs::Entity;
use lightcone_render::gpu::Gpu;
use lightcone_tracker::cave::CaveConfig;
use lightcone_tracker::follow::TrackerStatus;
use winit::event_loop::ActiveEventLoop;
use winit::window::WindowId;

use super::outputs::{self, OutputWindow};
use crate::cave::{self, Side, TrackedHead};
use crate::model::{Framing, GameState};

/// A tracked head and a CAVE, either or both or neither.
pub struct Immersion {
    /// The tracked head driving the eye, with `--tracker`.
    pub head: Option<TrackedHead>,
    /// The CAVE drawn, with `--cave`.
    pub cave: Option<CaveConfig>,
    /// The player's own flight added to the tracked head (board metres).
    pub flight: DVec3,
    /// Its velocity this frame, m/s.
    flight_v: DVec3,
    /// Which eye the window shows the CAVE walls for (E cycles).
    pub eye: Side,
    /// The eyes drawn this frame (the window's first, then those the
    /// outputs need): each side, its view and where it is (tracker space).
    pub stereo: Vec<(Side, Entity, DVec3)>,
    /// One window per `[[output]]` of the CAVE file.
    outputs: Vec<OutputWindow>,
    /// The master's head for this frame (a render node).
    pub node_head: Option<(DVec3, DQuat)>,
}

impl Immersion {
    /// Follows the head tracker `service` (if any) in `cave` (if any); the
    /// tracker's space is placed on the table as the CAVE file says, or
    /// as a desktop's ([`cave::desktop_map`]).
    pub fn new(service: Option<String>, cave: Option<CaveConfig>, table: glam::DVec2) -> Self {
        let map = cave
            .as_ref()
            .map_or_else(|| cave::desktop_map(table), |c| c.tracker);
        Self {
            head: service.map(|s| TrackedHead::new(&s, map)),
            cave,
            flight: DVec3::ZERO,
            flight_v: DVec3::ZERO,
            eye: Side::Mono,
            stereo: Vec::new(),
            outputs: Vec::new(),
            node_head: None,
        }
    }

    /// Whether a head or a CAVE places the eye (the keys then fly the
    /// tracked space, not the eye).
    pub fn tracked(&self) -> bool {
        self.head.is_some() || self.cave.is_some()
    }

    /// The keys fly the tracked space through the scene in direction `dir`
    /// at 1 m/s for `dt` seconds: a velocity the observer has (while time
    /// `running`), added to the head's own.
    pub fn fly(&mut self, dir: DVec3, dt: f64, running: bool) {
        self.flight_v = if running { dir } else { DVec3::ZERO };
        self.flight += dir * dt;
    }

    /// Places the game's eye for this frame: at the tracked head (which
    /// aims the camera), or at the CAVE's centre without a tracker, carried
    /// by the flight.
    pub fn place_eye(&mut self, state: &mut GameState, now: Instant) {
        match (&mut self.head, &self.cave) {
            (Some(head), _) => {
                head.poll(now);
                head.drive(state, self.flight, self.flight_v);
                state.framing = Framing::Look;
            }
            (None, Some(c)) => cave::place_untracked(state, c, self.flight, self.flight_v),
            (None, None) => {}
        }
    }

    /// The head in tracker space: the master's (a render node), the
    /// tracked one, or the default standing head.
    pub fn head(&self) -> (DVec3, DQuat) {
        self.node_head.unwrap_or_else(|| self.own_head())
    }

    /// The tracked head, or the default standing one.
    pub fn own_head(&self) -> (DVec3, DQuat) {
        self.head
            .as_ref()
            .map_or((cave::DEFAULT_HEAD, DQuat::IDENTITY), TrackedHead::head)
    }

    /// Publication time (Unix ns) of the newest tracker sample accepted.
    pub fn newest_sample_ns(&self) -> Option<u64> {
        self.head.as_ref().and_then(TrackedHead::newest_sample_ns)
    }

    /// Runs the CAVE's stereo eyes this frame (the window's eye, then
    /// those the outputs need). Returns false without a CAVE.
    pub fn run_stereo(&mut self, state: &mut GameState) -> bool {
        let Some(c) = &self.cave else {
            return false;
        };
        let sides = cave::sides_needed(c, self.eye);
        let views = cave::stereo_views(state, c, self.head(), &sides, self.flight);
        self.stereo = sides
            .into_iter()
            .zip(views)
            .map(|(side, (view, eye))| (side, view, eye))
            .collect();
        true
    }

    /// E: the walls for the next eye (mono, left, right).
    pub fn cycle_eye(&mut self) {
        self.eye = match self.eye {
            Side::Mono => Side::Left,
            Side::Left => Side::Right,
            Side::Right => Side::Mono,
        }
    }

    /// The tracker's status line for the panel (with a CAVE: which eye
    /// the walls are for, and the cluster's `cluster` status line).
    pub fn status_line(&self, cluster: Option<String>) -> Option<String> {
        let line = match (&self.head, &self.cave) {
            (Some(h), _) => h.status_line(),
            (None, Some(_)) => "no tracker: the head stands at the CAVE's centre".to_owned(),
            (None, None) => return None,
        };
        Some(match &self.cave {
            Some(_) => format!(
                "{line}\nCAVE walls, {} eye (E switches){}",
                self.eye.name(),
                cluster.map(|s| format!("\n{s}")).unwrap_or_default()
            ),
            None => line,
        })
    }

    /// The status line's colour: green while the tracker is live.
    pub fn status_colour(&self) -> egui::Color32 {
        match self.head.as_ref().and_then(TrackedHead::status) {
            Some(TrackerStatus::Live) => egui::Color32::LIGHT_GREEN,
            _ => egui::Color32::LIGHT_RED,
        }
    }

    /// Opens a window per output of the CAVE, with `instance`.
    pub fn open_outputs(
        &mut self,
        event_loop: &ActiveEventLoop,
        instance: &wgpu::Instance,
    ) -> Result<(), String> {
        if let Some(c) = &self.cave {
            self.outputs = outputs::open(event_loop, instance, c)?;
        }
        Ok(())
    }

    /// Configures the outputs' surfaces for `gpu`.
    pub fn configure_outputs(&mut self, gpu: &Gpu) -> Result<(), String> {
        self.outputs.iter_mut().try_for_each(|o| o.configure(gpu))
    }

    /// The output whose window is `id`, if one is.
    pub fn output(&mut self, id: WindowId) -> Option<&mut OutputWindow> {
        self.outputs.iter_mut().find(|o| o.id() == id)
    }

    /// Draws this frame's views on every output (each its wall); with
    /// `shot`, saves each beside the main window's screenshot.
    pub fn draw_outputs(
        &mut self,
        gpu: &Gpu,
        state: &GameState,
        shot: Option<&Path>,
    ) -> Result<(), String> {
        let Some(c) = &self.cave else {
            return Ok(());
        };
        for o in &mut self.outputs {
            o.draw(gpu, state, c, &self.stereo, shot)?;
        }
        Ok(())
    }
}
