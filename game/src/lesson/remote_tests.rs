//! The lesson protocol's bounds and requests, tested without a lesson's
//! process (`super` is `lesson::remote`).

use super::*;

#[test]
fn a_hook_that_prints_megabytes_sends_only_what_the_panel_keeps() {
    let many: Vec<String> = (0..400_000)
        .map(|i| format!("line {i} {}", "x".repeat(30)))
        .collect();
    let tail = printed_tail(many);
    assert_eq!(tail.len(), super::super::PRINTED_LINES);
    assert!(tail.last().is_some_and(|l| l.starts_with("line 399999 ")));
    let long = printed_tail(vec!["y".repeat(40 << 20)]);
    assert_eq!(long[0].chars().count(), 4097);
}

#[test]
fn the_game_serves_the_world_and_nothing_else() {
    super::super::init_python().unwrap();
    for op in ["state", "impulse", "say", "diagram", "claims", "=paused"] {
        assert!(served(op), "{op}");
    }
    // `load` runs in the lesson's process; the rest is not World's.
    for op in ["load", "__init__", "__class__", "=t", "=claims", "", "dir"] {
        assert!(!served(op), "{op}");
    }
}

#[test]
fn the_snapshot_built_in_rust_is_the_worlds() {
    super::super::init_python().unwrap();
    let scene = lightcone_engine::scene::load(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/paper_carom.toml"),
    )
    .unwrap();
    let mut game = GameState::new(scene);
    game.step(0.25);
    game.time_scale = 0.5;
    game.observer = Some(0);
    let ours = serde_json::to_value(snapshot(&game)).unwrap();
    let world = Python::attach(|py| Py::new(py, World::new(".".into(), lend::new_game))).unwrap();
    let theirs = Python::attach(|py| -> PyResult<String> {
        let w = world.bind(py);
        w.borrow_mut().game = Some(Box::new(game));
        let text = module(py)?
            .call_method1("call", (w, "on_frame", "[]"))?
            .extract::<String>()?;
        w.borrow_mut().game = None;
        Ok(text)
    })
    .unwrap();
    Python::attach(|_| drop(world)); // unsendable: released here
    let theirs: Value = serde_json::from_str(&theirs).unwrap();
    assert_eq!(ours, theirs["snapshot"]);
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
