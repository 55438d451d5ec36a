//! The window: winit events, the wgpu surface, the scene renderer and the
//! egui panels. The rules live in [`crate::model`].

use std::collections::HashSet;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use glam::{DVec2, DVec3};
use lightcone_engine::scene::Effect;
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

use super::lesson_panel::{self, LessonAction};
use super::outputs::{self, OutputWindow};
use super::overlay::{aspect, markers, overlays, project, ring_colour};
use crate::cave::{self, Side, TrackedHead};
use crate::cluster::master::ClusterMaster;
use crate::cluster::node::{ClusterNode, Headless};
use crate::lesson::LessonHost;
use crate::model::{GameState, Pane, ViewMode};
use lightcone_render::frame::{self, FrameVertex, ViewKind};
use lightcone_render::gpu::{self, Gpu};
use lightcone_render::headless::BACKGROUND;
use lightcone_render::pipeline::{Draw, Renderer};
use lightcone_tracker::cave::CaveConfig;
use lightcone_tracker::follow::TrackerStatus;

/// How `play` runs.
pub struct Options {
    /// The game to start with.
    pub game: GameState,
    /// The lesson driving it, if one was given.
    pub lesson: Option<LessonHost>,
    /// iceoryx2 service of a head tracker driving the observer.
    pub tracker: Option<String>,
    /// A CAVE whose walls are drawn instead of the desktop views.
    pub cave: Option<CaveConfig>,
    /// Save a screenshot of frame `frames` to this PNG and quit (for docs
    /// and the Xvfb test).
    pub screenshot: Option<PathBuf>,
    /// Frames to run before the screenshot.
    pub frames: u32,
    /// The render cluster this game is the master of (`--serve`).
    pub cluster: Option<ClusterMaster>,
    /// Log each frame's CAVE eyes to this file (`--frame-log`).
    pub frame_log: Option<PathBuf>,
}

/// Opens the window and runs the game until it is closed.
pub fn run(options: Options) -> Result<(), String> {
    let event_loop = open_event_loop()?;
    let mut app = App::new(options)?;
    event_loop
        .run_app(&mut app)
        .map_err(|e| format!("the window's event loop failed: {e}"))?;
    app.result
}

/// Opens the window of a render node (`lightcone wall`) on its walls, once
/// the master's first frame is in; runs until the master is silent for
/// `options.silence`, `options.frames` frames were shown, or the window is
/// closed. Returns the frames shown.
pub fn run_node(mut node: ClusterNode, options: &Headless) -> Result<u64, String> {
    let event_loop = open_event_loop()?;
    let mut game = crate::cluster::node::placeholder()?;
    let Some(first) = node.next_frame(&mut game, options.silence)? else {
        return Err(format!("no frame from the master in {:?}", options.silence));
    };
    let cave = node
        .cave
        .clone()
        .ok_or("the master's snapshot had no CAVE")?;
    let mut app = App::new(Options {
        game,
        lesson: None,
        tracker: None,
        cave: Some(cave),
        screenshot: options.screenshot.clone(),
        frames: u32::try_from(options.frames).unwrap_or(u32::MAX).max(1),
        cluster: None,
        frame_log: options.log.clone(),
    })?;
    app.node = Some(NodeRole {
        node,
        pending: Some(first),
        frames: options.frames,
        silence: options.silence,
        last_frame: Instant::now(),
        shown: 0,
    });
    event_loop
        .run_app(&mut app)
        .map_err(|e| format!("the window's event loop failed: {e}"))?;
    let shown = app.node.as_ref().map_or(0, |r| r.shown);
    app.result.map(|()| shown)
}

fn open_event_loop() -> Result<EventLoop<()>, String> {
    EventLoop::new().map_err(|e| {
        format!("cannot open a window ({e}); on a machine without a display, use `lightcone render`, or run under Xvfb")
    })
}

/// A render node's part of the window: frames come from the master.
struct NodeRole {
    node: ClusterNode,
    /// The first frame, taken before the window opened.
    pending: Option<crate::cluster::message::Frame>,
    /// Frames to show (0: no limit).
    frames: u64,
    /// How long without a frame before the node stops.
    silence: std::time::Duration,
    /// When the last frame came.
    last_frame: Instant,
    shown: u64,
}

impl App {
    fn new(options: Options) -> Result<Self, String> {
        let Options {
            game,
            lesson,
            screenshot,
            frames,
            tracker,
            cave,
            cluster,
            frame_log,
        } = options;
        let frame_log = match frame_log {
            Some(p) => Some(std::io::BufWriter::new(
                std::fs::File::create(&p).map_err(|e| format!("{}: {e}", p.display()))?,
            )),
            None => None,
        };
        let map = cave
            .as_ref()
            .map_or_else(|| cave::desktop_map(game.scene.table.size), |c| c.tracker);
        Ok(Self {
            head: tracker.map(|service| TrackedHead::new(&service, map)),
            cave,
            flight: DVec3::ZERO,
            flight_v: DVec3::ZERO,
            cave_eye: Side::Mono,
            stereo: Vec::new(),
            outputs: Vec::new(),
            state: game,
            lesson,
            screenshot,
            frames,
            reload_checked: Instant::now(),
            gfx: None,
            last: Instant::now(),
            frame: 0,
            keys: HashSet::new(),
            cursor: DVec2::ZERO,
            looking: false,
            orbiting: false,
            aiming: None,
            scene_left: 0.0,
            scene_right: 0.0,
            result: Ok(()),
            cluster,
            frame_log,
            node: None,
            node_head: None,
            views_done: false,
        })
    }
}

struct Gfx {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    gpu: Gpu,
    config: wgpu::SurfaceConfiguration,
    /// The scene renderer (one for every view and CAVE wall).
    views: Vec<Renderer>,
    egui: egui::Context,
    egui_state: egui_winit::State,
    egui_renderer: egui_wgpu::Renderer,
}

impl Gfx {
    /// The window's new size.
    fn resize(&mut self, size: winit::dpi::PhysicalSize<u32>) {
        self.config.width = size.width.max(1);
        self.config.height = size.height.max(1);
        self.surface.configure(&self.gpu.device, &self.config);
    }
}

struct App {
    state: GameState,
    /// The tracked head driving the eye, with `--tracker`.
    head: Option<TrackedHead>,
    /// The CAVE drawn, with `--cave`.
    cave: Option<CaveConfig>,
    /// The player's own flight added to the tracked head (board metres).
    flight: DVec3,
    /// Its velocity this frame, m/s.
    flight_v: DVec3,
    /// Which eye the window shows the CAVE walls for (E cycles).
    cave_eye: Side,
    /// The eyes drawn this frame (the window's first, then those the
    /// outputs need): each side, its view and where it is (tracker space).
    stereo: Vec<(Side, lightcone_engine::ecs::Entity, DVec3)>,
    /// One window per `[[output]]` of the CAVE file.
    outputs: Vec<OutputWindow>,
    lesson: Option<LessonHost>,
    /// Screenshot path and frame count (see [`Options`]).
    screenshot: Option<PathBuf>,
    frames: u32,
    /// When the lesson file was last looked at for edits.
    reload_checked: Instant,
    gfx: Option<Gfx>,
    last: Instant,
    frame: u32,
    keys: HashSet<KeyCode>,
    cursor: DVec2,
    looking: bool,
    /// Middle-drag orbits the eye about the table (or the followed puck).
    orbiting: bool,
    /// Puck being aimed and where the drag started (physical px).
    aiming: Option<(usize, DVec2)>,
    /// Left and right edges (physical px) of the area the panels leave for
    /// the views.
    scene_left: f32,
    scene_right: f32,
    result: Result<(), String>,
    /// The render cluster this game is the master of.
    cluster: Option<ClusterMaster>,
    /// Where each frame's CAVE eyes are logged.
    frame_log: Option<std::io::BufWriter<std::fs::File>>,
    /// The render node this window is (`lightcone wall`).
    node: Option<NodeRole>,
    /// The master's head for this frame (a render node).
    node_head: Option<(DVec3, glam::DQuat)>,
    /// This frame's views were run before drawing (a render node runs them
    /// before the swap lock).
    views_done: bool,
}

/// What the panels show besides the game state.
struct Hud {
    /// The tracker's status line.
    tracker: Option<String>,
    tracker_colour: egui::Color32,
    /// Draw the clocks over the desktop views (not over CAVE walls).
    clocks: bool,
    /// A lesson runs (it owns c).
    lesson: bool,
}

/// How one rectangle of the window is drawn.
enum Plan {
    /// A desktop picture (a view of an eye: seen or truth).
    Desktop(Pane),
    /// CAVE wall `i`, from the head's midpoint.
    Wall(usize),
}

/// `rect` cut to the `w × h` surface (wgpu refuses viewports outside it);
/// `None` when nothing is left.
fn clamp_rect(rect: [f32; 4], w: f32, h: f32) -> Option<[f32; 4]> {
    let (x0, y0) = (rect[0].max(0.0), rect[1].max(0.0));
    let (x1, y1) = ((rect[0] + rect[2]).min(w), (rect[1] + rect[3]).min(h));
    (x1 - x0 >= 1.0 && y1 - y0 >= 1.0).then_some([x0, y0, x1 - x0, y1 - y0])
}

/// The walls the main window tiles in a CAVE: those no output shows; all
/// of them (a preview) when every wall has an output.
fn tiled_walls(cave: &CaveConfig) -> Vec<usize> {
    let unmapped = cave.unmapped_walls();
    if unmapped.is_empty() {
        (0..cave.walls.len()).collect()
    } else {
        unmapped
    }
}

/// The CAVE walls tiled in a grid over `[x0, x0 + w] × [0, h]`, each tile
/// keeping its wall's aspect ratio.
fn wall_tiles(
    cave: &CaveConfig,
    walls: &[usize],
    x0: f32,
    w: f32,
    h: f32,
) -> Vec<([f32; 4], Plan)> {
    let n = walls.len().max(1);
    let cols = (n as f32).sqrt().ceil() as usize;
    let rows = n.div_ceil(cols);
    let (tw, th) = (
        w.max(cols as f32) / cols as f32,
        h.max(rows as f32) / rows as f32,
    );
    walls
        .iter()
        .enumerate()
        .map(|(i, &index)| {
            let wall = &cave.walls[index];
            let aspect = (wall.width() / wall.height()) as f32;
            let (mut rw, mut rh) = ((tw - 4.0).max(1.0), (th - 4.0).max(1.0));
            if rw / rh > aspect {
                rw = rh * aspect;
            } else {
                rh = rw / aspect;
            }
            let (cx, cy) = (
                x0 + tw * ((i % cols) as f32 + 0.5),
                th * ((i / cols) as f32 + 0.5),
            );
            (
                [cx - rw / 2.0, cy - rh / 2.0, rw.max(1.0), rh.max(1.0)],
                Plan::Wall(index),
            )
        })
        .collect()
}

/// The rectangles (x, y, w, h in physical px) of the pictures `panes`,
/// side by side in equal widths, left to right, in the area
/// `[x0, x0 + w] × [0, h]` left free by the panels.
pub fn layout(panes: &[Pane], x0: f32, w: f32, h: f32) -> Vec<([f32; 4], Pane)> {
    let (w, h) = (w.max(1.0), h.max(1.0));
    let n = panes.len().max(1) as f32;
    panes
        .iter()
        .enumerate()
        .map(|(k, &p)| ([x0 + w * k as f32 / n, 0.0, w / n, h], p))
        .collect()
}

impl App {
    fn init(&mut self, event_loop: &ActiveEventLoop) -> Result<(), String> {
        let attributes = Window::default_attributes()
            .with_title(match (&self.lesson, &self.node) {
                (_, Some(role)) => format!("Lightcone render node: {}", role.node.name),
                (Some(l), None) => format!("Lightcone lesson: {}", l.path().display()),
                (None, None) => format!("Lightcone: {}", self.state.scene.title),
            })
            .with_inner_size(winit::dpi::LogicalSize::new(1280.0, 720.0));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| format!("cannot open a window: {e}"))?,
        );
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends: wgpu::Backends::VULKAN | wgpu::Backends::GL,
            ..wgpu::InstanceDescriptor::new_without_display_handle()
        });
        let surface = instance
            .create_surface(window.clone())
            .map_err(|e| format!("cannot draw into the window: {e}"))?;
        let mut outputs = match &self.cave {
            Some(c) => outputs::open(event_loop, &instance, c)?,
            None => Vec::new(),
        };
        let gpu = gpu::open(instance, Some(&surface))?;
        for o in &mut outputs {
            o.configure(&gpu)?;
        }
        self.outputs = outputs;
        let size = window.inner_size();
        let mut config = surface
            .get_default_config(&gpu.handle, size.width.max(1), size.height.max(1))
            .ok_or_else(|| format!("the adapter {} cannot draw into this window", gpu.adapter))?;
        config.usage |=
            wgpu::TextureUsages::COPY_SRC & surface.get_capabilities(&gpu.handle).usages;
        surface.configure(&gpu.device, &config);
        let views = vec![Renderer::new(
            &gpu.device,
            config.format,
            config.width,
            config.height,
        )];
        let egui = egui::Context::default();
        let egui_state = egui_winit::State::new(
            egui.clone(),
            egui::ViewportId::ROOT,
            &*window,
            Some(window.scale_factor() as f32),
            None,
            Some(gpu.device.limits().max_texture_dimension_2d as usize),
        );
        let egui_renderer =
            egui_wgpu::Renderer::new(&gpu.device, config.format, Default::default());
        self.gfx = Some(Gfx {
            window,
            surface,
            gpu,
            config,
            views,
            egui,
            egui_state,
            egui_renderer,
        });
        Ok(())
    }

    /// Held keys fly the eye: W/S forward and back, A/D sideways, R/F up
    /// and down, at a proper acceleration of 0.5 c per second.
    fn fly(&mut self, dt: f64) {
        let f = self.state.forward();
        let flat = DVec3::new(f.x, f.y, 0.0).normalize_or(DVec3::X);
        let side = flat.cross(DVec3::Z);
        let mut dir = DVec3::ZERO;
        for (key, d) in [
            (KeyCode::KeyW, flat),
            (KeyCode::KeyS, -flat),
            (KeyCode::KeyD, side),
            (KeyCode::KeyA, -side),
            (KeyCode::KeyR, DVec3::Z),
            (KeyCode::KeyF, -DVec3::Z),
        ] {
            if self.keys.contains(&key) {
                dir += d;
            }
        }
        let dir = dir.normalize_or_zero();
        if self.head.is_some() || self.cave.is_some() {
            // With a tracked head or a CAVE, the keys carry the tracked
            // space through the scene at 1 m/s (while time runs): a velocity
            // the observer has, added to the head's own.
            let running = !(self.state.paused || self.state.replaying());
            self.flight_v = if running { dir } else { DVec3::ZERO };
            self.flight += dir * dt;
        } else if dir != DVec3::ZERO {
            self.state.thrust(dir * 0.5 * dt, dir * 1.0 * dt);
        }
    }

    fn key(&mut self, code: KeyCode) {
        if super::scene_menu::key(&mut self.state, code, self.lesson.is_some()) {
            return;
        }
        let s = &mut self.state;
        match code {
            KeyCode::KeyP | KeyCode::Space => {
                s.paused = !s.paused;
                s.intro = false;
            }
            KeyCode::KeyL => s.go_live(),
            KeyCode::KeyX => s.halt(),
            KeyCode::Home => s.reset_view(),
            KeyCode::Digit7 => s.show.trails = !s.show.trails,
            KeyCode::Digit8 => s.show.ghost = !s.show.ghost,
            KeyCode::Digit9 => s.show.arrows = !s.show.arrows,
            KeyCode::KeyY => s.show.diagram = !s.show.diagram,
            KeyCode::KeyV => s.top_view(),
            KeyCode::KeyG => {
                let n = s.physics().len();
                s.follow = match s.follow {
                    None if n > 0 => Some(0),
                    Some(i) if i + 1 < n => Some(i + 1),
                    _ => None,
                };
                s.framing = crate::model::Framing::Fit;
            }
            KeyCode::ArrowLeft => s.orbit(-0.1, 0.0),
            KeyCode::ArrowRight => s.orbit(0.1, 0.0),
            KeyCode::ArrowUp => s.orbit(0.0, 0.08),
            KeyCode::ArrowDown => s.orbit(0.0, -0.08),
            KeyCode::Equal | KeyCode::NumpadAdd => s.zoom_by(1.25),
            KeyCode::Minus | KeyCode::NumpadSubtract => s.zoom_by(0.8),
            KeyCode::KeyE => {
                self.cave_eye = match self.cave_eye {
                    Side::Mono => Side::Left,
                    Side::Left => Side::Right,
                    Side::Right => Side::Mono,
                }
            }
            KeyCode::F5 => {
                if let Some(lesson) = &mut self.lesson {
                    lesson.reload(s);
                }
            }
            KeyCode::KeyT => {
                let next = match (&s.panes, s.view) {
                    (Some(_), _) => ViewMode::Seen,
                    (None, ViewMode::Seen) => ViewMode::Truth,
                    (None, ViewMode::Truth) => ViewMode::Split,
                    (None, ViewMode::Split) => ViewMode::Seen,
                };
                s.set_view(next);
            }
            KeyCode::Digit1
            | KeyCode::Digit2
            | KeyCode::Digit3
            | KeyCode::Digit4
            | KeyCode::Digit5
            | KeyCode::Digit6 => {
                let i = match code {
                    KeyCode::Digit1 => 0,
                    KeyCode::Digit2 => 1,
                    KeyCode::Digit3 => 2,
                    KeyCode::Digit4 => 3,
                    KeyCode::Digit5 => 4,
                    _ => 5,
                };
                let e = Effect::ALL[i];
                let on = s.effects.is_on(e);
                s.effects.set(e, !on);
            }
            _ => {}
        }
    }

    /// The pictures' rectangles as the last frame laid them out.
    fn rects(&self) -> Vec<([f32; 4], Pane)> {
        let Some(gfx) = self.gfx.as_ref() else {
            return Vec::new();
        };
        self.rects_in(gfx.config.width as f32, gfx.config.height as f32)
    }

    /// The pictures' rectangles in a `w × h` window, between the edges the
    /// last frame's panels left.
    fn rects_in(&self, w: f32, h: f32) -> Vec<([f32; 4], Pane)> {
        let (left, width) = self.scene_span(w);
        layout(&self.state.pane_list(), left, width, h)
    }

    /// The left edge and width of the area the last frame's panels left
    /// for the pictures in a window `w` wide.
    fn scene_span(&self, w: f32) -> (f32, f32) {
        let right = if self.scene_right > self.scene_left {
            self.scene_right.min(w)
        } else {
            w
        };
        (self.scene_left, right - self.scene_left)
    }

    /// The rectangle and picture in which the cue picks pucks: the one
    /// under the cursor (the last one when none is).
    fn pick_rect(&self) -> Option<([f32; 4], Pane)> {
        let rects = self.rects();
        let (x, y) = (self.cursor.x as f32, self.cursor.y as f32);
        rects
            .iter()
            .copied()
            .find(|(r, _)| x >= r[0] && x < r[0] + r[2] && y >= r[1] && y < r[1] + r[3])
            .or_else(|| rects.last().copied())
    }

    fn press(&mut self) {
        let Some((rect, pane)) = self.pick_rect() else {
            return;
        };
        let Some(view) = self.state.view_of(pane) else {
            return;
        };
        let Some(camera) = self.state.camera(view) else {
            return;
        };
        let best = self
            .state
            .centres(view)
            .iter()
            .filter_map(|c| {
                project(&camera, rect, c.seen.position).map(|p| (c.puck, p.distance(self.cursor)))
            })
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((i, d)) = best
            && d < 30.0
        {
            self.aiming = Some((i, self.cursor));
        }
    }

    fn drag(&mut self) {
        let Some((puck, start)) = self.aiming else {
            return;
        };
        let f = self
            .pick_rect()
            .and_then(|(_, p)| self.state.view_of(p))
            .and_then(|v| self.state.camera(v))
            .map_or_else(|| self.state.forward(), |c| c.forward);
        let flat = DVec3::new(f.x, f.y, 0.0).normalize_or(DVec3::Y);
        let right = flat.cross(DVec3::Z);
        let d = self.cursor - start;
        // 60 px of pull = 1 m/s of proper velocity γv.
        let pull = (right * d.x - flat * d.y) / 60.0;
        self.state.aim(puck, pull.truncate());
    }

    fn release(&mut self) {
        if self.aiming.take().is_some()
            && let Err(e) = self.state.strike()
        {
            self.state.message = e;
        }
    }

    fn frame(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(role) = self.node.take() {
            self.node_frame(role, event_loop);
            return;
        }
        let now = Instant::now();
        let dt = (now - self.last).as_secs_f64().min(0.1);
        self.last = now;
        self.fly(dt);
        // The hooks sent last frame ran in the lesson's process while that
        // frame was drawn: take their ends (waiting at most a budget).
        if let Some(lesson) = &mut self.lesson {
            lesson.serve(&mut self.state, crate::lesson::remote::FRAME_BUDGET);
        }
        let before = self.state.live_time;
        // Board time waits while a lesson hook is out in its process.
        if !self.lesson.as_ref().is_some_and(LessonHost::busy) {
            self.state.step(dt);
        }
        if let Some(lesson) = &mut self.lesson {
            lesson.after_step(&mut self.state, before);
            // An edited lesson reloads by itself (checked twice a second).
            if now - self.reload_checked > std::time::Duration::from_millis(500) {
                self.reload_checked = now;
                lesson.reload_if_edited(&mut self.state);
            }
        }
        match (&mut self.head, &self.cave) {
            (Some(head), _) => {
                head.poll(now);
                head.drive(&mut self.state, self.flight, self.flight_v);
                // The tracked head aims the camera.
                self.state.framing = crate::model::Framing::Look;
            }
            (None, Some(c)) => {
                // No tracker: the head stands at the CAVE's centre, carried
                // by the flight.
                cave::place_untracked(&mut self.state, c, self.flight, self.flight_v);
            }
            (None, None) => {}
        }
        self.frame += 1;
        let shot = self.screenshot.is_some() && self.frame >= self.frames;
        // The render nodes compute this frame and show it together (the
        // swap lock); the window draws it after, so that its own drawing
        // (the console's, not a wall's) adds nothing to the walls' latency.
        if let Some(master) = &mut self.cluster {
            let head = self.head.as_ref().map_or(
                (cave::DEFAULT_HEAD, glam::DQuat::IDENTITY),
                TrackedHead::head,
            );
            let sample = self.head.as_ref().and_then(TrackedHead::newest_sample_ns);
            master.publish(&self.state, head, self.flight, sample);
            master.swap(&self.state);
        }
        // The frame log reads the views of the state just published: they
        // are run before the panels (drawn next) can change it.
        if self.frame_log.is_some() && self.cave.is_some() {
            self.run_views(0.0, 0.0);
            self.views_done = true;
            if let Err(e) = self.log_frame() {
                crate::errln!("--frame-log: {e}; no longer logging");
                self.frame_log = None;
            }
        }
        if let Err(e) = self.draw(shot) {
            self.result = Err(e);
            event_loop.exit();
            return;
        }
        if let Some(master) = &mut self.cluster {
            for line in master.take_news() {
                crate::errln!("{line}");
                self.state.message = line;
            }
        }
        // Answer what the lesson asked while the frame was drawn, so its
        // hook can end before the next frame.
        if let Some(lesson) = &mut self.lesson {
            lesson.serve(&mut self.state, std::time::Duration::ZERO);
        }
        if shot {
            event_loop.exit();
        }
    }
}

/// The egui panels and the clocks drawn on the pucks. Returns the left and
/// right edges (physical px) of the area left for the views.
fn panels(
    state: &mut GameState,
    hud: &Hud,
    lesson: Option<(&LessonHost, &mut Vec<LessonAction>)>,
    ctx: &egui::Context,
    ui: &mut egui::Ui,
    size: (u32, u32),
) -> (f32, f32) {
    let ppp = ctx.pixels_per_point();
    let left;
    let mut right = size.0 as f32;
    if let Some((host, actions)) = lesson {
        egui::Panel::right("lesson")
            .default_size(340.0)
            .show(ui, |ui| lesson_panel::show(ui, host, actions));
        right = ui.available_rect_before_wrap().right() * ppp;
    }
    {
        let s = &mut *state;
        egui::Panel::left("controls")
            .default_size(260.0)
            .show(ui, |ui| {
                ui.heading("Lightcone");
                ui.label(&s.scene.title);
                if ui.small_button("other scenes… (M)").clicked() {
                    s.scene_menu.open = !s.scene_menu.open;
                }
                ui.separator();
                ui.horizontal(|ui| {
                    if ui
                        .button(if s.paused { "play (P)" } else { "pause (P)" })
                        .clicked()
                    {
                        s.paused = !s.paused;
                        s.intro = false;
                    }
                    if ui.button("live (L)").clicked() {
                        s.go_live();
                    }
                    if ui.button("restart").clicked() {
                        s.restart();
                    }
                    if ui.button("view (Home)").clicked() {
                        s.reset_view();
                    }
                });
                ui.add(
                    egui::Slider::new(&mut s.time_scale, 0.01..=4.0)
                        .logarithmic(true)
                        .text("time scale"),
                );
                let mut t = s.view_time;
                let live = s.live_time.max(1e-9);
                // The replay window: the past before it is forgotten.
                let oldest = s
                    .physics()
                    .forgotten_before()
                    .map_or(0.0, |f| f.clamp(0.0, live));
                if ui
                    .add(egui::Slider::new(&mut t, oldest..=live).text("board time (s)"))
                    .changed()
                {
                    s.replay_to(t);
                }
                ui.label(format!(
                    "replay window: the last {:.0} min of board time{}",
                    crate::model::REPLAY_WINDOW / 60.0,
                    if oldest > 0.0 {
                        format!(" (before {oldest:.0} s is forgotten)")
                    } else {
                        String::new()
                    }
                ));
                if s.replaying() {
                    ui.colored_label(egui::Color32::YELLOW, "replay: what was seen then");
                }
                ui.separator();
                let mut c = s.scene.c;
                // A lesson sets c itself (restarting under it would break
                // its bookkeeping).
                if ui
                    .add_enabled(
                        !hud.lesson,
                        egui::Slider::new(&mut c, 0.2..=1.0e6)
                            .logarithmic(true)
                            .text("c (m/s)"),
                    )
                    .drag_stopped()
                {
                    s.restart_with_c(c);
                }
                ui.label("effects (1–6):");
                for e in Effect::ALL {
                    let mut on = s.effects.is_on(e);
                    if ui.checkbox(&mut on, e.key()).changed() {
                        s.effects.set(e, on);
                    }
                }
                ui.horizontal(|ui| {
                    ui.checkbox(&mut s.show.trails, "trails (7)");
                    ui.checkbox(&mut s.show.ghost, "ghost (8)");
                    ui.checkbox(&mut s.show.arrows, "arrows (9)");
                });
                ui.checkbox(&mut s.show.diagram, "space-time diagram (Y)");
                if s.effects.doppler {
                    super::overlay::doppler_legend(ui);
                }
                ui.label("view (T):");
                ui.horizontal(|ui| {
                    let mut mode = s.panes.is_none().then_some(s.view);
                    ui.selectable_value(&mut mode, Some(ViewMode::Seen), "seen");
                    ui.selectable_value(&mut mode, Some(ViewMode::Truth), "truth");
                    ui.selectable_value(&mut mode, Some(ViewMode::Split), "split");
                    if s.panes.is_some() {
                        let _ = ui.selectable_label(true, "--views");
                    }
                    if let Some(m) = mode
                        && (s.panes.is_some() || m != s.view)
                    {
                        s.set_view(m);
                    }
                });
                egui::ComboBox::from_label("eye")
                    .selected_text(match s.observer {
                        None => "you (WASD, R/F, right-drag)".to_owned(),
                        Some(i) => s.scene.observers[i].name.clone(),
                    })
                    .show_ui(ui, |ui| {
                        ui.selectable_value(&mut s.observer, None, "you");
                        for (i, o) in s.scene.observers.iter().enumerate() {
                            ui.selectable_value(&mut s.observer, Some(i), &o.name);
                        }
                    });
                let follow_name = |f: Option<usize>| match f {
                    Some(i) if i < s.scene.pucks.len() => s.scene.pucks[i].name.clone(),
                    _ => "the table".to_owned(),
                };
                let mut follow = s.follow;
                egui::ComboBox::from_label("camera on (G)")
                    .selected_text(follow_name(follow))
                    .show_ui(ui, |ui| {
                        ui.selectable_value(&mut follow, None, "the table");
                        for (i, p) in s.scene.pucks.iter().enumerate() {
                            ui.selectable_value(&mut follow, Some(i), &p.name);
                        }
                    });
                if follow != s.follow {
                    s.follow = follow;
                    s.framing = crate::model::Framing::Fit;
                }
                ui.horizontal(|ui| {
                    if ui.button("from above (V)").clicked() {
                        s.top_view();
                    }
                    ui.label(format!("zoom {:.2}× (wheel)", s.zoom));
                });
                let eb = s.eye.u.beta();
                ui.label(format!(
                    "your β = ({:.3}, {:.3}, {:.3}), γ = {:.4} (X stops)",
                    eb.x,
                    eb.y,
                    eb.z,
                    s.eye.u.gamma()
                ));
                ui.separator();
                ui.label("pucks now (board frame):");
                egui::Grid::new("pucks").striped(true).show(ui, |ui| {
                    ui.label("name");
                    ui.label("|β|");
                    ui.label("γ");
                    ui.label("τ (s)");
                    ui.end_row();
                    for i in 0..s.physics().len() {
                        let st = s.physics().worldline(i).state_at(s.view_time);
                        ui.label(s.physics().name(i));
                        ui.label(format!("{:.4}", st.u.beta().length()));
                        ui.label(format!("{:.4}", st.u.gamma()));
                        ui.label(format!("{:.3}", st.proper_time));
                        ui.end_row();
                    }
                });
                if let Some(c) = s.last_collision() {
                    ui.label(format!("last collision: {c}"));
                }
                if let Some(cue) = s.cue {
                    let u = lightcone_engine::spacetime::ProperVelocity(
                        s.physics()
                            .worldline(cue.puck)
                            .proper_velocity_at(s.live_time)
                            .0
                            + cue.du,
                    );
                    ui.colored_label(
                        egui::Color32::LIGHT_BLUE,
                        format!(
                            "cue on {}: β = {:.6}, γ = {:.4}",
                            s.physics().name(cue.puck),
                            u.beta().length(),
                            u.gamma()
                        ),
                    );
                }
                if let Some(line) = &hud.tracker {
                    ui.separator();
                    ui.colored_label(hud.tracker_colour, line);
                }
                if !s.message.is_empty() {
                    ui.colored_label(egui::Color32::LIGHT_RED, &s.message);
                }
                ui.separator();
                ui.small("Drag from a puck to aim the cue (pull back, release to strike).");
            });
        left = ui.available_rect_before_wrap().left() * ppp;
    }
    if state.show.diagram {
        let mut open = true;
        egui::Window::new("space-time diagram")
            .open(&mut open)
            .default_pos(egui::pos2(left / ppp + 12.0, size.1 as f32 / ppp - 340.0))
            .default_width(420.0)
            .show(ctx, |ui| {
                super::diagram_controls::frame_and_axis(ui, state);
                super::overlay::diagram_panel(ui, state);
            });
        state.show.diagram = open;
    }
    super::scene_menu::window(ctx, state, hud.lesson);
    if state.intro {
        intro(state, ctx, (left + right) / 2.0 / ppp, 12.0);
    }
    if !hud.clocks {
        return (left, right);
    }
    // Under windows (the diagram) and the intro: the background layer,
    // drawn within the views.
    let painter = ctx.layer_painter(egui::LayerId::new(
        egui::Order::Background,
        egui::Id::unique("clocks"),
    ));
    let rects = layout(&state.pane_list(), left, right - left, size.1 as f32);
    overlays(state, &painter, &rects, ppp);
    (left, right)
}

/// The scene's title and description at the top of the views, with a
/// start button (Space or P also starts), its top centre at `(x, y)`
/// (points).
fn intro(state: &mut GameState, ctx: &egui::Context, x: f32, y: f32) {
    egui::Area::new(egui::Id::unique("intro"))
        .fixed_pos(egui::pos2(x, y))
        .pivot(egui::Align2::CENTER_TOP)
        .order(egui::Order::Foreground)
        .show(ctx, |ui| {
            egui::Frame::window(ui.style()).show(ui, |ui| {
                ui.set_max_width(420.0);
                ui.heading(&state.scene.title);
                if !state.scene.description.is_empty() {
                    ui.add(egui::Label::new(egui::RichText::new(&state.scene.description).size(15.0)).wrap());
                }
                ui.separator();
                ui.small(
                    "Drag from a puck to strike it. Wheel: zoom; middle-drag or arrows: orbit; \
                     V: from above; G: follow a puck; Home: reset the view; T: seen / truth / split.",
                );
                if ui.button("start (Space)").clicked() {
                    state.intro = false;
                    state.paused = false;
                }
            });
        });
}

impl App {
    /// A render node's frame: the master's next one applied to the copy of
    /// its game, the walls' eyes computed, the swap lock, then drawn.
    fn node_frame(&mut self, mut role: NodeRole, event_loop: &ActiveEventLoop) {
        let frame = match role.pending.take() {
            Some(f) => f,
            // Waits in short slices, so the window stays responsive (it can
            // be closed) while the master is silent.
            None => match role
                .node
                .next_frame(&mut self.state, std::time::Duration::from_millis(50))
            {
                Ok(Some(f)) => f,
                Ok(None) => {
                    let silent = role.last_frame.elapsed() >= role.silence;
                    if role.node.master_gone {
                        crate::errln!("lightcone wall: the master is gone; stopping");
                    } else if silent {
                        crate::errln!(
                            "lightcone wall: no frame from the master in {:?}; stopping",
                            role.silence
                        );
                    }
                    let stop = silent || role.node.master_gone;
                    self.node = Some(role);
                    if stop {
                        event_loop.exit();
                    }
                    return;
                }
                Err(e) => {
                    self.result = Err(e);
                    self.node = Some(role);
                    event_loop.exit();
                    return;
                }
            },
        };
        if let Some(c) = &role.node.cave
            && self.cave.as_ref() != Some(c)
        {
            self.cave = Some(c.clone());
        }
        role.last_frame = Instant::now();
        self.flight = frame.view.flight;
        self.node_head = Some(frame.view.head());
        self.state.message = role.node.status_line();
        self.frame += 1;
        if let Some(gfx) = &self.gfx {
            let (w, h) = (gfx.config.width as f32, gfx.config.height as f32);
            self.run_views(w, h);
            self.views_done = true;
        }
        role.node.ready(frame.seq);
        role.node.wait_swap(frame.seq, crate::cluster::BARRIER * 4);
        let shown_ns = crate::cluster::now_ns();
        let shot = self.screenshot.is_some() && self.frame >= self.frames;
        if let Err(e) = self.draw(shot) {
            self.result = Err(e);
            self.node = Some(role);
            event_loop.exit();
            return;
        }
        role.shown += 1;
        if let (Some(log), Some(cave)) = (&mut self.frame_log, &self.cave) {
            use std::io::Write;
            let stamps = crate::cluster::node::Stamps {
                sample_ns: frame.sample_ns,
                sent_ns: frame.sent_ns,
                shown_ns,
            };
            let line = crate::cluster::node::frame_record(
                frame.seq,
                frame.view.head_position,
                stamps,
                &self.state,
                cave,
                &self.stereo,
            );
            if writeln!(log, "{line}").and_then(|()| log.flush()).is_err() {
                crate::errln!("--frame-log: cannot write; no longer logging");
                self.frame_log = None;
            }
        }
        let done = shot || (role.frames > 0 && role.shown >= role.frames);
        self.node = Some(role);
        if done {
            event_loop.exit();
        }
    }

    /// Writes this frame's CAVE eyes to the frame log (`--frame-log`), as a
    /// render node logs them (call after the frame's views were run).
    fn log_frame(&mut self) -> Result<(), String> {
        use std::io::Write;
        let (Some(log), Some(cave)) = (&mut self.frame_log, &self.cave) else {
            return Ok(());
        };
        let head = self.head.as_ref().map_or(
            (cave::DEFAULT_HEAD, glam::DQuat::IDENTITY),
            TrackedHead::head,
        );
        let seq = self
            .cluster
            .as_ref()
            .map_or(u64::from(self.frame), ClusterMaster::seq);
        let stamps = crate::cluster::node::Stamps {
            sample_ns: self.head.as_ref().and_then(TrackedHead::newest_sample_ns),
            sent_ns: 0,
            shown_ns: crate::cluster::now_ns(),
        };
        let line = crate::cluster::node::frame_record(
            seq,
            head.0,
            stamps,
            &self.state,
            cave,
            &self.stereo,
        );
        writeln!(log, "{line}").map_err(|e| e.to_string())?;
        log.flush().map_err(|e| e.to_string())
    }

    fn draw(&mut self, screenshot: bool) -> Result<(), String> {
        let Some(mut gfx) = self.gfx.take() else {
            return Ok(());
        };
        let result = self.draw_with(&mut gfx, screenshot);
        self.gfx = Some(gfx);
        result
    }

    /// Runs the game's frame schedule for what this frame draws: the
    /// desktop pictures (laid out as the last frame's panels left room),
    /// or the CAVE's stereo eye. Everything drawn next (the views, the
    /// clocks, labels and picking) reads what it wrote.
    fn run_views(&mut self, w: f32, h: f32) {
        match &self.cave {
            Some(c) => {
                let head = self.node_head.unwrap_or_else(|| {
                    self.head.as_ref().map_or(
                        (cave::DEFAULT_HEAD, glam::DQuat::IDENTITY),
                        TrackedHead::head,
                    )
                });
                let sides = cave::sides_needed(c, self.cave_eye);
                let views = cave::stereo_views(&mut self.state, c, head, &sides, self.flight);
                self.stereo = sides
                    .into_iter()
                    .zip(views)
                    .map(|(side, (view, eye))| (side, view, eye))
                    .collect();
            }
            None => {
                let panes: Vec<(Pane, f64)> = self
                    .rects_in(w, h)
                    .into_iter()
                    .map(|(r, p)| (p, aspect(r)))
                    .collect();
                self.state.run_frame(&panes);
            }
        }
    }

    fn draw_with(&mut self, gfx: &mut Gfx, screenshot: bool) -> Result<(), String> {
        if !std::mem::take(&mut self.views_done) {
            self.run_views(gfx.config.width as f32, gfx.config.height as f32);
        }
        let raw = gfx.egui_state.take_egui_input(&gfx.window);
        let ctx = gfx.egui.clone();
        let size = (gfx.config.width, gfx.config.height);
        let hud = Hud {
            tracker: match (&self.head, &self.cave) {
                (Some(h), _) => Some(h.status_line()),
                (None, Some(_)) => {
                    Some("no tracker: the head stands at the CAVE's centre".to_owned())
                }
                (None, None) => None,
            }
            .map(|line| match &self.cave {
                Some(_) => format!(
                    "{line}\nCAVE walls, {} eye (E switches){}",
                    self.cave_eye.name(),
                    self.cluster
                        .as_ref()
                        .map(|m| format!("\n{}", m.status_line()))
                        .unwrap_or_default()
                ),
                None => line,
            }),
            tracker_colour: match self.head.as_ref().and_then(TrackedHead::status) {
                Some(TrackerStatus::Live) => egui::Color32::LIGHT_GREEN,
                _ => egui::Color32::LIGHT_RED,
            },
            clocks: self.cave.is_none(),
            lesson: self.lesson.is_some(),
        };
        let state = &mut self.state;
        let mut edges = (self.scene_left, self.scene_right);
        let mut actions = Vec::new();
        let lesson = self.lesson.as_ref();
        // A render node shows only its walls, and one line of status.
        let node = self.node_head.is_some();
        let output = ctx.run_ui(raw, |ui| {
            let ctx = ui.ctx().clone();
            if node {
                egui::Area::new(egui::Id::unique("node status"))
                    .anchor(egui::Align2::LEFT_BOTTOM, egui::vec2(8.0, -8.0))
                    .show(&ctx, |ui| {
                        ui.label(
                            egui::RichText::new(&state.message)
                                .small()
                                .color(egui::Color32::GRAY),
                        );
                    });
                edges = (0.0, size.0 as f32);
                return;
            }
            edges = panels(
                state,
                &hud,
                lesson.map(|l| (l, &mut actions)),
                &ctx,
                ui,
                size,
            );
        });
        if edges != (self.scene_left, self.scene_right) {
            // The panels took another width (the first frame, a resize):
            // frame the views for the room they now leave.
            (self.scene_left, self.scene_right) = edges;
            self.run_views(size.0 as f32, size.1 as f32);
        }
        if let Some(lesson) = &mut self.lesson {
            for action in actions {
                match action {
                    LessonAction::Answer(i) => lesson.answer(&mut self.state, i),
                    LessonAction::Reload => lesson.reload(&mut self.state),
                }
            }
        }
        gfx.egui_state
            .handle_platform_output(&gfx.window, output.platform_output);
        let jobs = gfx.egui.tessellate(output.shapes, output.pixels_per_point);
        for (id, deltas) in &output.textures_delta.set {
            for delta in deltas {
                gfx.egui_renderer
                    .update_texture(&gfx.gpu.device, &gfx.gpu.queue, *id, delta);
            }
        }
        let frame = match gfx.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f)
            | wgpu::CurrentSurfaceTexture::Suboptimal(f) => f,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                gfx.surface.configure(&gfx.gpu.device, &gfx.config);
                return Ok(());
            }
            _ => return Ok(()),
        };
        let target = frame
            .texture
            .create_view(&wgpu::TextureViewDescriptor::default());
        let (w, h) = (gfx.config.width as f32, gfx.config.height as f32);
        let mut vertices: Vec<FrameVertex> = Vec::new();
        let right = if self.scene_right > self.scene_left {
            self.scene_right.min(w)
        } else {
            w
        };
        let mut cleared = false;
        let plans: Vec<([f32; 4], Plan)> = match &self.cave {
            Some(c) => wall_tiles(
                c,
                &tiled_walls(c),
                self.scene_left,
                right - self.scene_left,
                h,
            ),
            None => layout(
                &self.state.pane_list(),
                self.scene_left,
                right - self.scene_left,
                h,
            )
            .into_iter()
            .map(|(r, p)| (r, Plan::Desktop(p)))
            .collect(),
        };
        for (rect, plan) in plans {
            vertices.clear();
            let view_proj = match (plan, &self.cave) {
                (Plan::Wall(i), Some(c)) => {
                    let Some(&(_, view, tracker_eye)) = self.stereo.first() else {
                        continue;
                    };
                    match cave::wall_frame(
                        &self.state,
                        c,
                        &c.walls[i],
                        view,
                        tracker_eye,
                        &mut vertices,
                    ) {
                        Some(m) => m,
                        None => continue,
                    }
                }
                (Plan::Desktop(pane), _) => {
                    let Some(view) = self.state.view_of(pane) else {
                        continue;
                    };
                    let (Some(apparent), Some(camera)) =
                        (self.state.apparent(view), self.state.camera(view))
                    else {
                        continue;
                    };
                    frame::build_view(apparent, &self.state.meshes, &mut vertices);
                    camera.view_proj(rect[2] / rect[3])
                }
                (Plan::Wall(_), None) => continue,
            };
            let Some(rect) = clamp_rect(rect, w, h) else {
                continue;
            };
            // One renderer draws every view, each submitted before the next
            // is written: its multisampled target then holds the views
            // drawn so far, which the next one loads and resolves whole.
            let mut encoder =
                gfx.gpu
                    .device
                    .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                        label: Some("scene view"),
                    });
            gfx.views[0].resize(&gfx.gpu.device, gfx.config.width, gfx.config.height);
            gfx.views[0].render(
                &gfx.gpu.device,
                &gfx.gpu.queue,
                &mut encoder,
                &target,
                Draw {
                    vertices: &vertices,
                    view_proj,
                    clear: (!cleared).then_some(BACKGROUND),
                    viewport: Some(rect),
                },
            );
            gfx.gpu.queue.submit([encoder.finish()]);
            cleared = true;
        }
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [gfx.config.width, gfx.config.height],
            pixels_per_point: output.pixels_per_point,
        };
        let mut encoder = gfx
            .gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("egui"),
            });
        gfx.egui_renderer.update_buffers(
            &gfx.gpu.device,
            &gfx.gpu.queue,
            &mut encoder,
            &jobs,
            &screen,
        );
        {
            let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("egui pass"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            gfx.egui_renderer
                .render(&mut pass.forget_lifetime(), &jobs, &screen);
        }
        let readback = if screenshot {
            Some(copy_out(
                &gfx.gpu,
                &gfx.config,
                &frame.texture,
                &mut encoder,
            ))
        } else {
            None
        };
        gfx.gpu.queue.submit([encoder.finish()]);
        for id in &output.textures_delta.free {
            gfx.egui_renderer.free_texture(id);
        }
        if let (Some((buffer, padded)), Some(path)) = (readback, &self.screenshot) {
            save(&gfx.gpu, &gfx.config, &buffer, padded, path)?;
            self.save_layout(&path.with_extension("json"), w, h)?;
        }
        gfx.gpu.queue.present(frame);
        // The outputs: the same frame's views, each output's wall.
        if let Some(c) = &self.cave {
            let shot = if screenshot {
                self.screenshot.as_deref()
            } else {
                None
            };
            for o in &mut self.outputs {
                o.draw(&gfx.gpu, &self.state, c, &self.stereo, shot)?;
            }
        }
        Ok(())
    }
}

impl App {
    /// Beside a screenshot, where its views and pucks are (for tests and
    /// for marking up slides): `{"views": [{"rect": [x, y, w, h], "kind"}],
    /// "pucks": [{"name", "view", "centre": [x, y], "ring_px", "ring_colour":
    /// [r, g, b], "clock_s"}]}`, physical px from the top left.
    fn save_layout(&self, path: &std::path::Path, w: f32, h: f32) -> Result<(), String> {
        if let Some(c) = &self.cave {
            return self.save_cave_layout(c, path, w, h);
        }
        let rects = self.rects_in(w, h);
        let views: Vec<serde_json::Value> = rects
            .iter()
            .map(|(r, p)| {
                serde_json::json!({
                    "rect": r,
                    "kind": match p.kind { ViewKind::Seen => "seen", ViewKind::Truth => "truth" },
                    "caption": super::overlay::caption(&self.state, *p),
                })
            })
            .collect();
        let pucks: Vec<serde_json::Value> = markers(&self.state, &rects)
            .iter()
            .map(|m| {
                let c = ring_colour(self.state.scene.pucks[m.puck].color);
                serde_json::json!({
                    "name": self.state.scene.pucks[m.puck].name,
                    "view": m.view,
                    "centre": [m.centre.x, m.centre.y],
                    "ring_px": 2.0 * m.ring,
                    "ring_colour": [c.r(), c.g(), c.b()],
                    "clock_s": m.clock,
                })
            })
            .collect();
        let text = serde_json::json!({
            "views": views,
            "pucks": pucks,
            "scene_pucks": self.state.physics().len(),
        })
        .to_string();
        std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
    }

    /// In a CAVE, beside the main window's screenshot: the walls tiled
    /// there (`{"walls": [{"rect": [x, y, w, h], "wall": name}], "outputs":
    /// [name], "scene_pucks": n}`, physical px from the top left; the
    /// walls no output shows, or all of them when every wall has one), and
    /// the outputs saved beside it as `<shot>.<name>.png`.
    fn save_cave_layout(
        &self,
        cave: &CaveConfig,
        path: &std::path::Path,
        w: f32,
        h: f32,
    ) -> Result<(), String> {
        let (left, width) = self.scene_span(w);
        let tiles: Vec<serde_json::Value> = wall_tiles(cave, &tiled_walls(cave), left, width, h)
            .iter()
            .filter_map(|(r, plan)| match plan {
                Plan::Wall(i) => Some(serde_json::json!({
                    "rect": r,
                    "wall": cave.walls[*i].name,
                })),
                Plan::Desktop(_) => None,
            })
            .collect();
        let outputs: Vec<&str> = cave.outputs.iter().map(|o| o.name.as_str()).collect();
        let text = serde_json::json!({
            "walls": tiles,
            "outputs": outputs,
            "scene_pucks": self.state.physics().len(),
        })
        .to_string();
        std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
    }
}

/// Records a copy of a surface's frame (configured as `config`) into a
/// readable buffer (for `--screenshot`).
pub(super) fn copy_out(
    gpu: &Gpu,
    config: &wgpu::SurfaceConfiguration,
    texture: &wgpu::Texture,
    encoder: &mut wgpu::CommandEncoder,
) -> (wgpu::Buffer, u32) {
    let (w, h) = (config.width, config.height);
    let padded =
        (4 * w).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("screenshot"),
        size: u64::from(padded) * u64::from(h),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(h),
            },
        },
        wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
    );
    (buffer, padded)
}

/// Reads the screenshot buffer back and writes it as PNG (RGBA; BGRA
/// surfaces are swizzled).
pub(super) fn save(
    gpu: &Gpu,
    config: &wgpu::SurfaceConfiguration,
    buffer: &wgpu::Buffer,
    padded: u32,
    path: &std::path::Path,
) -> Result<(), String> {
    let (w, h) = (config.width, config.height);
    let mut rgba = lightcone_render::headless::read_rows(gpu, buffer, padded, w, h)?;
    let bgra = matches!(
        config.format,
        wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb
    );
    for px in rgba.chunks_mut(4) {
        if bgra {
            px.swap(0, 2);
        }
        px[3] = 255;
    }
    lightcone_render::headless::Image {
        width: w,
        height: h,
        rgba,
    }
    .save_png(path)
}

impl App {
    /// A key pressed or released in any of the game's windows.
    fn keyboard(&mut self, event: &winit::event::KeyEvent) {
        if let PhysicalKey::Code(code) = event.physical_key {
            match event.state {
                ElementState::Pressed => {
                    if !event.repeat {
                        self.key(code);
                    }
                    self.keys.insert(code);
                }
                ElementState::Released => {
                    self.keys.remove(&code);
                }
            }
        }
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.gfx.is_none()
            && let Err(e) = self.init(event_loop)
        {
            self.result = Err(e);
            event_loop.exit();
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, id: WindowId, event: WindowEvent) {
        let Some(gfx) = self.gfx.as_mut() else { return };
        if let Some(o) = self.outputs.iter_mut().find(|o| o.id() == id) {
            // An output window: it follows its size; it is drawn with the
            // main window's frame, and keys pressed in it fly the head
            // as in the main window. Closing one ends the game, as closing
            // the main window does.
            match event {
                WindowEvent::Resized(_) => {
                    if let Err(e) = o.configure(&gfx.gpu) {
                        self.result = Err(e);
                        event_loop.exit();
                    }
                }
                WindowEvent::CloseRequested => event_loop.exit(),
                WindowEvent::KeyboardInput { event, .. } if self.node.is_none() => {
                    self.keyboard(&event);
                }
                _ => {}
            }
            return;
        }
        if self.node.is_some() {
            // A render node shows the master's game: it takes no input.
            match event {
                WindowEvent::CloseRequested => event_loop.exit(),
                WindowEvent::Resized(size) => gfx.resize(size),
                WindowEvent::RedrawRequested => self.frame(event_loop),
                _ => {}
            }
            return;
        }
        let consumed = gfx.egui_state.on_window_event(&gfx.window, &event).consumed;
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => gfx.resize(size),
            WindowEvent::RedrawRequested => self.frame(event_loop),
            WindowEvent::KeyboardInput { event, .. } if !consumed => self.keyboard(&event),
            WindowEvent::CursorMoved { position, .. } => {
                let p = DVec2::new(position.x, position.y);
                let d = p - self.cursor;
                if self.looking {
                    self.state.look(-d.x * 0.004, -d.y * 0.004);
                }
                if self.orbiting {
                    self.state.orbit(-d.x * 0.006, d.y * 0.006);
                }
                self.cursor = p;
                self.drag();
            }
            WindowEvent::MouseWheel { delta, .. } if !consumed => {
                let lines = match delta {
                    winit::event::MouseScrollDelta::LineDelta(_, y) => f64::from(y),
                    winit::event::MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
                };
                self.state.zoom_by(1.1f64.powf(lines));
            }
            WindowEvent::MouseInput { state, button, .. }
                if !consumed || state == ElementState::Released =>
            {
                match (button, state) {
                    (MouseButton::Left, ElementState::Pressed) => self.press(),
                    (MouseButton::Left, ElementState::Released) => self.release(),
                    (MouseButton::Right, s) => self.looking = s == ElementState::Pressed,
                    (MouseButton::Middle, s) => self.orbiting = s == ElementState::Pressed,
                    _ => {}
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _event_loop: &ActiveEventLoop) {
        if let Some(gfx) = &self.gfx {
            gfx.window.request_redraw();
        }
    }
}
