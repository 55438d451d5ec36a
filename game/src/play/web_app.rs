//! The game's frame in a browser tab (wasm32): what [`super::app`] does
//! for the desktop window, without what needs the desktop (a lesson's
//! Python process, the tracked head, CAVE outputs, the render cluster,
//! screenshots to files). The same model, frame schedule, renderer,
//! panels, keys, cue, camera and split views, in [`super::window`] on
//! the page's canvas.

use web_time::Instant;
use winit::event::WindowEvent;
use winit::window::WindowId;

use super::actions::UiAction;
use super::input::Input;
use super::layout::SceneArea;
use super::panels::{self, Hud};
use super::pictures::Pictures;
use super::shown::aspect;
use super::window::{self, Flow, Gfx};
use crate::model::{GameState, Pane};

/// Starts the game on the page: the shipped scene `scene` (a file name of
/// [`crate::assets::SCENES`], `.toml` optional), or the default one when
/// `scene` is `None`. A scene that is not shipped, or does not parse, is
/// an error naming it (the page shows it). Returns once the event loop
/// is running (the browser drives it).
pub fn start(scene: Option<&str>) -> Result<(), String> {
    let game = GameState::new(load(scene)?);
    window::spawn(WebApp::new(game))
}

/// The shipped scene named `name`, or the default one.
fn load(name: Option<&str>) -> Result<lightcone_engine::scene::Scene, String> {
    let Some(name) = name else {
        return crate::assets::default_scene().map_err(|e| e.to_string());
    };
    let file = if name.ends_with(".toml") {
        name.to_owned()
    } else {
        format!("{name}.toml")
    };
    match crate::assets::shipped_scene(&file) {
        Some(scene) => scene.map_err(|e| e.to_string()),
        None => {
            let names: Vec<&str> = crate::assets::SCENES.iter().map(|(n, _)| *n).collect();
            Err(format!(
                "?scene={name}: not a shipped scene (one of {})",
                names.join(", ")
            ))
        }
    }
}

/// The game in the page's canvas.
struct WebApp {
    state: GameState,
    input: Input,
    /// The scene renderer (made once the GPU is open).
    pictures: Option<Pictures>,
    /// When the last frame began.
    last: Instant,
    /// The area the last frame's panels left for the pictures.
    area: SceneArea,
    /// Frames drawn so far (the page's test waits for the first).
    frames: u64,
}

impl WebApp {
    fn new(state: GameState) -> Self {
        Self {
            state,
            input: Input::new(false),
            pictures: None,
            last: Instant::now(),
            area: SceneArea::default(),
            frames: 0,
        }
    }

    /// Carries out what the keys and panels asked; the window's own
    /// actions (the CAVE's eye, a lesson's) have nothing to act on here.
    fn act(&mut self, actions: Vec<UiAction>) {
        for action in actions {
            let _ = action.apply(&mut self.state);
        }
    }

    /// The pictures' rectangles in a canvas of `size`.
    fn rects(&self, (w, h): (u32, u32)) -> Vec<([f32; 4], Pane)> {
        self.area.rects(&self.state.pane_list(), w as f32, h as f32)
    }

    /// Runs the frame schedule for the pictures laid out in `size`.
    fn run_views(&mut self, size: (u32, u32)) {
        let panes: Vec<(Pane, f64)> = self
            .rects(size)
            .into_iter()
            .map(|(r, p)| (p, aspect(r)))
            .collect();
        self.state.run_frame(&panes);
    }

    /// Runs the panels; returns them to paint, the area they leave and
    /// what they asked.
    fn panels(&mut self, gfx: &mut Gfx) -> (window::Ui, SceneArea, Vec<UiAction>) {
        let size = gfx.size();
        let mut area = self.area;
        let mut actions = Vec::new();
        let hud = Hud {
            tracker: None,
            tracker_colour: egui::Color32::GRAY,
            clocks: true,
            lesson: None,
            lessons: false,
        };
        let state = &mut self.state;
        let ui = gfx.run_ui(|ui| {
            area = panels::panels(ui, state, &hud, None, size, &mut actions);
        });
        (ui, area, actions)
    }
}

impl window::Game for WebApp {
    fn title(&self) -> String {
        format!("Lightcone: {}", self.state.scene.title)
    }

    fn ready(&mut self, gfx: &Gfx) -> Result<(), String> {
        self.pictures = Some(Pictures::new(&gfx.gpu, gfx.config.format, gfx.size()));
        Ok(())
    }

    fn input(&mut self, gfx: &Gfx, event: &WindowEvent, consumed: bool) {
        let rects = self.rects(gfx.size());
        let mut actions = Vec::new();
        self.input
            .event(event, consumed, &mut self.state, &rects, &mut actions);
        self.act(actions);
    }

    fn other_window(
        &mut self,
        _gfx: &Gfx,
        _id: WindowId,
        _event: &WindowEvent,
    ) -> Option<Result<Flow, String>> {
        None
    }

    fn frame(&mut self, gfx: &mut Gfx) -> Result<Flow, String> {
        let now = Instant::now();
        let dt = (now - self.last).as_secs_f64().min(0.1);
        self.last = now;
        // Held keys fly the eye at a proper acceleration of 0.5 c per
        // second, as in the window.
        let dir = self.input.flight(self.state.forward());
        if dir != glam::DVec3::ZERO {
            self.state.thrust(dir * 0.5 * dt, dir * 1.0 * dt);
        }
        self.state.step(dt);
        let size = gfx.size();
        self.run_views(size);
        let (ui, area, actions) = self.panels(gfx);
        if area != self.area {
            self.area = area;
            self.run_views(size);
        }
        self.act(actions);
        let texture = gfx.next_texture();
        let target = texture.as_ref().map(|t| {
            t.texture
                .create_view(&wgpu::TextureViewDescriptor::default())
        });
        if let (Some(target), Some(pictures)) = (&target, &mut self.pictures) {
            let (w, h) = (size.0 as f32, size.1 as f32);
            let plans = self.area.plans(None, &self.state.pane_list(), w, h);
            pictures.draw(&gfx.gpu, target, size, &plans, &self.state, None);
        }
        gfx.paint_ui(ui, target.as_ref());
        if let Some(texture) = texture {
            gfx.gpu.queue.present(texture);
            self.frames += 1;
            if self.frames == 1 {
                first_frame_drawn();
            }
        }
        Ok(Flow::Continue)
    }
}

/// Notes on the page that the first frame was drawn: its time since the
/// page began loading (ms, `performance.now()`) becomes
/// `window.lightconeFirstFrameMs`, for the browser test and the
/// benchmark, and is logged to the console.
fn first_frame_drawn() {
    let Some(page) = web_sys::window() else {
        return;
    };
    let ms = page.performance().map_or(f64::NAN, |p| p.now());
    let _ = web_sys::js_sys::Reflect::set(&page, &"lightconeFirstFrameMs".into(), &ms.into());
    web_sys::console::log_1(&format!("lightcone: first frame drawn at {ms:.0} ms").into());
}
