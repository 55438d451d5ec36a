//! The lesson protocol's bounds and requests, tested without a lesson's
//! process (`super` is `lesson::remote`).

use super::*;
use std::cell::RefCell;
use std::rc::Rc;

use lightcone_python::World;

#[test]
fn a_hook_that_prints_megabytes_sends_only_what_the_panel_keeps() {
    let many: Vec<String> = (0..400_000)
        .map(|i| format!("line {i} {}", "x".repeat(30)))
        .collect();
    let tail = protocol::printed_tail(many);
    assert_eq!(tail.len(), protocol::PRINTED_LINES);
    assert!(tail.last().is_some_and(|l| l.starts_with("line 399999 ")));
    let long = protocol::printed_tail(vec!["y".repeat(40 << 20)]);
    assert_eq!(long[0].chars().count(), 4097);
}

#[test]
fn the_game_serves_the_world_and_nothing_else() {
    super::super::init_python().unwrap();
    for op in ["state", "impulse", "say", "diagram", "claims", "=paused"] {
        assert!(protocol::serves(op), "{op}");
    }
    // `load` runs in the lesson's process; the rest is not World's.
    for op in ["load", "__init__", "__class__", "=t", "=claims", "", "dir"] {
        assert!(!protocol::serves(op), "{op}");
    }
    // What the game serves (Rust) is what the lesson's stand-in asks for
    // (remote.py's SERVED), both ways.
    let asked: Vec<String> = Python::attach(|py| {
        module(py)
            .and_then(|m| m.getattr("SERVED"))
            .and_then(|s| s.extract())
    })
    .unwrap();
    assert!(asked.iter().all(|op| protocol::serves(op)), "{asked:?}");
    let served = protocol::METHODS.len() + protocol::GETTERS.len() + protocol::SETTABLE.len();
    assert_eq!(asked.len(), served, "{asked:?}");
}

#[test]
fn the_snapshot_says_what_the_python_world_says() {
    super::super::init_python().unwrap();
    let scene = lightcone_engine::scene::load(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/paper_carom.toml"),
    )
    .unwrap();
    let mut game = GameState::new(scene);
    game.step(0.25);
    game.time_scale = 0.5;
    game.observer = Some(0);
    game.effects
        .set(lightcone_engine::scene::Effect::Doppler, false);
    let ours = serde_json::to_value(protocol::snapshot(&game)).unwrap();
    let world = Python::attach(|py| Py::new(py, World::new(".".into()))).unwrap();
    // The getters of `lightcone.World`, read by Python on the same game.
    let theirs = Python::attach(|py| -> PyResult<String> {
        let w = world.bind(py);
        let shared: Rc<RefCell<dyn lightcone_lesson::LessonGame>> = Rc::new(RefCell::new(game));
        w.borrow_mut().share(Some(shared));
        // As after the lesson's `world.start(scene)`.
        w.borrow_mut().generation = 1;
        let json = py.import("json")?;
        let d = pyo3::types::PyDict::new(py);
        for name in [
            "t",
            "c",
            "paused",
            "time_scale",
            "view",
            "observer",
            "effects",
        ] {
            d.set_item(name, w.getattr(name)?)?;
        }
        let text = json.call_method1("dumps", (d,))?.extract::<String>()?;
        w.borrow_mut().share(None);
        Ok(text)
    })
    .unwrap();
    Python::attach(|_| drop(world)); // unsendable: released here
    let theirs: Value = serde_json::from_str(&theirs).unwrap();
    assert_eq!(ours, theirs);
    assert_eq!(ours["effects"]["doppler"], Value::Bool(false));
    assert_eq!(ours["view"], Value::from("seen"));
}

#[test]
fn only_the_two_messages_parse() {
    let done = r#"{"done":{"error":null,"timed_out":false,"printed":[],"hooks":["on_frame"]}}"#;
    assert!(matches!(
        serde_json::from_str::<Up>(done),
        Ok(Up::Done { .. })
    ));
    let request = r#"{"request":{"op":"say","args":["hi"],"kwargs":{}}}"#;
    assert!(matches!(
        serde_json::from_str::<Up>(request),
        Ok(Up::Request { .. })
    ));
    for bad in [
        r#"{"shell":"rm -rf /"}"#,
        r#"{"done":{"error":null,"timed_out":false,"printed":[],"hooks":[],"extra":1}}"#,
        r#"{"request":{"op":"say"}}"#,
        "garbage",
    ] {
        assert!(serde_json::from_str::<Up>(bad).is_err(), "{bad}");
    }
}
