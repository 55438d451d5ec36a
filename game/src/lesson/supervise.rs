//! `lightcone lesson` runs each lesson in a child process: the same binary,
//! `lightcone lesson FILE --child`, which runs the headless host
//! ([`super::headless`]) and reports each hook's start and end, each
//! frame, claim and answer, and its outcome, as JSON lines on its standard
//! output (what the lesson prints goes to standard error). The parent
//! times the hooks itself, so a lesson can neither swallow nor block the
//! stop, nor take the runner down:
//!
//! - a hook still running [`KILL_AFTER`] past its limit (a long C builtin,
//!   a blocked call the in-process stop could not break) has its process
//!   group killed, and is reported as stopped at the time limit;
//! - a process that ends without its outcome (a crash through `ctypes`,
//!   memory beyond `--memory-limit`, an exit through a loophole) is
//!   reported with its exit status or signal;
//! - the child runs in its own process group, with its address space
//!   limited (`RLIMIT_AS`), and is killed with everything it started.
//!
//! Either way the outcome keeps what the lesson did before: board time,
//! frames, claims and answers. Each claim is sent as it is made (not when
//! its hook returns), so a process killed or crashed later in the same
//! hook keeps every claim it made.

use std::io::{BufReader, Read, Write};
use std::os::unix::process::{CommandExt, ExitStatusExt};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::Mutex;
use std::sync::mpsc;
use std::time::{Duration, Instant};

use serde::{Deserialize, Serialize};

use super::headless::{self, Outcome, Progress, Stop};
use super::line;
use super::sandbox::{self, Scratch};
use super::watchdog::{self, HARD_STOP_STATUS};
use lightcone_python::{MAX_CLAIM_BYTES, MAX_CLAIMS};

/// How long past its limit a hook runs before the parent kills its
/// process (the in-process stop usually ends it within 50 ms of the limit).
pub const KILL_AFTER: Duration = Duration::from_millis(500);

/// Default address-space limit of a lesson's process, MiB.
pub const MEMORY_LIMIT_MB: u64 = 4096;

/// Most questions a lesson's run may answer (each kept in its outcome).
pub const MAX_ANSWERS: usize = 10_000;

/// Longest question or choice kept of an answer, bytes.
pub const MAX_ANSWER_BYTES: usize = 64 << 10;

/// Most a lesson's process may print (to standard error, through its
/// parent), bytes: past it the lesson is stopped.
pub const MAX_PRINTED: u64 = 16 << 20;

/// Longest error or closing message sent in an outcome, bytes (longer
/// ones are cut, with "…").
const MAX_MESSAGE: usize = 1 << 20;

/// `text` cut to at most `max` bytes (at a character boundary), "…" added.
fn cut(mut text: String, max: usize) -> String {
    if text.len() > max {
        let mut end = max;
        while !text.is_char_boundary(end) {
            end -= 1;
        }
        text.truncate(end);
        text.push('…');
    }
    text
}

/// Why claim `c`, after `made` others, is beyond what a lesson may send
/// (`World.check` refuses it; only a forged message gets here).
fn claim_out_of_bounds(made: usize, c: &headless::ClaimLine) -> Option<String> {
    if made >= MAX_CLAIMS {
        Some(format!("it made more than {MAX_CLAIMS} claims"))
    } else if c.claim.len().max(c.detail.len()) > MAX_CLAIM_BYTES {
        Some(format!(
            "it sent a claim longer than {MAX_CLAIM_BYTES} bytes"
        ))
    } else {
        None
    }
}

/// Why an answer, after `given` others, is beyond what a run keeps.
fn answer_out_of_bounds(given: usize, question: &str, choice: &str) -> Option<String> {
    if given >= MAX_ANSWERS {
        Some(format!("it asked more than {MAX_ANSWERS} questions"))
    } else if question.len().max(choice.len()) > MAX_ANSWER_BYTES {
        Some(format!(
            "it asked a question (or gave a choice) longer than {} KiB",
            MAX_ANSWER_BYTES >> 10
        ))
    } else {
        None
    }
}

/// What the student is told of a lesson stopped for what it sent.
pub(crate) fn misbehaved(place: &str, why: &str) -> String {
    format!("{place}: the lesson's process misbehaved: {why}; it was stopped")
}

/// Copies what the lesson's process prints (`from`, its standard error)
/// to ours as it comes, in chunks (a line with no newline takes no
/// memory); past [`MAX_PRINTED`] bytes stops copying and tells `flood`.
pub(crate) fn forward_printed(
    mut from: std::process::ChildStderr,
    flood: impl FnOnce(String) + Send + 'static,
) {
    std::thread::spawn(move || {
        let mut buf = vec![0u8; 64 << 10];
        let mut total = 0u64;
        loop {
            let n = match from.read(&mut buf) {
                Ok(0) => return,
                Ok(n) => n,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                Err(_) => return,
            };
            total += n as u64;
            if total > MAX_PRINTED {
                flood(format!(
                    "it printed more than {} MiB (what a lesson prints is bounded)",
                    MAX_PRINTED >> 20
                ));
                return;
            }
            let _ = std::io::stderr().write_all(&buf[..n]);
        }
    });
}

/// What a run needs.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Board time to stop at, s.
    pub until: f64,
    /// Frames per real second.
    pub fps: f64,
    /// Longest a hook may run.
    pub hook: Duration,
    /// Address-space limit of the lesson's process, MiB.
    pub memory_mb: u64,
    /// Longest the whole run may take, real time (a lesson that slows
    /// time to nothing never reaches `until`).
    pub run: Duration,
}

/// One line from the child.
#[derive(Debug, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
enum Event {
    /// A hook started (`Some`) or returned (`None`).
    Hook(Option<String>),
    /// A frame, claim or answer.
    Progress(Progress),
    /// The run's outcome (the last line).
    Outcome(Outcome),
    /// The run could not start (no Python).
    Failed(String),
}

/// Where the child writes its events (its original standard output).
static EVENTS: Mutex<Option<std::fs::File>> = Mutex::new(None);

fn send(event: &Event) {
    let mut guard = EVENTS.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(out) = guard.as_mut()
        && let Ok(mut line) = serde_json::to_vec(event)
    {
        line.push(b'\n');
        let _ = out.write_all(&line);
    }
}

fn hook_event(name: Option<&'static str>) {
    send(&Event::Hook(name.map(str::to_owned)));
}

fn claim_event(claim: &lightcone_python::Claim) {
    send(&Event::Progress(Progress::Claim(headless::ClaimLine {
        claim: claim.claim.clone(),
        ok: claim.ok,
        detail: claim.detail.clone(),
    })));
}

/// Sets up a lesson's own process (the child of `lightcone lesson`, or of
/// the window): dies with its parent, limits its address space to
/// `memory_mb` MiB, and moves standard output to standard error (what the
/// lesson prints goes there). Returns the original standard output, the
/// channel to the parent.
pub(crate) fn child_process(memory_mb: u64) -> Result<std::fs::File, String> {
    // Die with the parent: a run killed from outside (or ended by Ctrl-C)
    // must not leave its lesson running.
    // SAFETY: a plain system call on this process.
    unsafe {
        libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGKILL);
    }
    if std::os::unix::process::parent_id() == 1 {
        return Err("the parent is already gone".to_owned());
    }
    // Nothing the game had open but the three pipes reaches the lesson
    // (the sandbox restricts what it opens, not what it holds).
    // SAFETY: closes this process's descriptors from 3 on; none is in use
    // yet.
    unsafe {
        libc::syscall(libc::SYS_close_range, 3u32, u32::MAX, 0u32);
    }

    // A batch task: woken by the game's call, it does not preempt the
    // game's frame on the same core (the wake-up would otherwise cost the
    // game the hook's whole run); it runs beside it or when it waits.
    // SAFETY: a plain system call on this process (a policy any user may
    // choose; failing leaves the default policy).
    unsafe {
        let param = libc::sched_param { sched_priority: 0 };
        libc::sched_setscheduler(0, libc::SCHED_BATCH, &param);
    }
    let bytes = memory_mb.saturating_mul(1 << 20);
    // SAFETY: plain system calls on this process's own descriptors and
    // limits; `dup` returns a fresh descriptor we own.
    unsafe {
        let limit = libc::rlimit {
            rlim_cur: bytes,
            rlim_max: bytes,
        };
        libc::setrlimit(libc::RLIMIT_AS, &limit);
        let fd = libc::dup(1);
        if fd < 0 || libc::dup2(2, 1) < 0 {
            return Err("cannot set up the lesson's process".to_owned());
        }
        Ok(<std::fs::File as std::os::fd::FromRawFd>::from_raw_fd(fd))
    }
}

/// Starts `lightcone ARGS` (this binary, `exe`) as a lesson's process: its
/// own process group, standard input, output and error piped (what it
/// prints is read through [`forward_printed`]), and its private temporary
/// folder (removed when the [`Scratch`] is dropped, after the process).
pub(crate) fn spawn(exe: &Path, args: &[std::ffi::OsString]) -> Result<(Child, Scratch), String> {
    let scratch = Scratch::new()?;
    let mut command = Command::new(exe);
    // Its private temporary folder, the one place it may write
    // (`super::sandbox`).
    command
        .env("TMPDIR", scratch.path())
        .env(sandbox::SCRATCH_ENV, scratch.path());
    // Under the address-space limit, glibc's malloc arenas (64 MiB of
    // address space each, one per thread that allocates, up to 8 per core)
    // would take it all: six of them fill 384 MiB, and the lesson could
    // not start a thread. Two are enough for a lesson.
    if std::env::var_os("MALLOC_ARENA_MAX").is_none() {
        command.env("MALLOC_ARENA_MAX", "2");
    }
    command
        .args(args)
        // For the headless child, a pipe nobody writes to: `input()`
        // waits, as in a terminal. The window's child reads its calls
        // there (and gives the lesson such a pipe instead).
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .process_group(0)
        .spawn()
        .map(|child| (child, scratch))
        .map_err(|e| format!("cannot start the lesson's process: {e}"))
}

/// Kills the process group `pid` leads (a child from [`spawn`]) with
/// everything the lesson started.
pub(crate) fn kill_group(pid: u32) {
    // SAFETY: signals the child's own process group (its id is the
    // child's pid, from `process_group(0)`).
    unsafe {
        libc::kill(-(pid as libc::pid_t), libc::SIGKILL);
    }
}

/// How a lesson's process that ended without reporting ended, in words
/// ("exited with status 7", "crashed (SIGSEGV: …)").
pub(crate) fn how_it_ended(status: std::process::ExitStatus, memory_mb: u64) -> String {
    match (status.code(), status.signal()) {
        (Some(code), _) => format!("exited with status {code}"),
        (None, Some(libc::SIGSEGV)) => {
            "crashed (SIGSEGV: a bad memory access, e.g. through ctypes)".to_owned()
        }
        (None, Some(libc::SIGKILL)) => {
            "was killed (SIGKILL: out of memory, or killed from outside)".to_owned()
        }
        (None, Some(libc::SIGABRT)) => {
            format!("aborted (SIGABRT: out of memory? the limit is {memory_mb} MiB)")
        }
        (None, Some(libc::SIGXCPU)) => format!(
            "was stopped by its CPU time limit (SIGXCPU: {} h)",
            sandbox::CPU_LIMIT_S / 3600
        ),
        (None, Some(libc::SIGXFSZ)) => format!(
            "was stopped writing a file larger than {} MiB (SIGXFSZ)",
            sandbox::FILE_SIZE >> 20
        ),
        (None, Some(libc::SIGSYS)) => "was stopped by its sandbox (SIGSYS)".to_owned(),

        (None, Some(sig)) => format!("was ended by signal {sig}"),
        (None, None) => "ended".to_owned(),
    }
}

/// What the student is told of a hook stopped by killing its process.
pub(crate) fn uninterruptible(place: &str, limit: Duration) -> String {
    format!(
        "{place}: the hook ran for more than {} s and could not be interrupted (a long computation inside one call, such as a C builtin?); its process was stopped",
        limit.as_secs_f64()
    )
}

/// The child's side (`lightcone lesson FILE --child`): limits its memory,
/// moves standard output to the event channel (the lesson's prints go to
/// standard error), runs the lesson and reports. Returns the exit status.
pub fn child(path: &Path, limits: Limits) -> u8 {
    let events = match child_process(limits.memory_mb) {
        Ok(f) => f,
        Err(e) => {
            crate::errln!("{e}");
            return 1;
        }
    };
    *EVENTS.lock().unwrap_or_else(|e| e.into_inner()) = Some(events);
    watchdog::observe_hooks(hook_event);
    // Each claim goes to the parent as it is made (not when its hook
    // returns): a process that dies later in the hook keeps it.
    lightcone_python::observe_claims(claim_event);
    if let Err(e) = super::init_python().and_then(|()| sandboxed(path)) {
        send(&Event::Failed(e));
        return 1;
    }
    let result = headless::run_reporting(path, limits.until, limits.fps, limits.hook, &mut |p| {
        if !matches!(p, Progress::Claim(_)) {
            send(&Event::Progress(p));
        }
    });
    match result {
        Ok(mut outcome) => {
            let status = outcome.status();
            // The parent has them all already, in order; the texts are cut
            // to what one line to the parent holds.
            outcome.claims.clear();
            outcome.answers.clear();
            outcome.error = outcome.error.map(|e| cut(e, MAX_MESSAGE));
            outcome.finished = outcome.finished.map(|e| cut(e, MAX_MESSAGE));
            send(&Event::Outcome(outcome));
            status
        }
        Err(e) => {
            send(&Event::Failed(cut(e, MAX_MESSAGE)));
            1
        }
    }
}

/// Enters the sandbox ([`super::sandbox`]) before the lesson at `path`
/// runs, saying on stderr what this kernel lacks.
pub(crate) fn sandboxed(path: &Path) -> Result<(), String> {
    for lacking in sandbox::enter(&super::lesson_dir(path))? {
        crate::errln!("{}: {lacking}", path.display());
    }
    Ok(())
}

/// What the parent knows of a child that did not report its outcome.
#[derive(Default)]
struct Partial {
    t: f64,
    frames: u64,
    claims: Vec<headless::ClaimLine>,
    answers: Vec<(String, String)>,
}

/// Runs the lesson at `path` in a child process and reports its outcome,
/// whatever the lesson does. Fails only when the child cannot start or
/// the run cannot (a bad argument, no Python).
pub fn run(path: &Path, limits: Limits) -> Result<Outcome, String> {
    let exe = std::env::current_exe().map_err(|e| format!("cannot find lightcone itself: {e}"))?;
    let args: Vec<std::ffi::OsString> = [
        "lesson".into(),
        "--until".into(),
        limits.until.to_string().into(),
        "--fps".into(),
        limits.fps.to_string().into(),
        "--hook-limit".into(),
        limits.hook.as_secs_f64().to_string().into(),
        "--memory-limit".into(),
        limits.memory_mb.to_string().into(),
        "--child".into(),
        // The file last, after `--`: a name that starts with `-`.
        "--".into(),
        path.as_os_str().to_owned(),
    ]
    .into();
    let (mut child, _scratch) = spawn(&exe, &args)?;
    let pid = child.id();
    let kill_group = || kill_group(pid);
    // Bounded both ways: a line is read to at most `MAX_LINE` bytes, and
    // a few events wait at most (a lesson that floods waits for the
    // parent). `Err` is a breach of the channel's bounds.
    let (tx, rx) = mpsc::sync_channel::<Result<Event, String>>(64);
    if let Some(printed) = child.stderr.take() {
        let tx = tx.clone();
        forward_printed(printed, move |why| {
            let _ = tx.send(Err(why));
        });
    }
    if let Some(out) = child.stdout.take() {
        std::thread::spawn(move || {
            let mut reader = BufReader::new(out);
            loop {
                let sent = match line::read_line(&mut reader) {
                    Ok(None) => break,
                    Err(e) => {
                        let _ = tx.send(Err(e));
                        break;
                    }
                    // A line that is no event is skipped (the lesson goes on).
                    Ok(Some(line)) => match serde_json::from_slice::<Event>(&line) {
                        Ok(event) => tx.send(Ok(event)),
                        Err(_) => Ok(()),
                    },
                };
                if sent.is_err() {
                    break;
                }
            }
        });
    }
    let mut partial = Partial::default();
    // Board time reached, towards `--until` (stderr, a terminal only; the
    // lesson's own printing goes there too, through the child).
    let progress = crate::progress::bar(limits.until, "board s");
    let mut hook: Option<(String, Instant)> = None;
    let mut outcome = None;
    let mut failed = None;
    let mut killed = false;
    let mut breach = None;
    let mut exited = None;
    let mut deadline = None;
    let started = Instant::now();
    loop {
        match rx.recv_timeout(Duration::from_millis(10)) {
            Ok(Ok(Event::Hook(Some(name)))) => hook = Some((name, Instant::now())),
            Ok(Ok(Event::Hook(None))) => hook = None,
            Ok(Ok(Event::Progress(Progress::Frame { t, frames }))) => {
                partial.t = t;
                partial.frames = frames;
                progress.set_position_f64(t);
            }
            Ok(Ok(Event::Progress(Progress::Claim(c)))) => {
                breach = claim_out_of_bounds(partial.claims.len(), &c);
                partial.claims.push(c);
            }
            Ok(Ok(Event::Progress(Progress::Answer(q, a)))) => {
                breach = answer_out_of_bounds(partial.answers.len(), &q, &a);
                partial.answers.push((q, a));
            }
            Ok(Ok(Event::Outcome(o))) => outcome = Some(o),
            Ok(Ok(Event::Failed(e))) => failed = Some(e),
            Ok(Err(why)) => breach = Some(why),
            Err(mpsc::RecvTimeoutError::Timeout) => {}
            Err(mpsc::RecvTimeoutError::Disconnected) => break,
        }
        if breach.is_some() {
            kill_group();
            break;
        }
        if crate::interrupt::interrupted() {
            // Ctrl-C: stop the lesson; what it did so far is reported.
            progress.finish();
            kill_group();
            let _ = child.wait();
            return Ok(Outcome {
                file: path.display().to_string(),
                t: partial.t,
                frames: partial.frames,
                finished: None,
                error: None,
                stopped: None,
                claims: partial.claims,
                answers: partial.answers,
            });
        }
        // (A lesson whose outcome has arrived has ended: its process is
        // exiting.)
        if started.elapsed() > limits.run && exited.is_none() && outcome.is_none() {
            progress.finish();
            kill_group();
            let _ = child.wait();
            let error = format!(
                "the lesson ran {} s of real time without finishing or reaching --until {} s \
                 (board time t = {:.3} s after {} frames): stopped; give --time-limit for longer",
                limits.run.as_secs_f64(),
                limits.until,
                partial.t,
                partial.frames,
            );
            crate::errln!("lesson {} stopped:\n{error}", path.display());
            return Ok(Outcome {
                file: path.display().to_string(),
                t: partial.t,
                frames: partial.frames,
                finished: None,
                error: Some(error),
                stopped: Some(Stop::Timeout),
                claims: partial.claims,
                answers: partial.answers,
            });
        }
        if let Some((_, since)) = &hook
            && since.elapsed() > limits.hook + KILL_AFTER
        {
            kill_group();
            killed = true;
            break;
        }
        if exited.is_none() {
            exited = child.try_wait().ok().flatten();
            if exited.is_some() {
                deadline = Some(Instant::now() + Duration::from_millis(200));
            }
        }
        // Exited, but something it started holds the pipe open: give the
        // reader a moment, then stop listening.
        if deadline.is_some_and(|d| Instant::now() > d) {
            break;
        }
    }
    progress.finish();
    // Whatever the child left behind (a forked process) goes with it.
    kill_group();
    let status = match exited {
        Some(s) => s,
        None => child
            .wait()
            .map_err(|e| format!("cannot wait for the lesson's process: {e}"))?,
    };
    let place = match &hook {
        Some((name, _)) => format!("in {name}"),
        None => "between hooks".to_owned(),
    };
    if let Some(why) = breach {
        // What it sent within the bounds is kept; the rest is dropped.
        partial.claims.truncate(MAX_CLAIMS);
        partial.answers.truncate(MAX_ANSWERS);
        let error = misbehaved(&place, &why);
        crate::errln!("lesson {} stopped:\n{error}", path.display());
        return Ok(Outcome {
            file: path.display().to_string(),
            t: partial.t,
            frames: partial.frames,
            finished: None,
            error: Some(error),
            stopped: Some(Stop::Died),
            claims: partial.claims,
            answers: partial.answers,
        });
    }
    if let Some(e) = failed {
        return Err(e);
    }
    if let Some(mut o) = outcome {
        // Sent one by one as they were made (the outcome carries none).
        o.claims = partial.claims;
        o.answers = partial.answers;
        return Ok(o);
    }
    // Status 3 is the watchdog's hard stop only for a hook over its limit
    // (a lesson may end its process with 3 itself, through ctypes).
    let over = hook
        .as_ref()
        .is_some_and(|(_, since)| since.elapsed() > limits.hook);
    let (stopped, error) = if killed || (over && status.code() == Some(HARD_STOP_STATUS)) {
        (Stop::Timeout, uninterruptible(&place, limits.hook))
    } else {
        let how = how_it_ended(status, limits.memory_mb);
        (
            Stop::Died,
            format!("{place}: the lesson's process {how}; the lesson stopped there"),
        )
    };
    crate::errln!("lesson {} stopped:\n{error}", path.display());
    Ok(Outcome {
        file: path.display().to_string(),
        t: partial.t,
        frames: partial.frames,
        finished: None,
        error: Some(error),
        stopped: Some(stopped),
        claims: partial.claims,
        answers: partial.answers,
    })
}

/// How the window starts its lesson's process: this binary, with the
/// address-space limit in `LIGHTCONE_MEMORY_LIMIT` (MiB, at least 256;
/// default [`MEMORY_LIMIT_MB`]). Fails, saying why,
/// when the binary cannot be found or the variable is not such a
/// number.
pub fn window_isolation() -> Result<super::isolation::Isolation, String> {
    let exe = std::env::current_exe().map_err(|e| format!("cannot find lightcone itself: {e}"))?;
    let memory_mb = match std::env::var("LIGHTCONE_MEMORY_LIMIT") {
        Err(_) => MEMORY_LIMIT_MB,
        Ok(text) => match text.trim().parse::<u64>() {
            Ok(mb) if mb >= 256 => mb,
            _ => {
                return Err(format!(
                    "LIGHTCONE_MEMORY_LIMIT={text:?}: give MiB, at least 256"
                ));
            }
        },
    };
    Ok(super::isolation::Isolation { exe, memory_mb })
}
