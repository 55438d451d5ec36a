//! Lessons from strangers (issue 34): what a lesson claimed survives its
//! process, what it sends is bounded, and its process is sandboxed.

use super::lesson_outcome;

/// A claim reaches `--json` when it is made: a hook that claims and then
/// is killed at its time limit inside one C call, or aborts its process,
/// keeps every claim (they came only when the hook returned, so both were
/// lost).
#[test]
fn claims_made_before_the_process_dies_are_kept() {
    let runs: Vec<_> = [
        ("claims_then_hangs", 3, "could not be interrupted"),
        ("claims_then_aborts", 4, "SIGABRT"),
    ]
    .into_iter()
    .map(|(name, status, says)| {
        let run = std::thread::spawn(move || {
            lesson_outcome(&format!("tests/lessons/{name}.py"), &["--hook-limit", "1"])
        });
        (name, status, says, run)
    })
    .collect();
    for (name, status, says, run) in runs {
        let (outcome, code, _, stderr) = run.join().unwrap();
        assert_eq!(code, Some(status), "{name}: {outcome}\n{stderr}");
        let error = outcome["error"].as_str().unwrap_or_default();
        assert!(error.contains(says), "{name}: {says:?} not in {error}");
        let claims: Vec<&str> = outcome["claims"]
            .as_array()
            .expect("claims")
            .iter()
            .map(|c| c["claim"].as_str().unwrap_or_default())
            .collect();
        let expected: &[&str] = if name == "claims_then_hangs" {
            &["claimed in setup", "claimed before the C call"]
        } else {
            &["claimed before the crash"]
        };
        assert_eq!(claims, expected, "{name}: {outcome}");
    }
}
