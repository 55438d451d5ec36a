//! A lesson in the browser: its Python runs in Pyodide in a Web Worker
//! (`web/static/lesson_worker.js`, started and spoken to by the page's
//! `window.lightconeLesson`, `web/static/lesson_host.js`), as the desktop
//! runs it in a child process: the same protocol (the JSON lines of
//! `lightcone_lesson::protocol`), carried by `postMessage` instead of a
//! pipe, the same hooks, and the same world's operations answered here
//! on the game (`lightcone_lesson::WorldCall`, borrowing the game for
//! each request: the page keeps it).
//!
//! The page never waits for the worker: each frame takes what has
//! arrived (a request is answered at once, a hook's end taken), sends the
//! next queued call, and while a hook is out board time waits. A hook
//! past its limit gets a `TimeoutError` at its line in the worker, as on
//! the desktop (`web/python/lightcone_web_child.py`); one that still runs
//! `protocol::HOOK_GRACE` later (a long call into C) ends the worker: the
//! game keeps its state, paused, and says why; *reload* starts a new
//! worker. Nothing the worker sends is trusted: a line over
//! `protocol::MAX_LINE`, a message that is not an `Up`, a request the game
//! does not serve, or a message when no call is out ends it, with the
//! reason.

use std::collections::VecDeque;
use std::time::Duration;

use lightcone_engine::report::CollisionLine;
use lightcone_lesson::protocol::{self, HOOK_GRACE, HOOK_LIMIT, MAX_LINE, PRINTED_LINES, Up};
use lightcone_lesson::{LessonGame, LessonUi, MAX_TEXT_BYTES, WorldCall, WorldCore};
use serde_json::Value;
use wasm_bindgen::prelude::*;
use web_time::Instant;

use super::lesson_panel::LessonStatus;
use crate::lesson_game::empty_game;
use crate::model::GameState;

#[wasm_bindgen]
extern "C" {
    /// Starts a new worker for the lesson `name` with its `source` (ends
    /// the old one).
    #[wasm_bindgen(catch, js_namespace = lightconeLesson, js_name = open)]
    fn js_open(name: &str, source: &str, limit_s: f64) -> Result<(), JsValue>;
    /// Sends a line (a call, or the answer to a request) to the worker.
    #[wasm_bindgen(catch, js_namespace = lightconeLesson, js_name = send)]
    fn js_send(line: &str) -> Result<(), JsValue>;
    /// The worker's messages since the last take.
    #[wasm_bindgen(catch, js_namespace = lightconeLesson, js_name = take)]
    fn js_take() -> Result<js_sys::Array, JsValue>;
    /// Ends the worker.
    #[wasm_bindgen(catch, js_namespace = lightconeLesson, js_name = stop)]
    fn js_stop() -> Result<(), JsValue>;
    /// Has `f` called after each message from the worker.
    #[wasm_bindgen(catch, js_namespace = lightconeLesson, js_name = onMessage)]
    fn js_on_message(f: &js_sys::Function) -> Result<(), JsValue>;
}

/// Has the page wake the game's loop at each message from the worker
/// (`window::wake`), so a request is answered at once rather than at the
/// next frame. Set once for the page's life.
fn wake_on_messages() {
    thread_local! {
        static SET: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    }
    if SET.with(|s| s.replace(true)) {
        return;
    }
    let wake = Closure::<dyn FnMut()>::new(super::window::wake);
    if js_on_message(wake.as_ref().unchecked_ref()).is_ok() {
        wake.forget();
    } else {
        SET.with(|s| s.set(false));
    }
}

/// One message of the page's host (`lightconeLesson.take()`).
enum FromWorker {
    /// Python is up, the package installed: calls may go.
    Ready,
    /// A line the worker wrote.
    Line(String),
    /// Python could not start there (or the browser cannot run it).
    Failed(String),
    /// The worker ended (an error event, a crash).
    Ended(String),
}

fn field(message: &JsValue, name: &str) -> Option<String> {
    js_sys::Reflect::get(message, &name.into())
        .ok()
        .and_then(|v| v.as_string())
}

fn take() -> Result<Vec<FromWorker>, String> {
    let all =
        js_take().map_err(|e| format!("the page cannot talk to the lesson's worker: {e:?}"))?;
    Ok(all
        .iter()
        .filter_map(|m| {
            Some(match field(&m, "kind")?.as_str() {
                "ready" => FromWorker::Ready,
                "line" => FromWorker::Line(field(&m, "line")?),
                "failed" => FromWorker::Failed(field(&m, "error").unwrap_or_default()),
                "ended" => FromWorker::Ended(field(&m, "why").unwrap_or_default()),
                _ => return None,
            })
        })
        .collect())
}

/// A lesson running (or failed) in the page's worker.
pub struct WebLesson {
    /// Its file's name, and its text (a reload starts it again).
    name: String,
    source: String,
    /// It is a shipped lesson (`crate::assets::LESSONS`): its link names it.
    shipped: bool,
    /// The lesson's world: its screen (the game stays the page's).
    world: WorldCore,
    /// The game `setup` is building.
    pending: Option<GameState>,
    /// Python is up in the worker.
    ready: bool,
    /// When the worker was started (how long Python takes to start).
    opened: Instant,
    /// The call out: its hook and when it was sent.
    out: Option<(&'static str, Instant)>,
    /// Calls waiting for the one out to end.
    queue: VecDeque<(&'static str, Value)>,
    /// The hooks the lesson defines (known after `setup`).
    hooks: Vec<String>,
    /// Collisions already passed to `on_collision`.
    seen_collisions: u64,
    /// The world's generation those collisions belong to.
    generation: u64,
    /// Why the hooks stopped, shown until a reload works.
    pub error: Option<String>,
    /// The lesson called `world.finish()`.
    finished: bool,
    /// Longest a hook may run.
    pub limit: Duration,
}

impl WebLesson {
    /// Starts the lesson `name` (its `source`) in a new worker; its
    /// `setup` runs once Python is up there, and replaces the game when it
    /// ends (until then board time waits). Fails when the page has no
    /// lesson host (an old `index.html`).
    pub fn open(name: &str, source: String, shipped: bool) -> Result<Self, String> {
        let mut lesson = Self {
            name: name.to_owned(),
            source,
            shipped,
            world: WorldCore::new(".".into()),
            pending: None,
            ready: false,
            opened: Instant::now(),
            out: None,
            queue: VecDeque::new(),
            hooks: Vec::new(),
            seen_collisions: 0,
            generation: 0,
            error: None,
            finished: false,
            limit: HOOK_LIMIT,
        };
        lesson.start()?;
        Ok(lesson)
    }

    /// A new worker, a fresh world, `setup` queued.
    fn start(&mut self) -> Result<(), String> {
        wake_on_messages();
        js_open(&self.name, &self.source, self.limit.as_secs_f64())
            .map_err(|e| format!("the page cannot start the lesson's worker: {e:?}"))?;
        self.world = WorldCore::new(".".into());
        self.pending = None;
        self.ready = false;
        self.opened = Instant::now();
        self.out = None;
        self.queue = VecDeque::from([("setup", Value::Array(vec![]))]);
        self.hooks.clear();
        self.seen_collisions = 0;
        self.error = None;
        self.finished = false;
        Ok(())
    }

    /// Starts the lesson again in a new worker (the reload button); the
    /// game is replaced when its `setup` ends.
    pub fn reload(&mut self, game: &mut GameState) {
        if let Err(e) = self.start() {
            self.fail(game, e);
        }
    }

    /// Whether hooks run: not failed, not finished.
    pub fn running(&self) -> bool {
        self.error.is_none() && !self.finished
    }

    /// Whether a hook is out in the worker (or waiting to be): board time
    /// waits meanwhile.
    pub fn busy(&self) -> bool {
        self.out.is_some() || !self.queue.is_empty()
    }

    /// The lesson finished with a closing message that waits for an
    /// event's light still on its way.
    pub fn awaiting_light(&self) -> bool {
        self.finished && self.world.ui.finish_light.is_some()
    }

    /// Shows the closing message once the light it waits for has reached
    /// the eye looked through now (as the desktop's host does).
    pub fn watch_light(&mut self, game: &GameState) {
        self.world.ui.light_arrived(game.eye().event, game.scene.c);
    }

    /// Queues `hook(world, *args)` if the lesson defines it.
    fn queue(&mut self, hook: &'static str, args: Value) {
        if self.running() && self.hooks.iter().any(|h| h == hook) {
            self.queue.push_back((hook, args));
        }
    }

    /// After a frame's step: `on_collision` for each new collision, then
    /// `on_frame` if board time advanced since `before`, queued and the
    /// first of them sent.
    pub fn after_step(&mut self, game: &mut GameState, before: f64) {
        let n = game.physics().collision_count();
        if n < self.seen_collisions {
            self.seen_collisions = 0; // the game restarted under the lesson
        }
        while self.running() && self.seen_collisions < n {
            let i = self.seen_collisions;
            self.seen_collisions += 1;
            if game.physics().collisions_forgotten() > i {
                continue;
            }
            let Some(record) = game.physics().collisions_from(i).first() else {
                continue;
            };
            let Ok(data) = serde_json::to_value(CollisionLine::new(game.physics(), record)) else {
                continue;
            };
            self.queue(
                "on_collision",
                serde_json::json!([{"$record": "Collision", "data": data}]),
            );
        }
        if game.live_time > before {
            self.queue("on_frame", serde_json::json!([game.live_time]));
        }
        self.serve(game);
    }

    /// The student chose `choice` for the open question: recorded, time
    /// resumed if the question paused it, `on_answer` queued.
    pub fn answer(&mut self, game: &mut GameState, choice: usize) {
        let Some((question, chosen, resume)) = self.world.ui.choose(choice) else {
            return;
        };
        if resume {
            game.paused = false;
        }
        self.queue("on_answer", serde_json::json!([question, chosen]));
        self.serve(game);
    }

    /// Takes what the worker sent (answering its requests on `game`),
    /// sends the next queued call, and ends a hook past its limit. Never
    /// waits.
    pub fn serve(&mut self, game: &mut GameState) {
        let messages = match take() {
            Ok(m) => m,
            Err(e) => return self.fail(game, e),
        };
        for message in messages {
            match message {
                FromWorker::Ready => self.ready = true,
                FromWorker::Failed(why) => {
                    return self.end(game, format!("Python could not start in the page: {why}"));
                }
                FromWorker::Ended(why) => {
                    return self.end(game, format!("the lesson's worker ended: {why}"));
                }
                FromWorker::Line(line) => {
                    if let Err(why) = self.handle(game, &line) {
                        return self.end(
                            game,
                            format!("the lesson's worker misbehaved: {why}; it was stopped"),
                        );
                    }
                }
            }
        }
        if let Some((hook, since)) = self.out {
            if since.elapsed() > self.limit + HOOK_GRACE {
                let why = format!(
                    "in {hook}: the hook ran longer than its limit of {} s and did not stop at its \
                     TimeoutError (a long call into C?); its worker was stopped. Reload to start the \
                     lesson again.",
                    self.limit.as_secs_f64()
                );
                self.end(game, why);
            }
            return;
        }
        if !self.ready {
            return;
        }
        let Some((hook, args)) = self.queue.pop_front() else {
            return;
        };
        if hook != "setup" && !self.running() {
            self.queue.clear();
            return;
        }
        // No game yet in `setup`: the snapshot says why.
        let shown = (hook != "setup").then_some(&*game as &dyn LessonGame);
        let line = protocol::call_line(shown, hook, &args);
        if let Err(e) = js_send(&line) {
            return self.end(game, format!("cannot call {hook}: {e:?}"));
        }
        self.out = Some((hook, Instant::now()));
    }

    /// One line from the worker.
    fn handle(&mut self, game: &mut GameState, line: &str) -> Result<(), String> {
        if line.len() > MAX_LINE {
            return Err(format!(
                "a line of {} bytes (at most {MAX_LINE})",
                line.len()
            ));
        }
        let up: Up = serde_json::from_str(line)
            .map_err(|e| format!("it sent a message the game does not understand ({e})"))?;
        let Some((hook, _)) = self.out else {
            return Err("it sent a message while no call was out".to_owned());
        };
        match up {
            Up::Request { op, args, kwargs } => {
                if !protocol::serves(&op) {
                    return Err(format!(
                        "it asked the game for {op:?}, which the game does not serve"
                    ));
                }
                let reply = self.on_world(game, hook == "setup", |world| {
                    protocol::reply_line(world, &op, &args, &kwargs)
                });
                js_send(&reply).map_err(|e| format!("cannot answer: {e:?}"))?;
            }
            Up::Done {
                error,
                timed_out,
                printed,
                hooks,
            } => {
                self.out = None;
                if hook == "setup" {
                    self.hooks = hooks;
                }
                let error = error.map(|e| {
                    if timed_out {
                        format!(
                            "{e}\n(stopped at its limit of {} s)",
                            self.limit.as_secs_f64()
                        )
                    } else {
                        e
                    }
                });
                self.hook_done(game, hook, error, printed);
            }
        }
        Ok(())
    }

    /// Runs `f` on the world for one request, borrowing the game: the
    /// student's, or in `setup` the game the lesson is building (shown
    /// once setup has ended well).
    fn on_world<R>(
        &mut self,
        game: &mut GameState,
        setup: bool,
        f: impl FnOnce(&mut WorldCall<'_>) -> R,
    ) -> R {
        let target = if setup {
            self.pending.get_or_insert_with(empty_game)
        } else {
            game
        };
        let result = f(&mut self.world.on(Some(target)));
        if !setup && self.world.generation != self.generation {
            // world.start in a hook: the collision list restarted.
            self.generation = self.world.generation;
            self.seen_collisions = 0;
        }
        result
    }

    /// The lesson's hook ended.
    fn hook_done(
        &mut self,
        game: &mut GameState,
        hook: &'static str,
        error: Option<String>,
        printed: Vec<String>,
    ) {
        let kept = &mut self.world.ui.printed;
        kept.extend(protocol::printed_tail(printed));
        let extra = kept.len().saturating_sub(PRINTED_LINES);
        kept.drain(..extra);
        self.finished = self.world.ui.finished.is_some();
        if let Some(error) = error {
            self.pending = None;
            let _ = js_stop();
            return self.fail(game, lightcone_lesson::cut(&error, MAX_TEXT_BYTES));
        }
        if hook == "setup" {
            match self.pending.take() {
                Some(new) if self.world.started() => {
                    *game = new;
                    self.generation = self.world.generation;
                    self.seen_collisions = 0;
                }
                _ => {
                    let _ = js_stop();
                    self.fail(
                        game,
                        format!(
                            "{}: setup(world) did not call world.start(scene)",
                            self.name
                        ),
                    );
                }
            }
        }
    }

    /// Ends the worker and stops the hooks with `message`.
    fn end(&mut self, game: &mut GameState, message: String) {
        let _ = js_stop();
        self.out = None;
        self.queue.clear();
        self.pending = None;
        self.fail(game, message);
    }

    /// Stops the hooks, pauses the game and keeps `message` for the
    /// screen and the console.
    fn fail(&mut self, game: &mut GameState, message: String) {
        let message = lightcone_lesson::cut(&message, MAX_TEXT_BYTES);
        web_sys::console::error_1(&format!("lesson {} stopped:\n{message}", self.name).into());
        game.paused = true;
        self.error = Some(message);
    }

    /// What the lesson shows.
    pub fn ui(&self) -> &LessonUi {
        &self.world.ui
    }

    /// The lesson's file name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Whether it is a shipped lesson.
    pub fn shipped(&self) -> bool {
        self.shipped
    }

    /// The link that opens this lesson in the page served at `base`:
    /// `?lesson=NAME` for a shipped one, else its text in `#lesson=DATA`.
    pub fn link(&self, base: &str) -> String {
        if self.shipped {
            crate::links::shipped_lesson_link(base, &self.name)
        } else {
            crate::links::file_link(base, &self.name, &self.source)
        }
    }
}

impl Drop for WebLesson {
    /// Its worker ends with it (a scene opened in the menu ends the
    /// lesson). The page has one worker at a time: drop the old lesson
    /// before opening another.
    fn drop(&mut self) {
        let _ = js_stop();
    }
}

impl LessonStatus for WebLesson {
    fn title(&self) -> String {
        self.name.clone()
    }

    fn hook_running(&self) -> Option<(&'static str, Duration)> {
        self.out.map(|(hook, since)| (hook, since.elapsed()))
    }

    fn limit(&self) -> Duration {
        self.limit
    }

    fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }

    fn screen(&self, f: &mut dyn FnMut(&LessonUi)) {
        f(&self.world.ui);
    }

    fn starting(&self) -> Option<String> {
        (!self.ready && self.error.is_none()).then(|| {
            format!(
                "Starting Python in the page ({:.0} s; the first time it is downloaded, about 10 MB)…",
                self.opened.elapsed().as_secs_f64()
            )
        })
    }
}
