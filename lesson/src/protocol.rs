//! The lesson protocol's game side, without Python: a lesson run
//! elsewhere (its own process on the desktop, a Web Worker in the
//! browser) holds a stand-in `World` (`game/src/lesson/remote.py`) whose
//! methods are requests; the game answers each with [`answer`] on its
//! [`WorldCall`], as JSON.
//!
//! Values travel as JSON: records as `{"$record": class, "data": {...}}`,
//! scenes as `{"$scene": json}` (rebuilt through every check of a scene
//! built in code when received), frames as `{"$frame": [png_base64,
//! width, height, t]}`. A reply is `{"ok": value, "snapshot": {...}}` or
//! `{"error": [kind, message], "snapshot": {...}}`, `kind` the Python
//! exception's name; the snapshot (t, c, paused, time_scale, view,
//! observer, effects, or `{"$none": why}` without a game) answers the
//! common getters without a round trip.

use base64::Engine as _;
use lightcone_engine::scene::{Effect, Scene};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value, json};

use crate::LessonGame;
use crate::args::{Arg, Bound, Vector, type_error};
use crate::error::{ErrorKind, WorldError, WorldResult};
use crate::world::{NO_GAME, WorldCall};

/// Longest a single hook may run: past it the hook gets a `TimeoutError`
/// at its line (a lesson's process and a browser's worker alike).
pub const HOOK_LIMIT: std::time::Duration = std::time::Duration::from_secs(10);

/// How long after its limit a hook that did not stop (a long call into C,
/// which never returns to Python) has its process or worker ended.
pub const HOOK_GRACE: std::time::Duration = std::time::Duration::from_millis(800);

/// Longest line either side accepts from the other, bytes.
pub const MAX_LINE: usize = 16 << 20;

/// How many of its newest printed lines the lesson's panel keeps.
pub const PRINTED_LINES: usize = 40;

/// Longest printed line the panel keeps, bytes (cut past it).
pub const PRINTED_LINE_BYTES: usize = 4096;

/// The lines a hook printed, as the panel keeps them: the newest
/// [`PRINTED_LINES`], each cut to [`PRINTED_LINE_BYTES`].
#[must_use]
pub fn printed_tail(lines: Vec<String>) -> Vec<String> {
    let skip = lines.len().saturating_sub(PRINTED_LINES);
    lines
        .into_iter()
        .skip(skip)
        .map(|l| crate::cut(&l, PRINTED_LINE_BYTES))
        .collect()
}

/// The world's methods a lesson may request (`remote.py`'s `METHODS`).
pub const METHODS: [&str; 17] = [
    "start",
    "pause",
    "resume",
    "set_effect",
    "state",
    "collisions",
    "velocity",
    "impulse",
    "observe",
    "show_diagram",
    "simultaneity",
    "say",
    "ask",
    "check",
    "bars",
    "finish",
    "diagram",
];

/// The read-only attributes served (`remote.py`'s `GETTERS`).
pub const GETTERS: [&str; 3] = ["claims", "scene", "finished"];

/// The attributes a lesson may set, each requested as `=name`
/// (`remote.py`'s `SETTABLE`).
pub const SETTABLE: [&str; 4] = ["paused", "time_scale", "view", "observer"];

/// What a lesson's side writes, one JSON object a line
/// (`{"request": {...}}` or `{"done": {...}}`).
#[derive(Debug, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Up {
    /// A `World` method, getter or setter (`=name`) for the game to run.
    Request {
        /// What is asked (see [`serves`]).
        op: String,
        /// Its positional arguments, encoded.
        args: Vec<Value>,
        /// Its keyword arguments, encoded.
        kwargs: Map<String, Value>,
    },
    /// The hook returned (`error: None`) or raised (its traceback).
    Done {
        /// The traceback, if the hook raised.
        error: Option<String>,
        /// The lesson's watchdog stopped the hook at its limit.
        timed_out: bool,
        /// What the lesson printed during the hook.
        printed: Vec<String>,
        /// The hooks the lesson defines (sent after `setup`).
        hooks: Vec<String>,
    },
}

/// Whether the game serves request `op` (one of [`METHODS`], [`GETTERS`],
/// or `=` and one of [`SETTABLE`]): a lesson that asks for anything else
/// is stopped.
#[must_use]
pub fn serves(op: &str) -> bool {
    match op.strip_prefix('=') {
        Some(name) => SETTABLE.contains(&name),
        None => METHODS.contains(&op) || GETTERS.contains(&op),
    }
}

/// The world's simple attributes, sent with every call and answer.
#[derive(Serialize)]
pub struct Snapshot<'a> {
    t: f64,
    c: f64,
    paused: bool,
    time_scale: f64,
    view: &'static str,
    observer: Option<&'a str>,
    effects: Effects,
}

/// The effects as a map from their keys to whether each is on.
struct Effects(lightcone_engine::scene::Effects);

impl Serialize for Effects {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_map(Effect::ALL.iter().map(|e| (e.key(), self.0.is_on(*e))))
    }
}

/// The snapshot of `game` (the same keys and values as the `World`
/// getters).
#[must_use]
pub fn snapshot(game: &dyn LessonGame) -> Snapshot<'_> {
    Snapshot {
        t: game.live_time(),
        c: game.scene().c,
        paused: game.paused(),
        time_scale: game.time_scale(),
        view: game.pictures().name(),
        observer: game
            .observer()
            .and_then(|i| game.scene().observers.get(i))
            .map(|o| o.name.as_str()),
        effects: Effects(game.effects()),
    }
}

/// The snapshot of `world`'s game, or why it has none, as JSON.
#[must_use]
pub fn snapshot_value(world: &WorldCall<'_>) -> Value {
    match world.game() {
        Ok(g) => serde_json::to_value(snapshot(g)).unwrap_or(Value::Null),
        Err(_) => no_snapshot(),
    }
}

/// The snapshot where there is no game (a call of `setup`): why.
fn no_snapshot() -> Value {
    json!({ "$none": NO_GAME })
}

/// A call line: `{"call": hook, "args": [...], "snapshot": {...}}`.
#[derive(Serialize)]
pub struct Call<'a, S: Serialize> {
    /// The hook to run.
    pub call: &'a str,
    /// Its arguments after the world.
    pub args: &'a Value,
    /// The world's snapshot as the hook starts ([`Snapshot`], or a
    /// [`snapshot_value`]).
    pub snapshot: S,
}

/// The line that runs `hook(world, *args)` in the lesson, its snapshot
/// taken of `game` (`None` for `setup`: there is no game yet, and the
/// snapshot says why).
#[must_use]
pub fn call_line(game: Option<&dyn LessonGame>, hook: &str, args: &Value) -> String {
    let line = match game {
        Some(g) => serde_json::to_string(&Call {
            call: hook,
            args,
            snapshot: snapshot(g),
        }),
        None => serde_json::to_string(&Call {
            call: hook,
            args,
            snapshot: no_snapshot(),
        }),
    };
    line.unwrap_or_default()
}

/// The reply line to request `op` with `args` and `kwargs`, run on `world`
/// (`op` one that [`serves`]).
pub fn reply_line(
    world: &mut WorldCall<'_>,
    op: &str,
    args: &[Value],
    kwargs: &Map<String, Value>,
) -> String {
    let mut reply = Map::new();
    match answer(world, op, args, kwargs) {
        Ok(v) => reply.insert("ok".to_owned(), v),
        Err(e) => reply.insert("error".to_owned(), json!([e.kind.name(), e.message])),
    };
    reply.insert("snapshot".to_owned(), snapshot_value(world));
    Value::Object(reply).to_string()
}

/// A scene sent as JSON (`Scene._to_json`), rebuilt through every check of
/// a scene built in code.
pub fn scene_from_json(text: &str) -> WorldResult<Scene> {
    let raw: Scene = serde_json::from_str(text)
        .map_err(|e| WorldError::new(ErrorKind::Scene, format!("a scene sent as JSON: {e}")))?;
    raw.rebuilt()
        .map_err(|e| WorldError::from(e.of("a scene sent as JSON")))
}

pub(crate) fn record<T: Serialize>(class: &str, value: &T) -> WorldResult<Value> {
    let data = serde_json::to_value(value).map_err(|e| WorldError::value(e.to_string()))?;
    Ok(json!({ "$record": class, "data": data }))
}

/// Runs request `op` on `world`: its result as JSON, or why it refused.
pub fn answer(
    world: &mut WorldCall<'_>,
    op: &str,
    args: &[Value],
    kwargs: &Map<String, Value>,
) -> WorldResult<Value> {
    if let Some(name) = op.strip_prefix('=') {
        let [value] = args else {
            return Err(type_error(format!("world.{name} = takes one value")));
        };
        if !kwargs.is_empty() {
            return Err(type_error(format!("world.{name} = takes one value")));
        }
        let arg = Arg { name, value };
        match name {
            "paused" => world.set_paused(arg.get()?)?,
            "time_scale" => world.set_time_scale(arg.get()?)?,
            "view" => world.set_view(&arg.get::<String>()?)?,
            "observer" => world.set_observer(arg.get::<Option<String>>()?.as_deref())?,
            _ => return Err(unknown(op)),
        }
        return Ok(Value::Null);
    }
    let none = Value::Null;
    let b = |params: &'static [&'static str]| Bound::new("World", op, params, args, kwargs);
    Ok(match op {
        "start" => {
            let a = b(&["scene"])?;
            let scene = match a.value(0) {
                Some(Value::Object(m)) if m.len() == 1 => match m.get("$scene") {
                    Some(Value::String(text)) => scene_from_json(text)?,
                    _ => return Err(a.wrong(0, "a lightcone.Scene")),
                },
                Some(_) => return Err(a.wrong(0, "a lightcone.Scene")),
                None => return Err(a.missing(0)),
            };
            world.start(scene)?;
            none
        }
        "pause" => {
            b(&[])?;
            world.set_paused(true)?;
            none
        }
        "resume" => {
            b(&[])?;
            world.set_paused(false)?;
            none
        }
        "set_effect" => {
            let a = b(&["name", "on"])?;
            world.set_effect(&a.req::<String>(0)?, a.req(1)?)?;
            none
        }
        "state" => {
            b(&[])?;
            record("State", &world.state()?)?
        }
        "collisions" => {
            b(&[])?;
            let all = world.collisions()?;
            let records: WorldResult<Vec<Value>> =
                all.iter().map(|c| record("Collision", c)).collect();
            Value::Array(records?)
        }
        "velocity" => {
            let a = b(&["name"])?;
            let (x, y) = world.velocity(&a.req::<String>(0)?)?;
            json!([x, y])
        }
        "impulse" => {
            let a = b(&["name", "du"])?;
            let [x, y] = a.req::<Vector<2>>(1)?.0;
            world.impulse(&a.req::<String>(0)?, (x, y))?;
            none
        }
        "observe" => {
            let a = b(&["observer", "t", "vertices", "effects", "at"])?;
            let report = world.observe(
                a.opt::<String>(0)?.as_deref(),
                a.opt(1)?,
                a.opt(2)?.unwrap_or(false),
                a.opt(3)?,
                a.opt(4)?,
            )?;
            record("Observation", &report)?
        }
        "diagram" => {
            let a = b(&["path", "observer", "size", "at", "axis", "frame"])?;
            // The lesson's side saves the frame (in its own sandbox): the
            // game writes no file a lesson names.
            if a.opt::<Value>(0)?.is_some() {
                return Err(WorldError::value(
                    "world.diagram: the path is saved by the lesson's side, not sent to the game",
                ));
            }
            let (image, t) = world.diagram(
                a.opt::<String>(1)?.as_deref(),
                pixels(&a, 2, (1000, 700))?,
                a.opt(3)?,
                &a.opt::<String>(4)?.unwrap_or_else(|| "x".to_owned()),
                a.opt::<String>(5)?.as_deref(),
            )?;
            frame(&image, t, None)?
        }
        "show_diagram" => {
            let a = b(&["on", "frame", "axis"])?;
            world.show_diagram(
                a.opt(0)?.unwrap_or(true),
                a.opt::<String>(1)?.as_deref(),
                &a.opt::<String>(2)?.unwrap_or_else(|| "x".to_owned()),
            )?;
            none
        }
        "simultaneity" => {
            let a = b(&["frame", "at"])?;
            let line = world.simultaneity(&a.req::<String>(0)?, a.opt(1)?)?;
            serde_json::to_value(line).map_err(|e| WorldError::value(e.to_string()))?
        }
        "say" => {
            let a = b(&["text", "append"])?;
            world.say(&a.req::<String>(0)?, a.opt(1)?.unwrap_or(false))?;
            none
        }
        "ask" => {
            let a = b(&["question", "choices", "answer"])?;
            world.ask(&a.req::<String>(0)?, a.req(1)?, a.opt(2)?)?;
            none
        }
        "check" => {
            let a = b(&["claim", "ok", "detail"])?;
            let claim = world.check(
                &a.req::<String>(0)?,
                a.req(1)?,
                &a.opt::<String>(2)?.unwrap_or_default(),
            )?;
            Value::Bool(claim.ok)
        }
        "bars" => {
            let a = b(&["title", "edges", "counts", "expected"])?;
            world.bars(&a.req::<String>(0)?, a.req(1)?, a.req(2)?, a.opt(3)?)?;
            none
        }
        "finish" => {
            let a = b(&["message", "after_light_from"])?;
            let light = a.opt::<Vector<3>>(1)?.map(|v| (v.0[0], v.0[1], v.0[2]));
            world.finish(&a.opt::<String>(0)?.unwrap_or_default(), light)?;
            none
        }
        "claims" => {
            b(&[])?;
            Value::Array(
                world
                    .claims()
                    .into_iter()
                    .map(|(c, ok, d)| json!([c, ok, d]))
                    .collect(),
            )
        }
        "scene" => {
            b(&[])?;
            let scene = world.game()?.scene();
            let text =
                serde_json::to_string(scene).map_err(|e| WorldError::value(e.to_string()))?;
            json!({ "$scene": text })
        }
        "finished" => {
            b(&[])?;
            Value::Bool(world.finished())
        }
        _ => return Err(unknown(op)),
    })
}

/// Argument `i` of `a` as a size in pixels (two whole numbers, as
/// Python's `(u32, u32)`), `default` when not given.
pub(crate) fn pixels(a: &Bound<'_>, i: usize, default: (u32, u32)) -> WorldResult<(u32, u32)> {
    let Some(v) = a.opt::<Vector<2>>(i)? else {
        return Ok(default);
    };
    let whole = |x: f64| x.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&x);
    if !v.0.iter().all(|x| whole(*x)) {
        return Err(a.wrong(i, "two whole numbers of pixels"));
    }
    // Whole and in range: exact.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    Ok((v.0[0] as u32, v.0[1] as u32))
}

/// An image as a frame value (`{"$frame": [png_base64, width, height,
/// t]}`), also written as a PNG file at `path` if given.
pub(crate) fn frame(
    image: &lightcone_render::headless::Image,
    t: f64,
    path: Option<&std::path::Path>,
) -> WorldResult<Value> {
    let png = image.png_bytes().map_err(WorldError::value)?;
    if let Some(path) = path {
        std::fs::write(path, &png)
            .map_err(|e| WorldError::value(format!("{}: {e}", path.display())))?;
    }
    let text = base64::engine::general_purpose::STANDARD.encode(&png);
    Ok(json!({ "$frame": [text, image.width, image.height, t] }))
}

fn unknown(op: &str) -> WorldError {
    WorldError::new(
        ErrorKind::Runtime,
        format!("the game does not serve {op:?}"),
    )
}
