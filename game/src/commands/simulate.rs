//! `lightcone simulate SCENE --until T [--out FILE]`: run the physics
//! headless and write every collision, then the final state, as JSON lines.
//!
//! The lines are streamed: the billiard runs in bounded steps, every
//! finished collision is written (and the output flushed) after each step,
//! and the billiard keeps no history (`set_history(Some(0))`), so memory
//! stays O(N) however long the run. A run stopped by Ctrl-C writes what it
//! has and a final state line at the time reached, then exits 130.

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use lightcone_engine::physics::Billiard;
use lightcone_engine::report::{CollisionLine, StateLine};
use lightcone_engine::scene;

/// Calendar entries processed between two flushes (and progress updates
/// and Ctrl-C checks): about 0.1–0.3 s of a dense braking gas, so a
/// Ctrl-C keeps nearly everything computed (2¹⁴ took 2–4 s there).
const STEP_EVENTS: usize = 1 << 11;

/// Runs `scene` to board time `until` and writes the JSON lines to `out`
/// (stdout when `None`). Warnings (e.g. a Zeno sequence ended) go to stderr.
pub fn run(scene_path: &Path, until: f64, out: Option<&PathBuf>) -> ExitCode {
    if !until.is_finite() || until < 0.0 {
        crate::errln!("--until {until}: give a finite board time ≥ 0 in seconds");
        return ExitCode::from(2);
    }
    if let Some(Err(e)) = out.map(|o| crate::output::not_the_input(o, scene_path)) {
        crate::errln!("{e}");
        return ExitCode::FAILURE;
    }
    let scene = match scene::load(scene_path) {
        Ok(s) => s,
        Err(e) => {
            crate::errln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let mut billiard = Billiard::from_scene(&scene);
    billiard.set_history(Some(0.0));
    // A braking cluster can keep one step busy for long: stop within 2 s
    // of Ctrl-C whatever the step is doing (the records are flushed a step
    // at a time).
    crate::interrupt::watch_within(std::time::Duration::from_millis(1500));
    let result = match out {
        Some(path) => match std::fs::File::create(path) {
            Ok(f) => stream(&mut billiard, until, BufWriter::new(f)),
            Err(e) => {
                crate::errln!("{}: cannot create: {e}", path.display());
                return ExitCode::FAILURE;
            }
        },
        None => stream(
            &mut billiard,
            until,
            BufWriter::new(std::io::stdout().lock()),
        ),
    };
    for w in billiard.warnings() {
        crate::errln!("{}: warning: {w}", scene_path.display());
    }
    let merges = billiard.stats().zeno_merges;
    if merges > 1 {
        crate::errln!(
            "{}: warning: {merges} inelastic collapses ended in all",
            scene_path.display()
        );
    }
    match result {
        Ok(Finish::Done) => ExitCode::SUCCESS,
        Ok(Finish::Interrupted(t)) => crate::interrupt::exit_code(&format!(
            "at board time {t} s; the collisions up to then and the state then were written"
        )),
        // The reader went away (`| head`): not an error of ours.
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(e) => {
            let to = out.map_or("stdout".to_owned(), |p| p.display().to_string());
            crate::errln!("{to}: cannot write the output: {e}");
            ExitCode::FAILURE
        }
    }
}

/// How a streamed run ended.
enum Finish {
    /// At `--until`.
    Done,
    /// Stopped by Ctrl-C at this board time.
    Interrupted(f64),
}

/// Runs to `until`, writing each finished collision as soon as it is known,
/// in the order processed (that of each collision's first velocity change),
/// then the state line.
fn stream(billiard: &mut Billiard, until: f64, mut w: impl Write) -> std::io::Result<Finish> {
    let progress = crate::progress::bar(until, "board s");
    let mut next = 0u64; // global index of the next record to write
    let mut finish = Finish::Done;
    loop {
        let done = billiard.step_until(until, STEP_EVENTS);
        next = write_finished(billiard, next, &mut w, done)?;
        w.flush()?;
        progress.set_position_f64(billiard.time());
        if done {
            break;
        }
        if crate::interrupt::interrupted() {
            finish = Finish::Interrupted(billiard.time());
            // Whatever is still pending is written as scheduled.
            write_finished(billiard, next, &mut w, true)?;
            break;
        }
    }
    progress.finish();
    let t = billiard.time().min(until);
    serde_json::to_writer(&mut w, &StateLine::new(billiard, t))?;
    w.write_all(b"\n")?;
    w.flush()?;
    Ok(finish)
}

/// Writes the records from global index `next` on that are finished (all
/// kicks landed), stopping at the first one still pending unless `all`.
/// Returns the index of the next record to write.
fn write_finished(
    billiard: &Billiard,
    mut next: u64,
    w: &mut impl Write,
    all: bool,
) -> std::io::Result<u64> {
    for c in billiard.collisions_from(next) {
        if !all && c.pucks.iter().any(|p| p.pending) {
            break;
        }
        serde_json::to_writer(&mut *w, &CollisionLine::new(billiard, c))?;
        w.write_all(b"\n")?;
        next += 1;
    }
    Ok(next)
}
