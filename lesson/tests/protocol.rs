//! The lesson protocol's game side and the browser's stand-ins, without
//! Python: requests bound as Python binds a call, refusals of the right
//! kind, and the stand-ins' scenes and simulations equal to the engine's
//! own.

use lightcone_engine::physics::Billiard;
use lightcone_engine::scene::{Effects, Scene};
use lightcone_lesson::protocol::{self, answer, reply_line};
use lightcone_lesson::standin::Objects;
use lightcone_lesson::{ErrorKind, LessonGame, Pictures, WorldCall, WorldCore};
use serde_json::{Map, Value, json};

/// A game as small as the trait allows: a scene, its board, a view.
struct Board {
    scene: Scene,
    billiard: Billiard,
    paused: bool,
    scale: f64,
    pictures: Pictures,
    observer: Option<usize>,
    effects: Effects,
}

impl LessonGame for Board {
    fn scene(&self) -> &Scene {
        &self.scene
    }
    fn billiard(&self) -> &Billiard {
        &self.billiard
    }
    fn billiard_mut(&mut self) -> &mut Billiard {
        &mut self.billiard
    }
    fn live_time(&self) -> f64 {
        self.billiard.time()
    }
    fn paused(&self) -> bool {
        self.paused
    }
    fn set_paused(&mut self, paused: bool) {
        self.paused = paused;
    }
    fn time_scale(&self) -> f64 {
        self.scale
    }
    fn set_time_scale(&mut self, scale: f64) {
        self.scale = scale;
    }
    fn pictures(&self) -> Pictures {
        self.pictures
    }
    fn set_pictures(&mut self, pictures: Pictures) {
        self.pictures = pictures;
    }
    fn observer(&self) -> Option<usize> {
        self.observer
    }
    fn set_observer(&mut self, observer: Option<usize>) {
        self.observer = observer;
    }
    fn effects(&self) -> Effects {
        self.effects
    }
    fn effects_mut(&mut self) -> &mut Effects {
        &mut self.effects
    }
    fn set_diagram(&mut self, _: bool, _: Option<usize>, _: lightcone_render::diagram::Axis) {}
    fn restart(&mut self, scene: Scene) {
        *self = new_board(scene);
    }
}

fn new_board(scene: Scene) -> Board {
    let billiard = Billiard::from_scene(&scene);
    let effects = scene.effects;
    Board {
        scene,
        billiard,
        paused: false,
        scale: 1.0,
        pictures: Pictures::Seen,
        observer: None,
        effects,
    }
}

/// A lesson's world and the game its host holds.
struct Host {
    core: WorldCore,
    board: Board,
}

impl Host {
    /// The world for one call on the host's game.
    fn call(&mut self) -> WorldCall<'_> {
        self.core.on(Some(&mut self.board))
    }
}

/// Two pucks, the first moving at u = 0.9 toward the second.
fn two_pucks() -> Scene {
    let text = r#"
title = "two"
[table]
size = [2.84, 1.42]
friction = 0.0
[[puck]]
name = "a"
position = [0.5, 0.71]
u = [0.9, 0.0]
[[puck]]
name = "b"
position = [1.5, 0.72]
[[observer]]
name = "eye"
position = [1.42, -1.5, 1.2]
"#;
    lightcone_engine::scene::parse(text, "two.toml").unwrap()
}

/// A host whose lesson has started the two pucks (on an empty board).
fn world() -> Host {
    let empty = Scene::empty(glam::DVec2::new(1.0, 1.0), None).unwrap();
    let mut host = Host {
        core: WorldCore::new(".".into()),
        board: new_board(empty),
    };
    host.call().start(two_pucks()).unwrap();
    host
}

fn ask(
    w: &mut WorldCall<'_>,
    op: &str,
    args: Value,
    kwargs: Value,
) -> Result<Value, (ErrorKind, String)> {
    let args = args.as_array().cloned().unwrap_or_default();
    let kwargs: Map<String, Value> = kwargs.as_object().cloned().unwrap_or_default();
    answer(w, op, &args, &kwargs).map_err(|e| (e.kind, e.message))
}

#[test]
fn requests_bind_their_arguments_as_python_binds_a_call() {
    let mut host = world();
    let mut w = host.call();
    // Positional, keyword, and both mixed: the same call.
    assert_eq!(
        ask(&mut w, "velocity", json!(["a"]), json!({})).unwrap(),
        json!([0.9, 0.0])
    );
    assert_eq!(
        ask(&mut w, "velocity", json!([]), json!({"name": "a"})).unwrap(),
        json!([0.9, 0.0])
    );
    ask(&mut w, "say", json!(["one"]), json!({})).unwrap();
    ask(&mut w, "say", json!(["two"]), json!({"append": true})).unwrap();
    assert_eq!(w.ui.text, "one\ntwo");
    // Python's TypeErrors, in Python's words.
    let (kind, message) = ask(&mut w, "velocity", json!([]), json!({})).unwrap_err();
    assert_eq!(kind, ErrorKind::Type);
    assert_eq!(
        message,
        "World.velocity() missing 1 required positional argument: 'name'"
    );
    let (kind, message) = ask(&mut w, "say", json!(["x"]), json!({"loud": true})).unwrap_err();
    assert_eq!(
        (kind, message.as_str()),
        (
            ErrorKind::Type,
            "World.say() got an unexpected keyword argument 'loud'"
        )
    );
    let (kind, _) = ask(&mut w, "say", json!(["x"]), json!({"text": "y"})).unwrap_err();
    assert_eq!(kind, ErrorKind::Type);
    let (kind, _) = ask(&mut w, "impulse", json!(["a", [1.0]]), json!({})).unwrap_err();
    assert_eq!(kind, ErrorKind::Type);
    // The world's own refusals keep their kind.
    let (kind, _) = ask(&mut w, "velocity", json!(["nobody"]), json!({})).unwrap_err();
    assert_eq!(kind, ErrorKind::Key);
    let (kind, _) = ask(&mut w, "=time_scale", json!([0.0]), json!({})).unwrap_err();
    assert_eq!(kind, ErrorKind::Value);
    let (kind, _) = ask(&mut w, "observe", json!([]), json!({"at": 5.0})).unwrap_err();
    assert_eq!(kind, ErrorKind::NotComputed);
    let (kind, _) = ask(&mut w, "ask", json!(["?", ["yes"], 3]), json!({})).unwrap_err();
    assert_eq!(kind, ErrorKind::Value);
}

#[test]
fn a_request_changes_the_game_it_is_answered_on() {
    let mut host = world();
    let mut w = host.call();
    ask(&mut w, "impulse", json!(["b", [0.0, 0.5]]), json!({})).unwrap();
    assert_eq!(
        ask(&mut w, "velocity", json!(["b"]), json!({})).unwrap(),
        json!([0.0, 0.5])
    );
    ask(&mut w, "=view", json!(["split"]), json!({})).unwrap();
    ask(&mut w, "=observer", json!(["eye"]), json!({})).unwrap();
    ask(&mut w, "set_effect", json!(["doppler", false]), json!({})).unwrap();
    let g = w.game().unwrap();
    assert_eq!((g.pictures(), g.observer()), (Pictures::Split, Some(0)));
    let snapshot = protocol::snapshot_value(&w);
    assert_eq!(snapshot["view"], json!("split"));
    assert_eq!(snapshot["observer"], json!("eye"));
    assert_eq!(snapshot["effects"]["doppler"], json!(false));
    // A question pauses the game, and promises to resume it.
    ask(
        &mut w,
        "ask",
        json!(["which?", ["x", "y"]]),
        json!({"answer": 1}),
    )
    .unwrap();
    assert!(w.game().unwrap().paused());
    assert!(
        w.ui.question
            .as_ref()
            .is_some_and(|q| q.resume && q.answer == Some(1))
    );
    assert_eq!(
        ask(&mut w, "check", json!(["holds", true, "1 = 1"]), json!({})).unwrap(),
        json!(true)
    );
    assert_eq!(
        ask(&mut w, "claims", json!([]), json!({})).unwrap(),
        json!([["holds", true, "1 = 1"]])
    );
    ask(
        &mut w,
        "finish",
        json!([]),
        json!({"message": "done", "after_light_from": [0.0, 1.0, 0.7]}),
    )
    .unwrap();
    assert_eq!(
        ask(&mut w, "finished", json!([]), json!({})).unwrap(),
        json!(true)
    );
    assert!(w.ui.finish_light.is_some() && w.ui.closing().is_none());
}

#[test]
fn records_and_scenes_travel_tagged() {
    let mut host = world();
    let mut w = host.call();
    let state = ask(&mut w, "state", json!([]), json!({})).unwrap();
    assert_eq!(state["$record"], json!("State"));
    assert_eq!(state["data"]["pucks"].as_array().map(Vec::len), Some(2));
    let seen = ask(&mut w, "observe", json!([]), json!({"vertices": false})).unwrap();
    assert_eq!(seen["$record"], json!("Observation"));
    let scene = ask(&mut w, "scene", json!([]), json!({})).unwrap();
    let text = scene["$scene"].as_str().unwrap();
    // Sent back, it starts a game on the same scene (rebuilt, checked).
    ask(&mut w, "start", json!([{"$scene": text}]), json!({})).unwrap();
    assert_eq!(w.generation, 2);
    assert_eq!(w.game().unwrap().scene(), &two_pucks());
    // A scene that breaks a rule is refused by the rule's kind.
    let mut bad: Value = serde_json::from_str(text).unwrap();
    bad["pucks"][0]["radius"] = json!(-1.0);
    let (kind, _) = ask(
        &mut w,
        "start",
        json!([{"$scene": bad.to_string()}]),
        json!({}),
    )
    .unwrap_err();
    assert!(
        matches!(kind, ErrorKind::OutOfRange | ErrorKind::Scene),
        "{kind:?}"
    );
    let frame = ask(&mut w, "diagram", json!([]), json!({"size": [200, 150]})).unwrap();
    assert_eq!(frame["$frame"][1], json!(200));
    assert_eq!(frame["$frame"][2], json!(150));
}

#[test]
fn without_a_game_every_answer_says_why_and_the_snapshot_too() {
    let mut core = WorldCore::new(".".into());
    let mut w = core.on(None);
    let reply: Value =
        serde_json::from_str(&reply_line(&mut w, "state", &[], &Map::new())).unwrap();
    assert_eq!(reply["error"][0], json!("RuntimeError"));
    assert_eq!(reply["snapshot"]["$none"], json!(lightcone_lesson::NO_GAME));
    // say() needs no game.
    let reply: Value =
        serde_json::from_str(&reply_line(&mut w, "say", &[json!("hi")], &Map::new())).unwrap();
    assert_eq!(reply["ok"], Value::Null);
}

fn call(objects: &mut Objects, request: Value) -> Value {
    serde_json::from_str(&objects.call(&request.to_string())).unwrap()
}

#[test]
fn the_standin_scene_is_the_engines_scene_built_in_code() {
    let mut o = Objects::default();
    let made = call(
        &mut o,
        json!({"class": "Scene", "op": "new", "args": [], "kwargs": {"title": "two"}}),
    );
    let mut state = made["state"].clone();
    for (name, position, u) in [
        ("a", [0.5, 0.71], Some([0.9, 0.0])),
        ("b", [1.5, 0.72], None),
    ] {
        let mut kwargs = json!({});
        if let Some(u) = u {
            kwargs["u"] = json!(u);
        }
        let r = call(
            &mut o,
            json!({"class": "Scene", "op": "add_puck", "state": state, "args": [name, position], "kwargs": kwargs}),
        );
        assert_eq!(r["ok"], Value::Null, "{r}");
        state = r["state"].clone();
    }
    let r = call(
        &mut o,
        json!({"class": "Scene", "op": "add_observer", "state": state, "args": ["eye", [1.42, -1.5, 1.2]]}),
    );
    state = r["state"].clone();
    let built: Scene = serde_json::from_str(state.as_str().unwrap()).unwrap();
    assert_eq!(built, two_pucks());
    let pucks = call(
        &mut o,
        json!({"class": "Scene", "op": "pucks", "state": state}),
    );
    assert_eq!(pucks["ok"], json!(["a", "b"]));
    // Faster than light: the rule's own kind.
    let r = call(
        &mut o,
        json!({"class": "Scene", "op": "add_puck", "state": state, "args": ["c", [2.0, 0.7]], "kwargs": {"beta": [1.2, 0.0]}}),
    );
    assert_eq!(r["error"][0], json!("SpeedOfLightError"), "{r}");
    // c kept as momentum: γv in m/s unchanged under a new c.
    let r = call(
        &mut o,
        json!({"class": "Scene", "op": "=c", "state": state, "args": [1e6]}),
    );
    let fast: Scene = serde_json::from_str(r["state"].as_str().unwrap()).unwrap();
    let v = |s: &Scene| s.pucks[0].u.0.x * s.c;
    assert!((v(&fast) - v(&two_pucks())).abs() < 1e-9 * v(&two_pucks()));
}

#[test]
fn the_standin_simulation_runs_the_engines_board() {
    let mut o = Objects::default();
    let text = serde_json::to_string(&two_pucks()).unwrap();
    let id = call(
        &mut o,
        json!({"class": "Simulation", "op": "new", "args": [text]}),
    )["ok"]
        .clone();
    call(
        &mut o,
        json!({"class": "Simulation", "op": "run_until", "id": id, "args": [3.0]}),
    );
    let theirs = call(
        &mut o,
        json!({"class": "Simulation", "op": "collisions", "id": id}),
    )["ok"]
        .clone();
    let mut billiard = Billiard::from_scene(&two_pucks());
    billiard.advance_to(3.0);
    billiard.forget_old_records();
    let ours: Vec<Value> = billiard
        .collisions()
        .iter()
        .map(|c| {
            let data =
                serde_json::to_value(lightcone_engine::report::CollisionLine::new(&billiard, c))
                    .unwrap();
            json!({"$record": "Collision", "data": data})
        })
        .collect();
    assert!(!ours.is_empty());
    assert_eq!(theirs, Value::Array(ours));
    let t = call(
        &mut o,
        json!({"class": "Simulation", "op": "time", "id": id}),
    );
    assert_eq!(t["ok"], json!(3.0));
    call(
        &mut o,
        json!({"class": "Simulation", "op": "drop", "id": id}),
    );
    let gone = call(
        &mut o,
        json!({"class": "Simulation", "op": "time", "id": id}),
    );
    assert_eq!(gone["error"][0], json!("RuntimeError"));
    // A flood of simulations is refused past the bound.
    for _ in 0..lightcone_lesson::standin::MAX_SIMULATIONS {
        call(
            &mut o,
            json!({"class": "Simulation", "op": "new", "args": [text]}),
        );
    }
    let r = call(
        &mut o,
        json!({"class": "Simulation", "op": "new", "args": [text]}),
    );
    assert_eq!(r["error"][0], json!("RuntimeError"));
}

#[test]
fn what_a_lesson_may_put_on_screen_is_bounded() {
    let mut host = world();
    let mut w = host.call();
    let big = "y".repeat(lightcone_lesson::MAX_TEXT_BYTES + 1);
    let (kind, _) = ask(&mut w, "say", json!([big]), json!({})).unwrap_err();
    assert_eq!(kind, ErrorKind::Value);
    // Appended lines count in all: the last that would pass is refused.
    let half = "z".repeat(lightcone_lesson::MAX_TEXT_BYTES / 2);
    ask(&mut w, "say", json!([half]), json!({})).unwrap();
    let (kind, _) = ask(&mut w, "say", json!([half]), json!({"append": true})).unwrap_err();
    assert_eq!(kind, ErrorKind::Value);
    assert_eq!(w.ui.text.len(), half.len());
    let many: Vec<String> = (0..=lightcone_lesson::MAX_CHOICES)
        .map(|i| i.to_string())
        .collect();
    let (kind, _) = ask(&mut w, "ask", json!(["?", many]), json!({})).unwrap_err();
    assert_eq!(kind, ErrorKind::Value);
    let (kind, _) = ask(&mut w, "finish", json!([big]), json!({})).unwrap_err();
    assert_eq!(kind, ErrorKind::Value);
    // The game writes no file a lesson names: the lesson's side saves it.
    let (kind, message) = ask(&mut w, "diagram", json!(["/tmp/x.png"]), json!({})).unwrap_err();
    assert_eq!(kind, ErrorKind::Value, "{message}");
    assert!(!std::path::Path::new("/tmp/x.png").exists() || message.contains("lesson's side"));
    // A bool is a number, as in Python (True == 1).
    ask(&mut w, "=time_scale", json!([true]), json!({})).unwrap();
    assert_eq!(w.game().unwrap().time_scale(), 1.0);
    // What a lesson printed or raised is cut for the panel.
    let tail = protocol::printed_tail(vec!["é".repeat(5000); 50]);
    assert_eq!(tail.len(), protocol::PRINTED_LINES);
    assert!(tail[0].len() <= protocol::PRINTED_LINE_BYTES + '…'.len_utf8());
    assert!(lightcone_lesson::cut(&"é".repeat(10), 5).ends_with('…'));
}

/// In `setup` the host lends the game the lesson is building: until
/// `world.start(scene)` the world has no game to speak of, then it has
/// exactly the host's, restarted on that scene (no game made elsewhere
/// and handed back).
#[test]
fn before_start_the_setup_game_is_no_game_and_start_restarts_the_hosts() {
    let empty = Scene::empty(glam::DVec2::new(1.0, 1.0), None).unwrap();
    let mut host = Host {
        core: WorldCore::new(".".into()),
        board: new_board(empty),
    };
    let mut w = host.call();
    let refused = ask(&mut w, "state", json!([]), json!({})).unwrap_err();
    assert_eq!(
        refused,
        (ErrorKind::Runtime, lightcone_lesson::NO_GAME.to_owned())
    );
    let scene = json!({ "$scene": serde_json::to_string(&two_pucks()).unwrap() });
    ask(&mut w, "start", json!([scene]), json!({})).unwrap();
    assert!(ask(&mut w, "state", json!([]), json!({})).is_ok());
    assert!(w.started());
    assert_eq!(
        host.board.scene,
        two_pucks(),
        "the host's own game was started"
    );
}
