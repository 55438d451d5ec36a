//! The game in a browser tab (wasm32): the shared frame
//! ([`super::stage`]) with what the page adds: scenes and lessons opened
//! by link (`?scene=NAME`, `?lesson=NAME`, `#scene=DATA`, `#lesson=DATA`,
//! [`crate::links`]) or by a file dropped on the page, a lesson's Python
//! run in a Web Worker ([`super::web_lesson`]), and a *share* button that
//! copies the link of what is open. What needs the desktop (the tracked
//! head, CAVE outputs, the render cluster, screenshots to files) is not
//! here.

use std::cell::RefCell;

use lightcone_engine::scene::{self, Scene};
use winit::event::WindowEvent;
use winit::window::WindowId;

use super::actions::UiAction;
use super::layout::SceneArea;
use super::lesson_panel::LessonStatus;
use super::panels::{self, Hud};
use super::scene_menu::Choice;
use super::stage::{Host, Stage};
use super::web_lesson::WebLesson;
use super::window::{self, Flow, Gfx};
use crate::links::{self, Kind, SceneSource};
use crate::model::GameState;

/// Largest file the page opens when dropped on it, bytes (the page checks
/// the size before reading the file).
pub const MAX_DROPPED: usize = links::MAX_TEXT;

/// What the page opens: the link's query (`location.search`) and fragment
/// (`location.hash`).
pub struct Address<'a> {
    /// `?scene=NAME`, if given.
    pub scene: Option<&'a str>,
    /// `?lesson=NAME`, if given: a shipped lesson (`.py` optional).
    pub lesson: Option<&'a str>,
    /// `?at=T`: open paused at board time `T` s (as `play --at`), from
    /// [`AT_RANGE`].
    pub at: Option<&'a str>,
    /// The fragment, with or without its `#` (`#scene=DATA`).
    pub fragment: &'a str,
    /// `?gpu=webgpu`: draw with the browser's WebGPU where it gives an
    /// adapter (else, and by default, WebGL2; see [`WebApp::webgpu`]).
    pub gpu: Option<&'a str>,
    /// `?drive=FPS`: play the lesson with nobody at the page, as
    /// `lightcone lesson --fps FPS` does: board time moves 1/FPS real
    /// seconds a frame (whatever the page's own frame rate), only between
    /// hooks, and each question is answered with the lesson's own answer
    /// (the first choice when it names none), until the lesson finishes.
    /// For the browser test's comparison with the desktop.
    pub drive: Option<&'a str>,
}

/// The board times `?at=` may name, s (the replay window's length ahead,
/// a minute of the time before the start behind): the page runs the
/// physics to it before its first frame.
pub const AT_RANGE: std::ops::RangeInclusive<f64> = -60.0..=600.0;

/// Starts the game on the page: the scene the address names (a file
/// carried in the fragment first, then `?scene=NAME` of a shipped scene),
/// else the default one. What the address names but cannot be opened (a
/// scene that is not shipped, a link cut short, a scene with errors, a
/// lesson) is said in the scene menu over the default scene, with the
/// errors located as `lightcone check` locates them. Returns once the
/// event loop is running (the browser drives it).
pub fn start(address: &Address<'_>) -> Result<(), String> {
    let mut state = default_game()?;
    let mut page = Page { lesson: None };
    match open_address(&mut state, address) {
        Ok(Some((name, text, shipped))) => page.open_lesson(&mut state, &name, text, shipped),
        Ok(None) => {}
        Err(e) => say_in_menu(&mut state, e),
    }
    let at = address.at.map(|at| go_to(&mut state, at));
    if let Some(Err(e)) = &at {
        say_in_menu(&mut state, e.clone());
    }
    let drive = match address.drive.map(str::parse::<f64>) {
        None => None,
        Some(Ok(fps)) if fps.is_finite() && fps > 0.0 && fps <= 1000.0 => Some(fps),
        Some(_) => {
            say_in_menu(
                &mut state,
                "?drive=FPS: give frames a second in (0, 1000]".to_owned(),
            );
            None
        }
    };
    let addressed = (state.generation, state.source.clone());
    window::spawn(WebApp {
        addressed,
        stage: Stage::new(state, false),
        page,
        frames: 0,
        stroke: None,
        publish_seen: matches!(at, Some(Ok(()))),
        cpu_ms: std::collections::VecDeque::with_capacity(CPU_FRAMES),
        webgpu: address.gpu == Some("webgpu"),
        drive,
    })
}

/// Goes to the board time `at` names (`?at=T`), paused there.
fn go_to(state: &mut GameState, at: &str) -> Result<(), String> {
    let t: f64 = at
        .trim()
        .parse()
        .map_err(|_| format!("?at={at}: not a board time in seconds"))?;
    if !AT_RANGE.contains(&t) {
        return Err(format!(
            "?at={at}: give a board time from {} to {} s",
            AT_RANGE.start(),
            AT_RANGE.end()
        ));
    }
    state.show_at(t);
    Ok(())
}

/// The default scene, paused on its title.
fn default_game() -> Result<GameState, String> {
    let scene = crate::assets::default_scene().map_err(|e| e.to_string())?;
    let mut state = GameState::new(scene);
    // As `play` opens a scene: paused on its title and description.
    state.paused = true;
    state.intro = true;
    let name = crate::DEFAULT_SCENE.rsplit('/').next().unwrap_or_default();
    state.source = Some(SceneSource::Shipped(name.to_owned()));
    Ok(state)
}

/// A lesson to start: its file's name, its text, and whether it is a
/// shipped one.
type LessonFile = (String, String, bool);

/// Opens the scene `address` names in `state` (nothing: the default scene
/// stays), or returns the lesson it names, for the page to start.
fn open_address(
    state: &mut GameState,
    address: &Address<'_>,
) -> Result<Option<LessonFile>, String> {
    if let Some(carried) = links::from_fragment(address.fragment) {
        let (kind, text) = carried.map_err(|e| e.to_string())?;
        let name = match kind {
            Kind::Lesson => "lesson_from_link.py".to_owned(),
            Kind::Scene => format!("the link's {}", kind.key()),
        };
        return open_text(state, kind, &name, text);
    }
    if let Some(name) = address.lesson {
        let file = if name.ends_with(".py") {
            name.to_owned()
        } else {
            format!("{name}.py")
        };
        return match crate::assets::LESSONS.iter().find(|(n, _)| *n == file) {
            Some((n, text)) => Ok(Some(((*n).to_owned(), (*text).to_owned(), true))),
            None => {
                let names: Vec<&str> = crate::assets::LESSONS.iter().map(|(n, _)| *n).collect();
                Err(format!(
                    "?lesson={name}: not a shipped lesson (one of {})",
                    names.join(", ")
                ))
            }
        };
    }
    let Some(name) = address.scene else {
        return Ok(None);
    };
    let file = if name.ends_with(".toml") {
        name.to_owned()
    } else {
        format!("{name}.toml")
    };
    match crate::assets::shipped_scene(&file) {
        Some(scene) => {
            let scene = scene.map_err(|e| e.to_string())?;
            open_scene(state, scene, SceneSource::Shipped(file));
            Ok(None)
        }
        None => {
            let names: Vec<&str> = crate::assets::SCENES.iter().map(|(n, _)| *n).collect();
            Err(format!(
                "?scene={name}: not a shipped scene (one of {})",
                names.join(", ")
            ))
        }
    }
}

/// Opens a file's `text`, named `name` in messages: a scene, checked as
/// `lightcone check` does; a lesson is returned, for the page to start.
fn open_text(
    state: &mut GameState,
    kind: Kind,
    name: &str,
    text: String,
) -> Result<Option<LessonFile>, String> {
    if kind == Kind::Lesson {
        return Ok(Some((name.to_owned(), text, false)));
    }
    let scene = scene::parse(&text, name).map_err(|e| e.to_string())?;
    let source = SceneSource::Text {
        name: name.to_owned(),
        text,
    };
    open_scene(state, scene, source);
    Ok(None)
}

/// `scene` in place of the game, paused on its title, as the scene menu
/// opens one.
fn open_scene(state: &mut GameState, scene: Scene, source: SceneSource) {
    super::scene_menu::switch(state, scene, Some(source));
}

/// Shows `message` in the scene menu (opened), where a scene that cannot
/// be opened is reported, and in the console; the game behind it goes on.
fn say_in_menu(state: &mut GameState, message: String) {
    web_sys::console::error_1(&format!("lightcone: {message}").into());
    state.scene_menu.open = true;
    state.scene_menu.error = Some(message);
}

/// A file dropped on the page, waiting for the next frame: its name, and
/// its text (`None` when it was larger than [`MAX_DROPPED`] and not
/// read).
type Dropped = (String, Option<String>);

thread_local! {
    /// The newest file dropped on the page and not yet opened (one: a
    /// second drop before the next frame replaces the first).
    static DROPPED: RefCell<Option<Dropped>> = const { RefCell::new(None) };
}

/// Hands the game a file dropped on the page (the page's `drop` handler
/// calls it): opened at the next frame. `text` is `None` for a file the
/// page did not read because it is larger than [`MAX_DROPPED`].
pub fn drop_file(name: String, text: Option<String>) {
    DROPPED.with(|d| *d.borrow_mut() = Some((name, text)));
}

/// What the page adds to the shared frame: the lesson (in its worker)
/// and the share button.
struct Page {
    lesson: Option<WebLesson>,
}

impl Page {
    /// Starts the lesson `name` (its `text`) in place of the one that ran;
    /// the game is replaced when its `setup` ends (until then board time
    /// waits). What cannot start is said in the scene menu.
    fn open_lesson(&mut self, state: &mut GameState, name: &str, text: String, shipped: bool) {
        // The old lesson's worker ends first (dropped after, it would end
        // the new one's: the page runs one worker).
        self.lesson = None;
        match WebLesson::open(name, text, shipped) {
            Ok(lesson) => {
                self.lesson = Some(lesson);
                state.scene_menu.open = false;
                state.scene_menu.error = None;
                state.intro = false;
                state.paused = true;
            }
            Err(e) => say_in_menu(state, e),
        }
    }
}

impl Page {
    /// One turn of the lesson with nobody at the page (`?drive=FPS`), as
    /// `lightcone lesson` takes it (`lesson::headless::turn`): nothing once
    /// the closing message is up or the lesson stopped; else the open
    /// question answered with the lesson's own answer; else board time
    /// moved 1/`fps` real seconds. Whether it did anything.
    fn drive(&mut self, state: &mut GameState, fps: f64) -> bool {
        let Some(lesson) = &mut self.lesson else {
            return false;
        };
        if !(lesson.running() || lesson.awaiting_light()) || lesson.ui().closing().is_some() {
            return false;
        }
        let open = lesson.ui().open_question().map(|q| q.lessons_own());
        match open {
            Some(i) => lesson.answer(state, i),
            None => {
                state.paused = false;
                state.step(1.0 / fps);
            }
        }
        true
    }
}

impl Host for Page {
    fn panels(
        &mut self,
        ui: &mut egui::Ui,
        state: &mut GameState,
        size: (u32, u32),
        actions: &mut Vec<UiAction>,
    ) -> SceneArea {
        let hud = Hud {
            tracker: None,
            tracker_colour: egui::Color32::GRAY,
            clocks: true,
            lesson: self.lesson.as_ref().map(|l| l.name().to_owned()),
            lessons: true,
            share: true,
        };
        let lesson = self.lesson.as_ref().map(|l| l as &dyn LessonStatus);
        panels::panels(ui, state, &hud, lesson, size, actions)
    }

    fn act(&mut self, action: UiAction, state: &mut GameState) {
        match action {
            UiAction::Share => share(state, self.lesson.as_ref()),
            UiAction::Open(Choice::Lesson(i)) => {
                if let Some((name, text)) = crate::assets::LESSONS.get(i) {
                    self.open_lesson(state, name, (*text).to_owned(), true);
                }
            }
            // A scene opened in the menu ends the lesson that ran.
            UiAction::SceneOpened => self.lesson = None,
            UiAction::ReloadLesson => {
                if let Some(lesson) = &mut self.lesson {
                    lesson.reload(state);
                }
            }
            UiAction::Answer(i) => {
                if let Some(lesson) = &mut self.lesson {
                    lesson.answer(state, i);
                }
            }
            // The CAVE's eye has nothing to act on in the page.
            _ => {}
        }
    }
}

/// Puts the link of what is open in the address bar and the clipboard,
/// and says so (the link is also `window.lightconeShareLink`, for the
/// browser test).
fn share(state: &mut GameState, lesson: Option<&WebLesson>) {
    let Some(page) = web_sys::window() else {
        return;
    };
    let Some(base) = page_address(&page) else {
        return;
    };
    let (link, what) = match (lesson, &state.source) {
        (Some(lesson), _) => (lesson.link(&base), "lesson"),
        (None, Some(source)) => (links::link(&base, source), "scene"),
        (None, None) => {
            state.message = "this scene was not opened from a file: nothing to share".to_owned();
            return;
        }
    };
    show_address(&page, &link);
    let _ =
        web_sys::js_sys::Reflect::set(&page, &"lightconeShareLink".into(), &link.as_str().into());
    let copied = if copy_text(&page, &link) {
        "copied, and in the address bar"
    } else {
        "in the address bar: copy it from there (this page has no clipboard: it is not served over https or from localhost)"
    };
    state.message = format!(
        "the link of this {what} ({} characters) is {copied}; it opens this {what} for whoever you send it to",
        link.len()
    );
}

/// The page's address without its query or fragment.
fn page_address(page: &web_sys::Window) -> Option<String> {
    let location = page.location();
    Some(format!(
        "{}{}",
        location.origin().ok()?,
        location.pathname().ok()?
    ))
}

/// Puts `url` in the address bar (no reload, no new history entry).
fn show_address(page: &web_sys::Window, url: &str) {
    if let Ok(history) = page.history() {
        let _ =
            history.replace_state_with_url(&web_sys::wasm_bindgen::JsValue::NULL, "", Some(url));
    }
}

/// Asks the browser to copy `text` to the clipboard; `false` when the page
/// has no clipboard (`navigator.clipboard` exists only on pages served
/// over https or from localhost). A refusal later (no permission) is
/// caught, not thrown into the game's frame.
fn copy_text(page: &web_sys::Window, text: &str) -> bool {
    use web_sys::js_sys::{Function, Promise, Reflect};
    use web_sys::wasm_bindgen::{JsCast, JsValue, closure::Closure};
    let navigator = page.navigator();
    let Ok(clipboard) = Reflect::get(&navigator, &"clipboard".into()) else {
        return false;
    };
    let write = Reflect::get(&clipboard, &"writeText".into())
        .ok()
        .and_then(|f| f.dyn_into::<Function>().ok());
    let Some(write) = write.filter(|_| clipboard.is_object()) else {
        return false;
    };
    match write.call1(&clipboard, &JsValue::from_str(text)) {
        Ok(promise) => {
            if let Ok(promise) = promise.dyn_into::<Promise>() {
                // A few bytes a share, kept for the page's life.
                let ignore = Closure::wrap(Box::new(|_: JsValue| {}) as Box<dyn FnMut(JsValue)>);
                let _ = promise.catch(&ignore);
                ignore.forget();
            }
            true
        }
        Err(_) => false,
    }
}

/// The game in the page's canvas.
struct WebApp {
    stage: Stage,
    page: Page,
    /// Frames drawn so far (the page's test waits for the first).
    frames: u64,
    /// Publish what the first picture shows (`window.lightconeSeen`) and
    /// where the frame's views, pucks and magnifier are
    /// (`window.lightconeLayout`) each frame: the page was opened at a
    /// board time (`?at=`), for the browser test's comparisons with
    /// `lightcone observe` and the window's screenshots.
    publish_seen: bool,
    /// The game (its generation) and scene the address bar names.
    addressed: (u64, Option<SceneSource>),
    /// The last stroke of the cue the page was told of.
    stroke: Option<crate::model::Stroke>,
    /// The page's time each of the last [`CPU_FRAMES`] frames took on its
    /// thread, ms (`window.lightconeFrameCpuMs` is their median).
    cpu_ms: std::collections::VecDeque<f64>,
    /// Asked for WebGPU (`?gpu=webgpu`). Not the default: its path starts
    /// (adapter, device, frames drawn at 60 fps on SwiftShader's WebGPU)
    /// but its pixels could not be looked at here (headless Chromium's
    /// screenshots miss a WebGPU canvas, even a five-line page's, and a
    /// copy of the frame mapped back aborts), and WebGL2's are checked
    /// against the window's by the browser test (docs/web.md).
    webgpu: bool,
    /// `?drive=FPS` ([`Address::drive`]).
    drive: Option<f64>,
}

/// Longest the page takes turns of a lesson played with nobody at it
/// between two looks at its own events, ms.
const DRIVE_MS: f64 = 12.0;

/// How many frames the page's frame-time median is over.
const CPU_FRAMES: usize = 64;

impl WebApp {
    /// Once another scene is open (from the menu, a dropped file), the
    /// address bar no longer names the one the page was opened with or
    /// shared: it names a shipped scene (`?scene=NAME`) or lesson
    /// (`?lesson=NAME`), else the bare page (a file's link is long:
    /// *share* makes it), so a reload never brings back a scene that was
    /// left.
    fn follow_address(&mut self) {
        let state = &self.stage.state;
        if state.generation == self.addressed.0 {
            return;
        }
        self.addressed.0 = state.generation;
        if state.source == self.addressed.1 {
            return;
        }
        self.addressed.1 = state.source.clone();
        let Some(page) = web_sys::window() else {
            return;
        };
        let Some(base) = page_address(&page) else {
            return;
        };
        // A lesson's game is the lesson's: the address names the lesson
        // (a shipped one), or keeps the link that carried it.
        let url = match (&self.page.lesson, &state.source) {
            (Some(lesson), _) if lesson.shipped() => lesson.link(&base),
            (Some(_), _) => return,
            (None, Some(shipped @ SceneSource::Shipped(_))) => links::link(&base, shipped),
            (None, _) => base,
        };
        show_address(&page, &url);
    }

    /// Opens the file dropped on the page since the last frame, if any;
    /// what cannot be opened is said in the scene menu.
    fn open_dropped(&mut self) {
        let Some((name, text)) = DROPPED.with(|d| d.borrow_mut().take()) else {
            return;
        };
        let state = &mut self.stage.state;
        let opened = match text {
            None => Err(format!(
                "{name}: larger than the {} MiB the page opens",
                MAX_DROPPED >> 20
            )),
            Some(text) => open_text(state, Kind::of_file(&name), &name, text),
        };
        match opened {
            Ok(Some((name, text, shipped))) => self.page.open_lesson(state, &name, text, shipped),
            // A scene opened: the lesson that ran ends, as from the menu.
            Ok(None) => self.page.lesson = None,
            Err(e) => say_in_menu(state, e),
        }
    }
}

impl window::Game for WebApp {
    fn title(&self) -> String {
        format!("Lightcone: {}", self.stage.state.scene.title)
    }

    fn webgpu(&self) -> bool {
        self.webgpu
    }

    fn ready(&mut self, gfx: &Gfx) -> Result<(), String> {
        self.stage.ready(gfx);
        gpu_chosen(&gfx.gpu.adapter);
        Ok(())
    }

    fn input(&mut self, gfx: &Gfx, event: &WindowEvent, consumed: bool) {
        self.stage.input(&mut self.page, gfx, event, consumed);
    }

    fn other_window(
        &mut self,
        _gfx: &Gfx,
        _id: WindowId,
        _event: &WindowEvent,
    ) -> Option<Result<Flow, String>> {
        None
    }

    fn woken(&mut self) {
        // A message from the lesson's worker: answered now, and with
        // nobody at the page (`?drive=`) the next turns taken at once, so
        // the lesson runs at the worker's pace, not the drawing's.
        match self.drive {
            Some(fps) => self.drive_turns(fps),
            None => {
                if let Some(lesson) = &mut self.page.lesson {
                    lesson.serve(&mut self.stage.state);
                }
            }
        }
    }

    fn frame(&mut self, gfx: &mut Gfx) -> Result<Flow, String> {
        let start = page_ms();
        self.open_dropped();
        self.follow_address();
        let (_, dt) = self.stage.tick();
        self.stage.fly_free(dt);
        let state = &mut self.stage.state;
        // As the window's lesson host: the worker's answers first, board
        // time waiting while a hook is out, then the lesson sees the step.
        if let Some(lesson) = &mut self.page.lesson {
            lesson.serve(state);
        }
        let before = state.live_time;
        // `?drive=` plays a lesson; without one (a scene opened from the
        // menu after it) time runs as usual.
        match self.drive {
            Some(fps) if self.page.lesson.is_some() => self.drive_turns(fps),
            _ => {
                if !self.page.lesson.as_ref().is_some_and(WebLesson::busy) {
                    state.step(dt);
                }
            }
        }
        let state = &mut self.stage.state;
        if let Some(lesson) = &mut self.page.lesson {
            lesson.after_step(state, before);
            lesson.watch_light(state);
            publish_lesson(lesson);
        }
        let state = &self.stage.state;
        if state.last_stroke != self.stroke {
            self.stroke = state.last_stroke;
            if let Some(stroke) = self.stroke {
                stroke_made(&state.scene.pucks[stroke.puck].name);
            }
        }
        if let Some(texture) = self.stage.draw(&mut self.page, gfx, false) {
            gfx.gpu.queue.present(texture);
            self.frames += 1;
            if self.frames == 1 {
                first_frame_drawn();
            }
        }
        if self.publish_seen {
            publish_seen(&self.stage.state);
            publish_layout(&self.stage, gfx);
        }
        self.frame_took(page_ms() - start);
        Ok(Flow::Continue)
    }
}

/// The page's clock, ms (`performance.now()`; NaN without one).
fn page_ms() -> f64 {
    web_sys::window()
        .and_then(|w| w.performance())
        .map_or(f64::NAN, |p| p.now())
}

impl WebApp {
    /// With nobody at the page (`?drive=FPS`): takes the lesson's turns
    /// (its hooks' ends, then the next question answered or board step,
    /// and the hooks that raised) while none is out in the worker, for at
    /// most [`DRIVE_MS`] of the page's time, so that a lesson whose frames
    /// call no hook is not held to the page's frame rate either.
    fn drive_turns(&mut self, fps: f64) {
        let until = page_ms() + DRIVE_MS;
        let state = &mut self.stage.state;
        loop {
            let Some(lesson) = &mut self.page.lesson else {
                return;
            };
            lesson.serve(state);
            if lesson.busy() {
                return;
            }
            let before = state.live_time;
            if !self.page.drive(state, fps) {
                return;
            }
            if let Some(lesson) = &mut self.page.lesson {
                lesson.after_step(state, before);
                lesson.watch_light(state);
            }
            // (A page without a clock, NaN, takes one turn.)
            if page_ms() >= until || until.is_nan() {
                return;
            }
        }
    }

    /// Keeps the time one frame took on the page's thread (`ms`: the game's
    /// work and its WebGL calls, not the browser's compositing) and
    /// publishes the median of the last [`CPU_FRAMES`] as
    /// `window.lightconeFrameCpuMs` (and the frames drawn as
    /// `window.lightconeFrames`).
    fn frame_took(&mut self, ms: f64) {
        if self.cpu_ms.len() == CPU_FRAMES {
            self.cpu_ms.pop_front();
        }
        self.cpu_ms.push_back(ms);
        let mut sorted: Vec<f64> = self.cpu_ms.iter().copied().collect();
        sorted.sort_by(f64::total_cmp);
        let median = sorted[sorted.len() / 2];
        if let Some(page) = web_sys::window() {
            let key = "lightconeFrameCpuMs".into();
            let _ = web_sys::js_sys::Reflect::set(&page, &key, &median.into());
            let frames = self.frames as f64;
            let _ = web_sys::js_sys::Reflect::set(&page, &"lightconeFrames".into(), &frames.into());
        }
    }
}

/// Puts on the page, as `window.lightconeSeen`, what the first picture
/// shows of each puck this frame: a JSON array of `{"name", "t",
/// "position": [x, y, z]}`, the emission event of its centre (board
/// frame, s and m), which `lightcone observe` reports as `emission`.
fn publish_seen(state: &GameState) {
    let Some(view) = state.pane_list().first().and_then(|&p| state.view_of(p)) else {
        return;
    };
    let seen: Vec<serde_json::Value> = state
        .centres(view)
        .iter()
        .map(|c| {
            let e = c.emission.event;
            serde_json::json!({
                "name": state.scene.pucks[c.puck].name,
                "t": e.t,
                "position": [e.position.x, e.position.y, e.position.z],
            })
        })
        .collect();
    if let Some(page) = web_sys::window() {
        let text = serde_json::Value::Array(seen).to_string();
        let _ = web_sys::js_sys::Reflect::set(&page, &"lightconeSeen".into(), &text.into());
    }
}

/// Puts on the page, as `window.lightconeLayout`, where this frame's
/// views, pucks, labels and magnifier are: the JSON of `play
/// --screenshot`'s sidecar ([`super::sidecar::layout`]; no diagram), in
/// the canvas's pixels, so that the browser test measures the page's
/// picture as `tests/view.rs` measures the window's.
fn publish_layout(stage: &Stage, gfx: &Gfx) {
    let (w, h) = gfx.size();
    let drawn = super::overlay::drawn(gfx.egui_context());
    let layout =
        super::sidecar::layout(&stage.state, stage.area, None, (w as f32, h as f32), &drawn);
    if let Some(page) = web_sys::window() {
        let _ = web_sys::js_sys::Reflect::set(
            &page,
            &"lightconeLayout".into(),
            &layout.to_string().into(),
        );
    }
}

/// Notes on the page that the cue struck `puck`: `window.lightconeStrokes`
/// counts the strokes and `window.lightconeStruck` names the last puck
/// struck (for the browser test of the pointer and touch cue).
fn stroke_made(puck: &str) {
    let Some(page) = web_sys::window() else {
        return;
    };
    let key = "lightconeStrokes".into();
    let n = web_sys::js_sys::Reflect::get(&page, &key)
        .ok()
        .and_then(|v| v.as_f64())
        .unwrap_or(0.0);
    let _ = web_sys::js_sys::Reflect::set(&page, &key, &(n + 1.0).into());
    let _ = web_sys::js_sys::Reflect::set(&page, &"lightconeStruck".into(), &puck.into());
}

/// Notes on the page which GPU the game draws with: the adapter's name and
/// backend (`BrowserWebGpu` or `Gl`) become `window.lightconeAdapter`, and
/// are logged to the console.
fn gpu_chosen(adapter: &str) {
    let Some(page) = web_sys::window() else {
        return;
    };
    let _ = web_sys::js_sys::Reflect::set(&page, &"lightconeAdapter".into(), &adapter.into());
    web_sys::console::log_1(&format!("lightcone: drawing with {adapter}").into());
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

/// Puts on the page, as `window.lightconeLessonState`, what the lesson has
/// shown so far: a JSON object `{"name", "claims": [{"claim", "ok",
/// "detail"}], "finished", "error", "text"}` (the claims as `lightcone
/// lesson --json` prints them), for the browser test's comparison with
/// the desktop.
fn publish_lesson(lesson: &WebLesson) {
    let ui = lesson.ui();
    let claims: Vec<serde_json::Value> = ui
        .claims
        .iter()
        .map(|c| serde_json::json!({"claim": c.claim, "ok": c.ok, "detail": c.detail}))
        .collect();
    let state = serde_json::json!({
        "name": lesson.name(),
        "claims": claims,
        "finished": ui.finished,
        "closing": ui.closing(),
        "error": lesson.error,
        "text": ui.text,
        "question": ui.question.as_ref().map(|q| &q.text),
    });
    if let Some(page) = web_sys::window() {
        let text = state.to_string();
        let _ = web_sys::js_sys::Reflect::set(&page, &"lightconeLessonState".into(), &text.into());
    }
}
