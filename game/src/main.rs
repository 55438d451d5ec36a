//! `lightcone`: the relativistic carom billiard and its command-line tools.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use lightcone::commands::args;
use lightcone::{commands, interrupt};

#[derive(Parser)]
#[command(
    name = "lightcone",
    version,
    about = "A relativistic carom billiard for learning Special Relativity"
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Play: the interactive game on a scene (the default scene if none),
    /// or a Python lesson (`.py`).
    Play {
        /// Scene file (TOML) or lesson (`.py`).
        scene: Option<PathBuf>,
        /// Save a screenshot of the window (with its panels) to this PNG
        /// after `--frames` frames, then quit.
        #[arg(long, value_parser = args::png_file)]
        screenshot: Option<PathBuf>,
        /// Frames to run before the screenshot (1 to 1000000).
        #[arg(long, default_value_t = 30, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
        frames: u32,
        /// Drive the observer from a head tracker on this iceoryx2 service
        /// (see `lightcone tracker`).
        #[arg(long)]
        tracker: Option<String>,
        /// Render the walls of this CAVE (TOML, e.g. assets/cave.toml), each
        /// with its off-axis projection from the (tracked) head.
        #[arg(long)]
        cave: Option<PathBuf>,
        /// Open at board time T (s), paused (repeatable screenshots); a
        /// scene only.
        #[arg(long)]
        at: Option<f64>,
        #[command(flatten)]
        looks: LookArgs,
        /// Open with the live space-time diagram shown.
        #[arg(long)]
        diagram: bool,
        /// Open with the live space-time diagram shown in this puck's frame
        /// (its line of simultaneity drawn; implies --diagram). For a
        /// lesson, a puck of the scene its setup starts.
        #[arg(long, value_name = "PUCK")]
        diagram_frame: Option<String>,
        /// With --cave: be the master of a render cluster, listening for
        /// render nodes (`lightcone wall --join`) on this Zenoh endpoint
        /// (default tcp/0.0.0.0:7447).
        #[arg(long, requires = "cave", num_args = 0..=1, default_missing_value = lightcone::cluster::DEFAULT_ENDPOINT)]
        serve: Option<String>,
        /// With --cave: write each frame's CAVE eyes (board times and every
        /// apparent vertex) to this file, one JSON line a frame.
        #[arg(long, requires = "cave")]
        frame_log: Option<PathBuf>,
    },
    /// A render node of a CAVE cluster: joins the master (`play --cave
    /// FILE --serve`) and draws the named walls of its CAVE, frame by frame
    /// with it.
    Wall(commands::wall::WallArgs),
    /// Make a CAVE's cluster key: writes CAVE.key beside the CAVE file (a
    /// new random secret, readable by its owner only), which `play --cave
    /// CAVE.toml --serve` reads and each render node is given a copy of
    /// (`lightcone wall --key FILE`).
    ClusterKey {
        /// The CAVE file (TOML).
        cave: PathBuf,
        /// Replace a key already there (every node then needs the new one).
        #[arg(long)]
        replace: bool,
    },
    /// The simulated head tracker: publish head motion (a path, or a
    /// recorded CSV track) with noise and faults on an iceoryx2 service.
    /// Options: --service NAME --path still|circle|walk|figure8 --csv FILE
    /// --rate HZ --noise METRES --seed N --first-seq N --duration S
    /// --count N --nan-every N --reorder-every N --stall START,DURATION
    /// --dropout START,DURATION --quiet
    #[command(disable_help_flag = true)]
    Tracker {
        /// The publisher's options (see above).
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// Internal: read a tracker service in a child of `play --tracker`
    /// (see tracker_bridge).
    #[command(hide = true, disable_help_flag = true)]
    TrackerBridge {
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// Render every wall of a CAVE, both eyes, headless to PNG.
    Cave {
        /// Scene file (TOML); the built-in default scene when not given.
        scene: Option<PathBuf>,
        /// CAVE description (TOML); the built-in `assets/cave.toml` when
        /// not given.
        #[arg(long)]
        config: Option<PathBuf>,
        /// Directory for `<wall>_<left|right>.png`.
        #[arg(long)]
        out_dir: PathBuf,
        /// Board time, s (0 to 1e9).
        #[arg(long, default_value_t = 0.0, allow_negative_numbers = true, value_parser = args::time_from_zero)]
        at: f64,
        /// Head position in tracker space, `x,y,z` metres (default: the
        /// CAVE's centre, 1.7 m up).
        #[arg(long, allow_hyphen_values = true, value_parser = args::head)]
        head: Option<String>,
        /// Image size as a fraction of each wall's projector resolution,
        /// in (0, 4].
        #[arg(long, default_value_t = 0.5, allow_negative_numbers = true, value_parser = args::scale)]
        scale: f64,
    },
    /// Validate scene files and print a short summary of each.
    Check {
        /// Scene files (TOML); the default scene when none is given.
        scenes: Vec<PathBuf>,
    },
    /// Print the link that opens a scene file or a lesson in the browser
    /// build (`#scene=` / `#lesson=`: the file itself, compressed, in the
    /// link's fragment), after checking it (a scene as `check` does, a
    /// lesson for Python syntax).
    Link {
        /// Scene file (TOML) or lesson (.py).
        scene: PathBuf,
        /// The address the browser build is served at.
        #[arg(long, default_value = lightcone::commands::link::DEFAULT_BASE)]
        base: String,
    },
    /// Run the physics headless; print every collision, then the final
    /// state, as JSON lines (schema: docs/guide/src/commands.md).
    Simulate {
        /// Scene file (TOML).
        scene: PathBuf,
        /// Board time to run to, s (0 to 1e9).
        #[arg(long, allow_negative_numbers = true, value_parser = args::time_from_zero)]
        until: f64,
        /// Write the JSON lines here instead of stdout.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// What an observer sees at a board time, as one JSON object (schema in
    /// docs/guide/src/commands.md).
    Observe {
        /// Scene file (TOML).
        scene: PathBuf,
        /// Board time of the observation, s (−1e9 to 1e9).
        #[arg(long, allow_negative_numbers = true, value_parser = args::time)]
        at: f64,
        /// Observer name (default: the scene's first).
        #[arg(long)]
        observer: Option<String>,
        /// List every mesh vertex of every puck.
        #[arg(long)]
        vertices: bool,
        /// Effects: `scene`, `all`, `none`, or a list such as
        /// `contraction,light_delay,doppler`.
        #[arg(long, default_value = "scene", value_parser = args::effects)]
        effects: String,
    },
    /// Render what an observer sees to a PNG, headless: the window's
    /// pictures with its overlays (rings, names, clocks, trails, arrows,
    /// arcs, captions, the magnifier), without its panels.
    Render {
        /// Scene file (TOML), or a lesson (.py: run to --at, its questions
        /// answered with its own answers).
        scene: PathBuf,
        /// Board time, s (−1e9 to 1e9; a lesson from 0).
        #[arg(long, allow_negative_numbers = true, value_parser = args::time)]
        at: f64,
        /// Observer looked through, by name (default: the scene's first).
        #[arg(long)]
        observer: Option<String>,
        /// Output PNG (a .png file); its layout (views, pucks, labels) is
        /// written beside it as the same name with .json.
        #[arg(short, long, value_parser = args::png_file)]
        out: PathBuf,
        /// Image size, WIDTHxHEIGHT (each 1 to 16384).
        #[arg(long, default_value = "1280x720", value_parser = args::size)]
        size: String,
        #[command(flatten)]
        looks: LookArgs,
        /// The bare pictures: no rings, names, clocks, trails or captions.
        #[arg(long)]
        no_overlays: bool,
    },
    /// Draw the space-time diagram at board time T to a PNG: worldlines
    /// (board x across, time up), the eye's past light cone along each
    /// puck's path, the emission events it sees, collisions.
    Diagram {
        /// Scene file (TOML).
        scene: PathBuf,
        /// Board time of the observation, s (−1e9 to 1e9).
        #[arg(long, allow_negative_numbers = true, value_parser = args::time)]
        at: f64,
        /// Observer name (default: the scene's first).
        #[arg(long)]
        observer: Option<String>,
        /// Also draw the lines of simultaneity of this puck's rest frame
        /// (its "now" through its event at T). Default: none (only the
        /// board's "now").
        #[arg(long)]
        frame: Option<String>,
        /// The board axis across: x (default) or y.
        #[arg(long, value_enum, default_value = "x")]
        axis: AxisArg,
        /// Output PNG (a .png file).
        #[arg(short, long, value_parser = args::png_file)]
        out: PathBuf,
        /// Image size, WIDTHxHEIGHT (each 1 to 16384).
        #[arg(long, default_value = "1000x700", value_parser = args::sides)]
        size: String,
    },
    /// Record what an observer sees from board time 0 to T, headless, as
    /// an animated GIF, an MP4 (through ffmpeg) or a directory of PNGs.
    Record {
        /// Scene file (TOML), or a lesson (.py: its hooks run and its
        /// questions are answered with its own answers).
        scene: PathBuf,
        /// Last board time, s (0 to 1e9).
        #[arg(long, allow_negative_numbers = true, value_parser = args::time_from_zero)]
        until: f64,
        /// Frames per second of board time (1 to 120).
        #[arg(long, default_value_t = 25.0, allow_negative_numbers = true, value_parser = commands::record::fps)]
        fps: f64,
        /// Observer looked through, by name (default: the scene's first).
        #[arg(long)]
        observer: Option<String>,
        /// `out.gif`, `out.mp4` (needs ffmpeg), or `DIR/` for
        /// `DIR/frame_00000.png`, ….
        #[arg(short, long, value_parser = commands::record::output)]
        out: commands::record::Output,
        /// Frame size, WIDTHxHEIGHT (each 1 to 16384).
        #[arg(long, default_value = "640x360", value_parser = args::size)]
        size: String,
        #[command(flatten)]
        looks: LookArgs,
        /// The bare pictures: no rings, names, clocks, trails or captions.
        #[arg(long)]
        no_overlays: bool,
    },
    /// Run a Python lesson headless: its hooks, questions answered with
    /// the lesson's answer, and its claims checked. Fails if the lesson
    /// raises or a claim does not hold.
    Lesson {
        /// Lesson files (`.py`), each run in turn.
        #[arg(required = true, value_parser = args::lesson_file)]
        lessons: Vec<PathBuf>,
        /// Stop at this board time (s, 0 to 1e9) if the lesson has not
        /// finished.
        #[arg(long, default_value_t = 600.0, allow_negative_numbers = true, value_parser = args::time_from_zero)]
        until: f64,
        /// Frames per real second to step (1 to 1000; the lesson's
        /// time_scale applies).
        #[arg(long, default_value_t = 30.0, allow_negative_numbers = true, value_parser = args::fps)]
        fps: f64,
        /// Stop a hook that runs longer than this (s, up to 86400) with
        /// TimeoutError.
        #[arg(long, default_value_t = 10.0, allow_negative_numbers = true, value_parser = args::hook_limit)]
        hook_limit: f64,
        /// Address-space limit of each lesson's process, MiB.
        #[arg(long, default_value_t = lightcone::lesson::supervise::MEMORY_LIMIT_MB)]
        memory_limit: u64,
        /// Stop a lesson that has neither finished nor reached `--until`
        /// after this much real time (s, up to 86400): a lesson that
        /// slows time to nothing or restarts for ever.
        #[arg(long, default_value_t = 600.0, allow_negative_numbers = true, value_parser = args::hook_limit)]
        time_limit: f64,
        /// Internal: run the lesson in this process and report to the
        /// parent `lightcone lesson` (see lesson::supervise).
        #[arg(long, hide = true)]
        child: bool,
        /// Internal: run the lesson's hooks for the window `lightcone play`
        /// (see lesson::remote).
        #[arg(long, hide = true, conflicts_with = "child")]
        window_child: bool,
        /// Print the outcome as one JSON object (schema: docs/guide/src/lessons.md).
        #[arg(long)]
        json: bool,
    },
    /// Measure the engine and print the figures of BENCHMARKS.md.
    Bench {
        /// What to measure: `physics`.
        what: BenchWhat,
        /// Shorter runs (for a smoke test).
        #[arg(long)]
        quick: bool,
        /// Also write the optics accuracy table as CSV (for the plot).
        #[arg(long)]
        csv: Option<PathBuf>,
    },
}

/// How the pictures look: `play`, `render` and `record` take the same
/// flags.
#[derive(clap::Args)]
struct LookArgs {
    /// The view: `seen` (default: what the eye sees, the scene's
    /// effects), `truth` (board-simultaneous) or `split` (both).
    #[arg(long, value_enum)]
    view: Option<PlayView>,
    /// Show several pictures side by side, each its own view: a
    /// comma-separated list of `seen`, `truth` (through the eye looked
    /// through), `you` or an observer's name (what that eye sees), or
    /// `EYE:seen` / `EYE:truth`. E.g. `seen,truth` or `you,observer`.
    #[arg(long, conflicts_with = "view")]
    views: Option<String>,
    /// The camera straight above the table.
    #[arg(long)]
    top: bool,
    /// Effects shown: `scene` (default), `all`, `none`, or a
    /// comma-separated list, as for `observe`.
    #[arg(long)]
    effects: Option<String>,
}

impl LookArgs {
    /// The looks, looking through scene observer `observer` (by name).
    fn looks(self, observer: Option<String>) -> commands::looks::Looks {
        commands::looks::Looks {
            view: self.view.map(|v| match v {
                PlayView::Seen => lightcone::model::ViewMode::Seen,
                PlayView::Truth => lightcone::model::ViewMode::Truth,
                PlayView::Split => lightcone::model::ViewMode::Split,
            }),
            views: self.views,
            effects: self.effects,
            top: self.top,
            observer,
        }
    }
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum AxisArg {
    /// Board x (the long side).
    X,
    /// Board y.
    Y,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum BenchWhat {
    /// Frame times, collision rates, fixed-step comparison.
    Physics,
    /// Emission-solve accuracy and cost, solves per second, effect costs.
    Optics,
    /// Headless frames per second, CPU and GPU parts.
    Render,
    /// Tracker jitter with and without filtering; publish → update latency.
    Tracker,
}

/// The views `play --view` opens on.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
enum PlayView {
    Seen,
    Truth,
    Split,
}

/// Gives Mesa's device-select layer a private `XDG_RUNTIME_DIR` when the
/// environment has no valid one (see
/// [`lightcone_render::gpu::private_runtime_dir`]), so no GPU command prints
/// libwayland's `XDG_RUNTIME_DIR is invalid` warning.
fn private_runtime_dir() {
    if let Some(dir) = lightcone_render::gpu::private_runtime_dir() {
        // SAFETY: called first thing in `main`, before any thread exists,
        // so nothing reads the environment concurrently.
        unsafe { std::env::set_var("XDG_RUNTIME_DIR", &dir) };
    }
}

fn main() -> ExitCode {
    private_runtime_dir();
    interrupt::install();
    let cli = Cli::parse();
    match cli.command {
        Some(Command::Check { scenes }) => commands::check::run(&scenes),
        Some(Command::Link { scene, base }) => commands::link::run(&scene, &base),
        Some(Command::Simulate { scene, until, out }) => {
            commands::simulate::run(&scene, until, out.as_ref())
        }
        Some(Command::Observe {
            scene,
            at,
            observer,
            vertices,
            effects,
        }) => commands::observe::run_named(&scene, at, observer.as_deref(), vertices, &effects),
        Some(Command::Render {
            scene,
            at,
            observer,
            out,
            size,
            looks,
            no_overlays,
        }) => commands::render::run(commands::render::Request {
            path: &scene,
            at,
            out: &out,
            size: &size,
            looks: looks.looks(observer),
            overlays: overlays(no_overlays),
        }),
        Some(Command::Diagram {
            scene,
            at,
            observer,
            frame,
            axis,
            out,
            size,
        }) => commands::diagram::run(
            &scene,
            at,
            observer.as_deref(),
            frame.as_deref(),
            match axis {
                AxisArg::X => lightcone_render::diagram::Axis::X,
                AxisArg::Y => lightcone_render::diagram::Axis::Y,
            },
            &out,
            &size,
        ),
        Some(Command::Record {
            scene,
            until,
            fps,
            observer,
            out,
            size,
            looks,
            no_overlays,
        }) => commands::record::run(commands::record::Request {
            scene: &scene,
            until,
            fps,
            size: &size,
            looks: looks.looks(observer),
            overlays: overlays(no_overlays),
            out,
        }),
        Some(Command::Lesson {
            lessons,
            until,
            fps,
            hook_limit,
            memory_limit,
            time_limit,
            child,
            window_child,
            json,
        }) => commands::lesson::run(
            &lessons,
            commands::lesson::Options {
                until,
                fps,
                hook_limit,
                memory_limit,
                time_limit,
                child,
                window_child,
                json,
            },
        ),
        Some(Command::Bench { what, quick, csv }) => match what {
            BenchWhat::Physics => commands::bench::run(quick),
            BenchWhat::Optics => commands::bench_optics::run(quick, csv.as_ref()),
            BenchWhat::Render => commands::bench_render::run(quick),
            BenchWhat::Tracker => commands::bench_tracker::run(quick),
        },
        Some(Command::Play {
            scene,
            screenshot,
            frames,
            tracker,
            cave,
            at,
            looks,
            diagram,
            diagram_frame,
            serve,
            frame_log,
        }) => commands::play::run(
            scene.as_deref(),
            commands::play::Extras {
                screenshot,
                frames,
                tracker,
                cave,
                at,
                looks: looks.looks(None),
                diagram,
                diagram_frame,
                serve,
                frame_log,
            },
        ),
        Some(Command::Wall(args)) => commands::wall::run(&args),
        Some(Command::ClusterKey { cave, replace }) => commands::wall::keygen(&cave, replace),
        Some(Command::Tracker { args }) => commands::tracker::run(args),
        Some(Command::TrackerBridge { args }) => lightcone::tracker_bridge::child_main(&args),
        Some(Command::Cave {
            scene,
            config,
            out_dir,
            at,
            head,
            scale,
        }) => commands::cave::run(
            scene.as_deref(),
            config.as_deref(),
            &out_dir,
            at,
            head.as_deref(),
            scale,
        ),
        None => commands::play::run(None, commands::play::Extras::default()),
    }
}

/// `--no-overlays` as a slide's overlays.
fn overlays(none: bool) -> lightcone::play::slide::Overlays {
    if none {
        lightcone::play::slide::Overlays::Hidden
    } else {
        lightcone::play::slide::Overlays::Shown
    }
}
