//! The game's frame as the desktop window ([`super::app`]) and the
//! browser page (`web_app`) both draw it: the views run for the
//! room the panels leave, the panels, what they asked carried out, the
//! pictures under them, the panels painted over. Each front end is a
//! [`Host`] that adds its own parts (a lesson, the CAVE's walls, a share
//! button), so there is one frame, not one per platform.

use web_time::Instant;
use winit::event::WindowEvent;

use super::actions::UiAction;
use super::input::Input;
use super::layout::SceneArea;
use super::pictures::{Pictures, Walls};
use super::shown::aspect;
use super::window::{self, Gfx};
use crate::model::{GameState, Pane};

/// What a front end adds to the shared frame.
pub trait Host {
    /// Runs this frame's views itself (the CAVE's stereo eyes); returns
    /// `false` when the stage is to run the desktop panes.
    fn run_views(&mut self, _state: &mut GameState) -> bool {
        false
    }

    /// This frame's panels (in egui's root `ui`, a surface of `size`
    /// physical px); clicks become `actions`. Returns the area left for
    /// the pictures.
    fn panels(
        &mut self,
        ui: &mut egui::Ui,
        state: &mut GameState,
        size: (u32, u32),
        actions: &mut Vec<UiAction>,
    ) -> SceneArea;

    /// Carries out an action the game's own table handed back
    /// ([`UiAction::apply`]: a lesson's, the CAVE's, a share).
    fn act(&mut self, action: UiAction, state: &mut GameState);

    /// The CAVE walls drawn in place of the desktop views, if any.
    fn walls(&self) -> Option<Walls<'_>> {
        None
    }
}

/// The game on screen: its state, the player's input, the scene renderer
/// and the room the last frame's panels left.
pub struct Stage {
    /// The game.
    pub state: GameState,
    /// Keys, pointer and the cue.
    pub input: Input,
    /// The scene renderer (made once the GPU is open).
    pub pictures: Option<Pictures>,
    /// The area the last frame's panels left for the pictures.
    pub area: SceneArea,
    /// When the last frame began.
    last: Instant,
}

impl Stage {
    /// The stage of `state`; `lessons` when the front end can start
    /// lessons (the desktop game).
    pub fn new(state: GameState, lessons: bool) -> Self {
        Self {
            state,
            input: Input::new(lessons),
            pictures: None,
            area: SceneArea::default(),
            last: Instant::now(),
        }
    }

    /// Opens the scene renderer for `gfx`'s surface.
    pub fn ready(&mut self, gfx: &Gfx) {
        self.pictures = Some(Pictures::new(
            &gfx.gpu,
            gfx.config.format,
            gfx.size(),
            gfx.gpu.window_samples(),
        ));
    }

    /// Starts a frame: now, and the real time since the last one (s, at
    /// most 0.1 so that a stalled frame does not jump the game).
    pub fn tick(&mut self) -> (Instant, f64) {
        let now = Instant::now();
        let dt = (now - self.last).as_secs_f64().min(0.1);
        self.last = now;
        (now, dt)
    }

    /// Flies the free eye along the held keys for `dt` s at a proper
    /// acceleration of 0.5 c per second (W/S, A/D, R/F).
    pub fn fly_free(&mut self, dt: f64) {
        let dir = self.input.flight(self.state.forward());
        if dir != glam::DVec3::ZERO {
            self.state.thrust(dir * 0.5 * dt, dir * 1.0 * dt);
        }
    }

    /// The pictures' rectangles in a surface of `size`, between the edges
    /// the last frame's panels left.
    pub fn rects(&self, (w, h): (u32, u32)) -> Vec<([f32; 4], Pane)> {
        self.area.rects(&self.state.pane_list(), w as f32, h as f32)
    }

    /// Runs the frame schedule for what this frame draws: the host's own
    /// views (the CAVE's eyes), or the desktop pictures laid out in a
    /// surface of `size`. Everything drawn next (the views, clocks, labels
    /// and picking) reads what it wrote.
    pub fn run_views(&mut self, host: &mut impl Host, size: (u32, u32)) {
        if host.run_views(&mut self.state) {
            return;
        }
        let panes: Vec<(Pane, f64)> = self
            .rects(size)
            .into_iter()
            .map(|(r, p)| (p, aspect(r)))
            .collect();
        self.state.run_frame(&panes);
    }

    /// Carries out what the keys and panels asked, in order: the game's
    /// action table first, then the host for what it hands back.
    pub fn act(&mut self, host: &mut impl Host, actions: Vec<UiAction>) {
        for action in actions {
            if let Some(left) = action.apply(&mut self.state) {
                host.act(left, &mut self.state);
            }
        }
    }

    /// An event of the main window (`consumed` when egui took it).
    pub fn input(&mut self, host: &mut impl Host, gfx: &Gfx, event: &WindowEvent, consumed: bool) {
        let rects = self.rects(gfx.size());
        let mut actions = Vec::new();
        self.input
            .event(event, consumed, &mut self.state, &rects, &mut actions);
        self.act(host, actions);
    }

    /// Draws the frame: the views (unless `views_done`: run already this
    /// frame), the panels, the views again if the panels took another
    /// width, what they asked, then the pictures and the panels over them.
    /// Returns the surface's texture, not yet presented (the window takes
    /// its screenshot first), or `None` when the surface gave none.
    pub fn draw(
        &mut self,
        host: &mut impl Host,
        gfx: &mut Gfx,
        views_done: bool,
    ) -> Option<wgpu::SurfaceTexture> {
        let size = gfx.size();
        if !views_done {
            self.run_views(host, size);
        }
        let (ui, area, actions) = self.panels(host, gfx);
        if area != self.area {
            // The panels took another width (the first frame, a resize):
            // frame the views for the room they now leave.
            self.area = area;
            self.run_views(host, size);
        }
        self.act(host, actions);
        let texture = gfx.next_texture();
        let target = texture.as_ref().map(|t| {
            t.texture
                .create_view(&wgpu::TextureViewDescriptor::default())
        });
        if let (Some(target), Some(pictures)) = (&target, &mut self.pictures) {
            let (w, h) = (size.0 as f32, size.1 as f32);
            let walls = host.walls();
            let plans = self
                .area
                .plans(walls.map(|w| w.0), &self.state.pane_list(), w, h);
            pictures.draw(&gfx.gpu, target, size, &plans, &self.state, walls);
        }
        gfx.paint_ui(ui, target.as_ref());
        texture
    }

    /// Runs the host's panels; returns them to paint, the area they leave
    /// and what they asked.
    fn panels(
        &mut self,
        host: &mut impl Host,
        gfx: &mut Gfx,
    ) -> (window::Ui, SceneArea, Vec<UiAction>) {
        let size = gfx.size();
        let mut area = self.area;
        let mut actions = Vec::new();
        let (state, input) = (&mut self.state, &mut self.input);
        let ui = gfx.run_ui(|ui| {
            input.keys(ui.ctx(), state, &mut actions);
            area = host.panels(ui, state, size, &mut actions);
        });
        (ui, area, actions)
    }
}
