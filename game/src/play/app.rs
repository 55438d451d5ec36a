//! The game's frame in the window: what one turn of the event loop does for
//! the player's game (board time with its lesson, the tracked head, the
//! views, the panels, the pictures, the screenshot) or for a render node
//! (the master's frame), put together from the files of each concern; and
//! how `play` and `lightcone wall` start it in [`super::window`].

use std::path::PathBuf;
use std::time::Instant;

use winit::event::WindowEvent;
use winit::event_loop::ActiveEventLoop;
use winit::window::WindowId;

use super::actions::UiAction;
use super::cave_role::Immersion;
use super::cluster_role::{self, FrameLog, NodeRole, NodeStep};
use super::input::Input;
use super::layout::SceneArea;
use super::lesson_host::HostedLesson;
use super::panels::{self, Hud};
use super::pictures::Pictures;
use super::screenshot;
use super::shown::aspect;
use super::window::{self, Flow, Gfx};
use crate::cluster::master::ClusterMaster;
use crate::cluster::node::{ClusterNode, Headless, Stamps};
use crate::lesson::LessonHost;
use crate::model::{GameState, Pane};
use lightcone_tracker::cave::CaveConfig;

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
    window::run(&mut App::new(options)?)
}

/// Opens the window of a render node (`lightcone wall`) on its walls, once
/// the master's first frame is in; runs until the master is silent for
/// `options.silence`, `options.frames` frames were shown, or the window is
/// closed. Returns the frames shown.
pub fn run_node(mut node: ClusterNode, options: &Headless) -> Result<u64, String> {
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
    app.node = Some(NodeRole::new(node, first, options.frames, options.silence));
    window::run(&mut app)?;
    Ok(app.node.as_ref().map_or(0, |r| r.shown))
}

/// The game in its window.
struct App {
    state: GameState,
    lesson: HostedLesson,
    /// The tracked head and the CAVE.
    immersion: Immersion,
    input: Input,
    /// The scene renderer (made once the GPU is open).
    pictures: Option<Pictures>,
    /// Screenshot path and frame count (see [`Options`]).
    screenshot: Option<PathBuf>,
    frames: u32,
    /// Frames run so far.
    frame: u32,
    /// When the last frame began.
    last: Instant,
    /// The area the last frame's panels left for the pictures.
    area: SceneArea,
    /// Where the last frame's panels drew the space-time diagram.
    diagram: Option<super::diagram::Placed>,
    /// The render cluster this game is the master of.
    cluster: Option<ClusterMaster>,
    /// Where each frame's CAVE eyes are logged.
    frame_log: Option<FrameLog>,
    /// The render node this window is (`lightcone wall`).
    node: Option<NodeRole>,
    /// This frame's views were run before drawing (a render node runs them
    /// before the swap lock).
    views_done: bool,
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
        let frame_log = frame_log.as_deref().map(FrameLog::create).transpose()?;
        Ok(Self {
            immersion: Immersion::new(tracker, cave, game.scene.table.size),
            // The desktop game starts lessons from the scene menu.
            input: Input::new(true),
            lesson: HostedLesson::new(lesson, crate::lesson::supervise::window_isolation()),
            state: game,
            pictures: None,
            screenshot,
            frames,
            frame: 0,
            last: Instant::now(),
            area: SceneArea::default(),
            diagram: None,
            cluster,
            frame_log,
            node: None,
            views_done: false,
        })
    }

    /// Carries out what the keys and panels asked, in order.
    fn act(&mut self, actions: Vec<UiAction>) {
        for action in actions {
            match action.apply(&mut self.state) {
                Some(UiAction::CycleCaveEye) => self.immersion.cycle_eye(),
                Some(other) => self.lesson.act(other, &mut self.state),
                None => {}
            }
        }
    }

    /// The pictures' rectangles in a window of `size`, between the edges
    /// the last frame's panels left.
    fn rects(&self, (w, h): (u32, u32)) -> Vec<([f32; 4], Pane)> {
        self.area.rects(&self.state.pane_list(), w as f32, h as f32)
    }

    /// Runs the game's frame schedule for what this frame draws: the
    /// desktop pictures (laid out as the last frame's panels left room in
    /// a window of `size`), or the CAVE's stereo eyes. Everything drawn
    /// next (the views, the clocks, labels and picking) reads what it
    /// wrote.
    fn run_views(&mut self, size: (u32, u32)) {
        if self.immersion.run_stereo(&mut self.state) {
            return;
        }
        let panes: Vec<(Pane, f64)> = self
            .rects(size)
            .into_iter()
            .map(|(r, p)| (p, aspect(r)))
            .collect();
        self.state.run_frame(&panes);
    }

    /// The player's frame: time moves (the eye flies, the lesson runs, the
    /// tracked head is placed), the cluster is sent it, then it is drawn.
    fn player_frame(&mut self, gfx: &mut Gfx) -> Result<Flow, String> {
        let now = Instant::now();
        let dt = (now - self.last).as_secs_f64().min(0.1);
        self.last = now;
        self.fly(dt);
        self.lesson.step(&mut self.state, dt, now);
        self.immersion.place_eye(&mut self.state, now);
        self.frame += 1;
        let shot = self.screenshot.is_some() && self.frame >= self.frames;
        if let Some(master) = &mut self.cluster {
            cluster_role::publish(master, &self.state, &self.immersion);
        }
        // The frame log reads the views of the state just published: they
        // are run before the panels (drawn next) can change it.
        if self.frame_log.is_some() && self.immersion.cave.is_some() {
            self.run_views((0, 0));
            self.views_done = true;
            self.log_frame();
        }
        self.draw(gfx, shot)?;
        if let Some(master) = &mut self.cluster {
            for line in master.take_news() {
                crate::errln!("{line}");
                self.state.message = line;
            }
        }
        self.lesson.after_draw(&mut self.state);
        Ok(if shot { Flow::Exit } else { Flow::Continue })
    }

    /// Held keys fly the eye at a proper acceleration of 0.5 c per second
    /// (W/S, A/D, R/F); with a tracked head or a CAVE they carry the
    /// tracked space at 1 m/s instead.
    fn fly(&mut self, dt: f64) {
        let dir = self.input.flight(self.state.forward());
        if self.immersion.tracked() {
            let running = !(self.state.paused || self.state.replaying());
            self.immersion.fly(dir, dt, running);
        } else if dir != glam::DVec3::ZERO {
            self.state.thrust(dir * 0.5 * dt, dir * 1.0 * dt);
        }
    }

    /// Writes this frame's CAVE eyes to the frame log (`--frame-log`), as a
    /// render node logs them (after the frame's views were run); stops
    /// logging when the log cannot be written.
    fn log_frame(&mut self) {
        let (Some(log), Some(cave)) = (&mut self.frame_log, &self.immersion.cave) else {
            return;
        };
        let seq = self
            .cluster
            .as_ref()
            .map_or(u64::from(self.frame), ClusterMaster::seq);
        let stamps = Stamps {
            sample_ns: self.immersion.newest_sample_ns(),
            sent_ns: 0,
            shown_ns: crate::cluster::now_ns(),
        };
        let head = self.immersion.own_head().0;
        let stereo = &self.immersion.stereo;
        if let Err(e) = log.write(seq, head, stamps, &self.state, cave, stereo) {
            crate::errln!("--frame-log: {e}; no longer logging");
            self.frame_log = None;
        }
    }

    /// A render node's frame: the master's next one applied to the copy of
    /// its game, the walls' eyes computed, the swap lock, then drawn.
    fn node_frame(&mut self, gfx: &mut Gfx) -> Result<Flow, String> {
        let Some(role) = &mut self.node else {
            return Ok(Flow::Continue);
        };
        let frame = match role.next(&mut self.state)? {
            NodeStep::Show(frame) => frame,
            NodeStep::Wait => return Ok(Flow::Continue),
            NodeStep::Stop => return Ok(Flow::Exit),
        };
        if let Some(c) = &role.node.cave
            && self.immersion.cave.as_ref() != Some(c)
        {
            self.immersion.cave = Some(c.clone());
        }
        self.immersion.flight = frame.view.flight;
        self.immersion.node_head = Some(frame.view.head());
        self.frame += 1;
        self.run_views(gfx.size());
        self.views_done = true;
        let shown_ns = self.node.as_mut().map_or(0, |r| r.swap(frame.seq));
        let shot = self.screenshot.is_some() && self.frame >= self.frames;
        self.draw(gfx, shot)?;
        if let (Some(log), Some(cave)) = (&mut self.frame_log, &self.immersion.cave) {
            let stamps = Stamps {
                sample_ns: frame.sample_ns,
                sent_ns: frame.sent_ns,
                shown_ns,
            };
            let (head, stereo) = (frame.view.head_position, &self.immersion.stereo);
            if log
                .write(frame.seq, head, stamps, &self.state, cave, stereo)
                .is_err()
            {
                crate::errln!("--frame-log: cannot write; no longer logging");
                self.frame_log = None;
            }
        }
        let done = self.node.as_mut().is_some_and(|r| r.shown_one(shot));
        Ok(if done { Flow::Exit } else { Flow::Continue })
    }

    /// Draws the frame: the views (run again if the panels took another
    /// width), the panels, the pictures under them, then the screenshot
    /// (with `screenshot`) and the CAVE's outputs.
    fn draw(&mut self, gfx: &mut Gfx, screenshot: bool) -> Result<(), String> {
        let size = gfx.size();
        if !std::mem::take(&mut self.views_done) {
            self.run_views(size);
        }
        let (ui, area, actions) = self.panels(gfx);
        if area != self.area {
            // The panels took another width (the first frame, a resize):
            // frame the views for the room they now leave.
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
            let cave = self.immersion.cave.as_ref();
            let plans = self.area.plans(cave, &self.state.pane_list(), w, h);
            let walls = cave.map(|c| (c, &self.immersion.stereo[..]));
            pictures.draw(&gfx.gpu, target, size, &plans, &self.state, walls);
        }
        gfx.paint_ui(ui, target.as_ref());
        let Some(texture) = texture else {
            return Ok(());
        };
        let shot = self.screenshot.as_deref().filter(|_| screenshot);
        if let Some(path) = shot {
            screenshot::save_frame(&gfx.gpu, &gfx.config, &texture.texture, path)?;
            let (w, h) = (size.0 as f32, size.1 as f32);
            let cave = self.immersion.cave.as_ref();
            let sidecar = path.with_extension("json");
            let drawn = super::overlay::drawn(gfx.egui_context());
            let diagram = self.diagram;
            screenshot::save_layout(
                &self.state,
                cave,
                self.area,
                diagram,
                &sidecar,
                (w, h),
                &drawn,
            )?;
        }
        gfx.gpu.queue.present(texture);
        // The outputs: the same frame's views, each output's wall.
        self.immersion.draw_outputs(&gfx.gpu, &self.state, shot)
    }

    /// Runs this frame's panels (a render node's: one line of status).
    /// Returns them to paint, the area they leave and what they asked.
    fn panels(&mut self, gfx: &mut Gfx) -> (window::Ui, SceneArea, Vec<UiAction>) {
        let size = gfx.size();
        let mut area = self.area;
        let mut actions = Vec::new();
        let hud = Hud {
            tracker: self
                .immersion
                .status_line(self.cluster.as_ref().map(ClusterMaster::status_line)),
            tracker_colour: self.immersion.status_colour(),
            clocks: self.immersion.cave.is_none(),
            lesson: self.lesson.host.as_ref().map(LessonHost::name),
            lessons: true,
        };
        let node = self.immersion.node_head.is_some();
        let (state, lesson) = (&mut self.state, self.lesson.host.as_ref());
        let mut diagram = None;
        let ui = gfx.run_ui(|ui| {
            if node {
                panels::node_status(ui, &state.message);
                area = SceneArea {
                    left: 0.0,
                    right: size.0 as f32,
                };
            } else {
                area = panels::panels(ui, state, &hud, lesson, size, &mut actions);
                diagram = state
                    .show
                    .diagram
                    .then(|| super::diagram::placed(ui.ctx()))
                    .flatten();
            }
        });
        self.diagram = diagram;
        (ui, area, actions)
    }
}

impl window::Game for App {
    fn title(&self) -> String {
        match (&self.lesson.host, &self.node) {
            (_, Some(role)) => format!("Lightcone render node: {}", role.node.name),
            (Some(l), None) => format!("Lightcone lesson: {}", l.name()),
            (None, None) => format!("Lightcone: {}", self.state.scene.title),
        }
    }

    fn open_windows(
        &mut self,
        event_loop: &ActiveEventLoop,
        instance: &wgpu::Instance,
    ) -> Result<(), String> {
        self.immersion.open_outputs(event_loop, instance)
    }

    fn ready(&mut self, gfx: &Gfx) -> Result<(), String> {
        self.immersion.configure_outputs(&gfx.gpu)?;
        self.pictures = Some(Pictures::new(&gfx.gpu, gfx.config.format, gfx.size()));
        Ok(())
    }

    fn takes_input(&self) -> bool {
        // A render node shows the master's game: it takes no input.
        self.node.is_none()
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
        gfx: &Gfx,
        id: WindowId,
        event: &WindowEvent,
    ) -> Option<Result<Flow, String>> {
        // An output window: it follows its size; it is drawn with the main
        // window's frame, and keys pressed in it fly the head as in the
        // main window. Closing one ends the game, as closing the main
        // window does.
        let output = self.immersion.output(id)?;
        match event {
            WindowEvent::Resized(_) => {
                if let Err(e) = output.configure(&gfx.gpu) {
                    return Some(Err(e));
                }
            }
            WindowEvent::CloseRequested => return Some(Ok(Flow::Exit)),
            WindowEvent::KeyboardInput { event, .. } if self.node.is_none() => {
                let mut actions = Vec::new();
                self.input.keyboard(event, &mut self.state, &mut actions);
                self.act(actions);
            }
            _ => {}
        }
        Some(Ok(Flow::Continue))
    }

    fn frame(&mut self, gfx: &mut Gfx) -> Result<Flow, String> {
        if self.node.is_some() {
            self.node_frame(gfx)
        } else {
            self.player_frame(gfx)
        }
    }
}
