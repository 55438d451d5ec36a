//! The game's frame in the window: what one turn of the event loop does for
//! the player's game (board time with its lesson, the tracked head, the
//! views, the panels, the pictures, the screenshot) or for a render node
//! (the master's frame), put together from the files of each concern; and
//! how `play` and `lightcone wall` start it in [`super::window`].

use std::path::PathBuf;

use winit::event::WindowEvent;
use winit::event_loop::ActiveEventLoop;
use winit::window::WindowId;

use super::actions::UiAction;
use super::cave_role::Immersion;
use super::cluster_role::{self, FrameLog, NodeRole, NodeStep};
use super::layout::SceneArea;
use super::lesson_host::HostedLesson;
use super::panels::{self, Hud};
use super::screenshot;
use super::stage::{Host, Stage};
use super::window::{self, Flow, Gfx};
use crate::cluster::master::ClusterMaster;
use crate::cluster::node::{ClusterNode, Headless, Stamps};
use crate::lesson::LessonHost;
use crate::model::GameState;
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

/// The game in its window: the shared frame ([`Stage`]) and what the
/// desktop adds to it ([`Desk`]), with the screenshot, the frame log and
/// a render node's role.
struct App {
    stage: Stage,
    desk: Desk,
    /// Screenshot path and frame count (see [`Options`]).
    screenshot: Option<PathBuf>,
    frames: u32,
    /// Frames run so far.
    frame: u32,
    /// Where each frame's CAVE eyes are logged.
    frame_log: Option<FrameLog>,
    /// The render node this window is (`lightcone wall`).
    node: Option<NodeRole>,
    /// This frame's views were run before drawing (a render node runs them
    /// before the swap lock).
    views_done: bool,
}

/// What the desktop window adds to the shared frame: the lesson, the
/// tracked head and the CAVE, the render cluster it is the master of,
/// and where the panels drew the diagram (for the screenshot's sidecar).
struct Desk {
    lesson: HostedLesson,
    /// The tracked head and the CAVE.
    immersion: Immersion,
    /// The render cluster this game is the master of.
    cluster: Option<ClusterMaster>,
    /// Where the last frame's panels drew the space-time diagram.
    diagram: Option<super::diagram::Placed>,
}

impl Host for Desk {
    fn run_views(&mut self, state: &mut GameState) -> bool {
        self.immersion.run_stereo(state)
    }

    /// The player's panels, or a render node's one line of status.
    fn panels(
        &mut self,
        ui: &mut egui::Ui,
        state: &mut GameState,
        size: (u32, u32),
        actions: &mut Vec<UiAction>,
    ) -> SceneArea {
        if self.immersion.node_head.is_some() {
            panels::node_status(ui, &state.message);
            self.diagram = None;
            return SceneArea {
                left: 0.0,
                right: size.0 as f32,
            };
        }
        let hud = Hud {
            tracker: self
                .immersion
                .status_line(self.cluster.as_ref().map(ClusterMaster::status_line)),
            tracker_colour: self.immersion.status_colour(),
            clocks: self.immersion.cave.is_none(),
            lesson: self.lesson.host.as_ref().map(LessonHost::name),
            lessons: true,
            share: false,
        };
        let area = panels::panels(
            ui,
            state,
            &hud,
            self.lesson
                .host
                .as_ref()
                .map(|h| h as &dyn super::lesson_panel::LessonStatus),
            size,
            actions,
        );
        self.diagram = state
            .show
            .diagram
            .then(|| super::diagram::placed(ui.ctx()))
            .flatten();
        area
    }

    fn act(&mut self, action: UiAction, state: &mut GameState) {
        match action {
            UiAction::CycleCaveEye => self.immersion.cycle_eye(),
            UiAction::Share => {
                state.message = "links are for the browser build: `lightcone link SCENE.toml` prints the link of a scene file".to_owned();
            }
            other => self.lesson.act(other, state),
        }
    }

    fn walls(&self) -> Option<super::pictures::Walls<'_>> {
        self.immersion
            .cave
            .as_ref()
            .map(|c| (c, &self.immersion.stereo[..]))
    }
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
            desk: Desk {
                immersion: Immersion::new(tracker, cave, game.scene.table.size),
                lesson: HostedLesson::new(lesson, crate::lesson::supervise::window_isolation()),
                cluster,
                diagram: None,
            },
            // The desktop game starts lessons from the scene menu.
            stage: Stage::new(game, true),
            screenshot,
            frames,
            frame: 0,
            frame_log,
            node: None,
            views_done: false,
        })
    }

    /// The player's frame: time moves (the eye flies, the lesson runs, the
    /// tracked head is placed), the cluster is sent it, then it is drawn.
    fn player_frame(&mut self, gfx: &mut Gfx) -> Result<Flow, String> {
        let (now, dt) = self.stage.tick();
        self.fly(dt);
        let state = &mut self.stage.state;
        self.desk.lesson.step(state, dt, now);
        self.desk.immersion.place_eye(state, now);
        self.frame += 1;
        let shot = self.screenshot.is_some() && self.frame >= self.frames;
        if let Some(master) = &mut self.desk.cluster {
            cluster_role::publish(master, state, &self.desk.immersion);
        }
        // The frame log reads the views of the state just published: they
        // are run before the panels (drawn next) can change it.
        if self.frame_log.is_some() && self.desk.immersion.cave.is_some() {
            self.stage.run_views(&mut self.desk, (0, 0));
            self.views_done = true;
            self.log_frame();
        }
        self.draw(gfx, shot)?;
        let state = &mut self.stage.state;
        if let Some(master) = &mut self.desk.cluster {
            for line in master.take_news() {
                crate::errln!("{line}");
                state.message = line;
            }
        }
        self.desk.lesson.after_draw(state);
        Ok(if shot { Flow::Exit } else { Flow::Continue })
    }

    /// Held keys fly the eye (see [`Stage::fly_free`]); with a tracked
    /// head or a CAVE they carry the tracked space at 1 m/s instead.
    fn fly(&mut self, dt: f64) {
        let immersion = &mut self.desk.immersion;
        if immersion.tracked() {
            let state = &self.stage.state;
            let dir = self.stage.input.flight(state.forward());
            let running = !(state.paused || state.replaying());
            immersion.fly(dir, dt, running);
        } else {
            self.stage.fly_free(dt);
        }
    }

    /// Writes this frame's CAVE eyes to the frame log (`--frame-log`), as a
    /// render node logs them (after the frame's views were run); stops
    /// logging when the log cannot be written.
    fn log_frame(&mut self) {
        let immersion = &self.desk.immersion;
        let (Some(log), Some(cave)) = (&mut self.frame_log, &immersion.cave) else {
            return;
        };
        let seq = self
            .desk
            .cluster
            .as_ref()
            .map_or(u64::from(self.frame), ClusterMaster::seq);
        let stamps = Stamps {
            sample_ns: immersion.newest_sample_ns(),
            sent_ns: 0,
            shown_ns: crate::cluster::now_ns(),
        };
        let head = immersion.own_head().0;
        let stereo = &immersion.stereo;
        if let Err(e) = log.write(seq, head, stamps, &self.stage.state, cave, stereo) {
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
        let frame = match role.next(&mut self.stage.state)? {
            NodeStep::Show(frame) => frame,
            NodeStep::Wait => return Ok(Flow::Continue),
            NodeStep::Stop => return Ok(Flow::Exit),
        };
        let immersion = &mut self.desk.immersion;
        if let Some(c) = &role.node.cave
            && immersion.cave.as_ref() != Some(c)
        {
            immersion.cave = Some(c.clone());
        }
        immersion.flight = frame.view.flight;
        immersion.node_head = Some(frame.view.head());
        self.frame += 1;
        self.stage.run_views(&mut self.desk, gfx.size());
        self.views_done = true;
        let shown_ns = self.node.as_mut().map_or(0, |r| r.swap(frame.seq));
        let shot = self.screenshot.is_some() && self.frame >= self.frames;
        self.draw(gfx, shot)?;
        let immersion = &self.desk.immersion;
        if let (Some(log), Some(cave)) = (&mut self.frame_log, &immersion.cave) {
            let stamps = Stamps {
                sample_ns: frame.sample_ns,
                sent_ns: frame.sent_ns,
                shown_ns,
            };
            let (head, stereo) = (frame.view.head_position, &immersion.stereo);
            if log
                .write(frame.seq, head, stamps, &self.stage.state, cave, stereo)
                .is_err()
            {
                crate::errln!("--frame-log: cannot write; no longer logging");
                self.frame_log = None;
            }
        }
        let done = self.node.as_mut().is_some_and(|r| r.shown_one(shot));
        Ok(if done { Flow::Exit } else { Flow::Continue })
    }

    /// Draws the frame ([`Stage::draw`]), then the screenshot (with
    /// `screenshot`) and the CAVE's outputs.
    fn draw(&mut self, gfx: &mut Gfx, screenshot: bool) -> Result<(), String> {
        let views_done = std::mem::take(&mut self.views_done);
        let Some(texture) = self.stage.draw(&mut self.desk, gfx, views_done) else {
            return Ok(());
        };
        let shot = self.screenshot.as_deref().filter(|_| screenshot);
        if let Some(path) = shot {
            screenshot::save_frame(&gfx.gpu, &gfx.config, &texture.texture, path)?;
            let (w, h) = (gfx.size().0 as f32, gfx.size().1 as f32);
            let cave = self.desk.immersion.cave.as_ref();
            let sidecar = path.with_extension("json");
            let drawn = super::overlay::drawn(gfx.egui_context());
            screenshot::save_layout(
                &self.stage.state,
                cave,
                self.stage.area,
                self.desk.diagram,
                &sidecar,
                (w, h),
                &drawn,
            )?;
        }
        gfx.gpu.queue.present(texture);
        // The outputs: the same frame's views, each output's wall.
        self.desk
            .immersion
            .draw_outputs(&gfx.gpu, &self.stage.state, shot)
    }
}

impl window::Game for App {
    fn title(&self) -> String {
        match (&self.desk.lesson.host, &self.node) {
            (_, Some(role)) => format!("Lightcone render node: {}", role.node.name),
            (Some(l), None) => format!("Lightcone lesson: {}", l.name()),
            (None, None) => format!("Lightcone: {}", self.stage.state.scene.title),
        }
    }

    fn open_windows(
        &mut self,
        event_loop: &ActiveEventLoop,
        instance: &wgpu::Instance,
    ) -> Result<(), String> {
        self.desk.immersion.open_outputs(event_loop, instance)
    }

    fn ready(&mut self, gfx: &Gfx) -> Result<(), String> {
        self.desk.immersion.configure_outputs(&gfx.gpu)?;
        self.stage.ready(gfx);
        Ok(())
    }

    fn takes_input(&self) -> bool {
        // A render node shows the master's game: it takes no input.
        self.node.is_none()
    }

    fn input(&mut self, gfx: &Gfx, event: &WindowEvent, consumed: bool) {
        self.stage.input(&mut self.desk, gfx, event, consumed);
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
        let output = self.desk.immersion.output(id)?;
        match event {
            WindowEvent::Resized(_) => {
                if let Err(e) = output.configure(&gfx.gpu) {
                    return Some(Err(e));
                }
            }
            WindowEvent::CloseRequested => return Some(Ok(Flow::Exit)),
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
