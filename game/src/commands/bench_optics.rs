//! `lightcone bench optics [--quick] [--csv FILE]`: what accuracy costs in
//! time and memory, for the exact emission solve and the paper's sampled
//! history, and what each effect costs in the frame schedule.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use glam::DVec3;
use lightcone_engine::ecs::frame_cost;
use lightcone_engine::optics::eye::Eye;
use lightcone_engine::optics::history::{SampledHistory, Search};
use lightcone_engine::optics::solve_rate::{BodyOutput, SolveRate};
use lightcone_engine::optics::view::{self, Method};
use lightcone_engine::optics::{Emission, mesh};
use lightcone_engine::physics::Billiard;
use lightcone_engine::scene::{Effects, Scene};
use lightcone_engine::spacetime::Event;
use lightcone_engine::worldline::mesh::PUCK_SEGMENTS;
use lightcone_engine::worldline::{RestShape, Worldline};

/// Bytes per vertex per frame of the paper's history table, from its
/// Table 1 (94.6 MB for 4 960 vertices × 1 000 events).
const PAPER_BYTES_PER_VERTEX_FRAME: f64 = 94.6e6 / (4960.0 * 1000.0);
/// Vertical field of view used to turn angles into pixels at 1080p.
const FOV: f64 = std::f64::consts::FRAC_PI_3;

struct Row {
    method: String,
    fps: f64,
    frames: usize,
    iterations: String,
    interpolate: bool,
    max_m: f64,
    mean_m: f64,
    max_px: f64,
    mean_px: f64,
    ns_per_vertex: f64,
    memory: f64,
    paper_memory: f64,
}

/// Runs the optics benchmarks.
pub fn run(quick: bool, csv: Option<&PathBuf>) -> ExitCode {
    let scene = match crate::assets::shipped_at("assets/scenes/paper_carom.toml") {
        Ok(s) => s,
        Err(e) => {
            crate::errln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let progress = crate::progress::steps(5, "bench optics");
    progress.step("accuracy of the emission solves");
    let rows = accuracy(&scene, quick);
    progress.inc();
    progress.suspend(|| print_rows(&rows));
    if let Some(path) = csv {
        let mut text = String::from(
            "method,fps,frames,iterations,interpolate,max_m,mean_m,max_px,mean_px,ns_per_vertex,memory_bytes\n",
        );
        for r in &rows {
            text += &format!(
                "{},{},{},{},{},{:e},{:e},{:e},{:e},{},{}\n",
                r.method,
                r.fps,
                r.frames,
                r.iterations,
                r.interpolate,
                r.max_m,
                r.mean_m,
                r.max_px,
                r.mean_px,
                r.ns_per_vertex,
                r.memory
            );
        }
        if let Err(e) = std::fs::write(path, text) {
            crate::errln!("{}: {e}", path.display());
            return ExitCode::FAILURE;
        }
    }
    progress.step("memory");
    let memory = memory_ten_pucks();
    progress.inc();
    progress.suspend(|| match memory {
        Ok(text) => crate::sayln!("{text}"),
        Err(e) => crate::errln!("{e}"),
    });
    progress.step("solves per second");
    let solves = throughput(quick);
    progress.inc();
    progress.suspend(|| crate::sayln!("{solves}"));
    progress.step("cost of each effect");
    let frames = if quick { 5 } else { 120 };
    let costs = frame_cost::effect_costs(if quick { 50 } else { 400 }, frames);
    progress.inc();
    progress.suspend(|| crate::sayln!("{costs}"));
    progress.step("frame time per number of views");
    let lanes = |n: usize| {
        let mut s = frame_cost::lanes(n);
        s.effects = Effects::default();
        s
    };
    let mut scenes = Vec::new();
    // The paper's scene as built in (whatever the working directory).
    if let Some(Ok(paper)) = crate::assets::shipped_scene("paper_carom.toml") {
        scenes.push(("paper_carom.toml", paper));
    }
    if quick {
        scenes.push(("100 pucks (lanes)", lanes(100)));
    } else {
        scenes.push(("1 000 pucks (lanes)", lanes(1000)));
        scenes.push(("10 000 pucks (lanes)", lanes(10_000)));
    }
    let views = frame_cost::view_counts(&scenes, if quick { 3 } else { 30 });
    progress.finish();
    crate::sayln!("{views}");
    ExitCode::SUCCESS
}

fn shapes_of(scene: &Scene) -> (Vec<RestShape>, Vec<f64>) {
    (
        scene
            .pucks
            .iter()
            .map(|p| mesh::puck(p.radius, p.height, PUCK_SEGMENTS))
            .collect(),
        scene.pucks.iter().map(|p| p.height).collect(),
    )
}

/// Apparent positions of every vertex of every puck for `eye`.
fn apparent(
    billiard: &Billiard,
    shapes: &[RestShape],
    eye: &Eye,
    method: Method,
    effects: &Effects,
    out: &mut Vec<DVec3>,
) {
    out.clear();
    let mut e: Vec<Emission> = Vec::new();
    let mut s = Vec::new();
    for (puck, shape) in shapes.iter().enumerate() {
        view::emissions(
            billiard,
            puck,
            &shape.vertices,
            eye,
            effects,
            method,
            &mut e,
        );
        view::seen(eye, billiard.c(), effects, &e, &mut s);
        out.extend(s.iter().map(|x| x.position));
    }
}

/// Table: error and cost of each emission method on the paper's scene.
fn accuracy(scene: &Scene, quick: bool) -> Vec<Row> {
    let (shapes, _) = shapes_of(scene);
    let vertices: usize = shapes.iter().map(|s| s.vertices.len()).sum();
    let observer = &scene.observers[0];
    let effects = Effects::default();
    let until = 20.0;
    let mut billiard = Billiard::from_scene(scene);
    billiard.advance_to(until);
    let times: Vec<f64> = (4..=(until as usize * 2)).map(|k| k as f64 * 0.5).collect();
    let eyes: Vec<Eye> = times
        .iter()
        .map(|&t| Eye {
            event: Event::new(t, observer.position + observer.u.velocity(scene.c) * t),
            u: observer.u,
        })
        .collect();
    let mut exact = Vec::new();
    let mut reference: Vec<Vec<DVec3>> = Vec::new();
    for eye in &eyes {
        apparent(&billiard, &shapes, eye, Method::Exact, &effects, &mut exact);
        reference.push(exact.clone());
    }
    let reps = if quick { 1 } else { 20 };
    let time_method = |method: Method| {
        let mut buf = Vec::new();
        let start = Instant::now();
        for _ in 0..reps {
            for eye in &eyes {
                apparent(&billiard, &shapes, eye, method, &effects, &mut buf);
            }
        }
        start.elapsed().as_secs_f64() * 1e9 / (reps * eyes.len() * vertices) as f64
    };
    let segments: usize = (0..billiard.len())
        .map(|i| billiard.worldline(i).segments().len())
        .sum();
    let mut rows = vec![Row {
        method: "exact".into(),
        fps: f64::NAN,
        frames: 0,
        iterations: "–".into(),
        interpolate: false,
        max_m: 0.0,
        mean_m: 0.0,
        max_px: 0.0,
        mean_px: 0.0,
        ns_per_vertex: time_method(Method::Exact),
        memory: (segments * std::mem::size_of::<lightcone_engine::worldline::Segment>()) as f64,
        paper_memory: f64::NAN,
    }];
    let settings: Vec<(f64, usize, u32, bool)> = {
        let mut v = Vec::new();
        for &fps in &[30.0, 60.0, 120.0] {
            for &interp in &[false, true] {
                v.push((fps, 1000, u32::MAX, interp));
            }
        }
        for &it in &[3u32, 6] {
            v.push((60.0, 1000, it, true));
        }
        v.push((60.0, 100, u32::MAX, true));
        v
    };
    for (fps, frames, iterations, interpolate) in settings {
        let mut history = SampledHistory::new(billiard.len(), frames);
        let worldlines: Vec<&Worldline> =
            (0..billiard.len()).map(|i| billiard.worldline(i)).collect();
        let search = Search {
            iterations,
            interpolate,
        };
        let (mut max_m, mut sum_m, mut max_px, mut sum_px, mut n) =
            (0.0f64, 0.0, 0.0f64, 0.0, 0usize);
        let mut next = 0.0;
        let mut frame = 0usize;
        let mut sampled = Vec::new();
        let mut elapsed = 0.0;
        for (k, eye) in eyes.iter().enumerate() {
            // Record frames up to the observation, as the game loop would.
            while next <= eye.event.t + 1e-12 {
                history.record(next, worldlines.iter().copied());
                frame += 1;
                next = frame as f64 / fps;
            }
            let start = Instant::now();
            apparent(
                &billiard,
                &shapes,
                eye,
                Method::Sampled(&history, search),
                &effects,
                &mut sampled,
            );
            elapsed += start.elapsed().as_secs_f64();
            for (a, b) in sampled.iter().zip(&reference[k]) {
                let m = (*a - *b).length();
                let angle = a.normalize().dot(b.normalize()).clamp(-1.0, 1.0).acos();
                let px = angle * 1080.0 / FOV;
                max_m = max_m.max(m);
                max_px = max_px.max(px);
                sum_m += m;
                sum_px += px;
                n += 1;
            }
        }
        rows.push(Row {
            method: "sampled".into(),
            fps,
            frames,
            iterations: if iterations == u32::MAX {
                "full".into()
            } else {
                iterations.to_string()
            },
            interpolate,
            max_m,
            mean_m: sum_m / n as f64,
            max_px,
            mean_px: sum_px / n as f64,
            ns_per_vertex: elapsed * 1e9 / (eyes.len() * vertices) as f64,
            memory: history.memory_bytes() as f64,
            paper_memory: PAPER_BYTES_PER_VERTEX_FRAME * (vertices * history.len()) as f64,
        });
    }
    rows
}

fn print_rows(rows: &[Row]) {
    crate::sayln!(
        "### Accuracy and cost of the emission solve: the paper's 3-puck scene\n\n\
         Observer \"eye\" at rest beside the table, observation every 0.5 s from 2 s to 20 s, every vertex of \
         the three pucks (48-segment meshes). Error: apparent position against the exact solve, in metres and \
         in pixels at 1080p (60° vertical field of view). Memory: the history held; for the sampled method \
         also what the paper's per-vertex table would take (its Table 1: 19 bytes per vertex per frame).\n\n\
         | method | samples/s | frames kept | dichotomy steps | interpolation | max error (m) | mean error (m) | max (px) | mean (px) | time per vertex (ns) | memory (bytes) | paper's layout (bytes) |\n\
         | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
    );
    for r in rows {
        crate::sayln!(
            "| {} | {} | {} | {} | {} | {:.2e} | {:.2e} | {:.3} | {:.3} | {:.1} | {:.0} | {} |",
            r.method,
            if r.fps.is_nan() {
                "–".into()
            } else {
                format!("{}", r.fps)
            },
            if r.frames == 0 {
                "–".into()
            } else {
                r.frames.to_string()
            },
            r.iterations,
            if r.method == "exact" {
                "–"
            } else if r.interpolate {
                "on"
            } else {
                "off"
            },
            r.max_m,
            r.mean_m,
            r.max_px,
            r.mean_px,
            r.ns_per_vertex,
            r.memory,
            if r.paper_memory.is_nan() {
                "–".into()
            } else {
                format!("{:.0}", r.paper_memory)
            }
        );
    }
    crate::sayln!();
}

/// History memory for the paper's 10-puck scene over 1 000 frames (its
/// Table 1 case).
fn memory_ten_pucks() -> Result<String, String> {
    let scene = crate::assets::shipped_at("assets/scenes/ten_pucks.toml")?;
    let (shapes, _) = shapes_of(&scene);
    let vertices: usize = shapes.iter().map(|s| s.vertices.len()).sum();
    let mut b = Billiard::from_scene(&scene);
    let mut history = SampledHistory::new(b.len(), 1000);
    for f in 1..=1000 {
        b.advance_to(f as f64 / 60.0);
        let w: Vec<&Worldline> = (0..b.len()).map(|i| b.worldline(i)).collect();
        history.record(f as f64 / 60.0, w);
    }
    let segments: usize = (0..b.len()).map(|i| b.worldline(i).segments().len()).sum();
    let exact = segments * std::mem::size_of::<lightcone_engine::worldline::Segment>();
    Ok(format!(
        "### History memory: the paper's 10-puck scene, 1 000 frames (its Table 1 case: 94.6 MB)\n\n\
         | what is kept | bytes |\n| --- | --- |\n\
         | exact: worldline segments ({segments} segments, {} collisions) | {exact} |\n\
         | sampled history, one centre and velocity per body per frame | {} |\n\
         | the paper's layout, every vertex every frame ({vertices} vertices × 1 000 × 19 B) | {:.0} |\n",
        b.stats().contacts(),
        history.memory_bytes(),
        PAPER_BYTES_PER_VERTEX_FRAME * vertices as f64 * 1000.0
    ))
}

/// Table: vertex solves per second at 10⁵–10⁶ vertices, 1 and 2 threads
/// ([`SolveRate`], the workload the `optics_rate` example and the
/// criterion bench run too).
fn throughput(quick: bool) -> String {
    let mut out = String::from(
        "### Exact emission solves per second\n\n\
         A gas of pucks (β < 0.8) run for 2 s of board time (so worldlines have kinks), observed from beside \
         the box; every vertex of every puck solved (emission event and apparent position, aberration on), \
         each puck's contracted shape kept from frame to frame as the schedule's kinematics phase keeps it \
         (built once, outside the timing). Two ways to keep the output (56 bytes of `Emission` and 40 of \
         `Seen` per vertex): each thread's arrays used for one body after another (in cache), or one pair \
         of arrays per body kept from frame to frame, as the frame pipeline's `Apparent` keeps them (every \
         frame writes all of them: 96 MB at 10⁶ vertices). Best of 5 runs each.\n\n\
         | pucks | vertices | threads | solves / s, arrays per thread | ns per vertex | solves / s, arrays per body |\n\
         | --- | --- | --- | --- | --- | --- |\n",
    );
    let configs: &[(usize, u32)] = if quick {
        &[(100, 48)]
    } else {
        &[(1000, 48), (1000, 512)]
    };
    for &(n, segments) in configs {
        let work = SolveRate::gas(n, segments);
        let vertices = work.vertices();
        let reps = if quick { 1 } else { 5 };
        // Best of `reps` runs of `run` (which returns the vertices solved).
        let best = |run: &mut dyn FnMut() -> usize| {
            (0..reps)
                .map(|_| {
                    let start = Instant::now();
                    let total = run();
                    total as f64 / start.elapsed().as_secs_f64()
                })
                .fold(0.0, f64::max)
        };
        let mut kept = vec![BodyOutput::default(); work.pucks()];
        for threads in [1, rayon::current_num_threads()] {
            let Ok(pool) = rayon::ThreadPoolBuilder::new().num_threads(threads).build() else {
                continue;
            };
            let (per_thread, per_body) = pool.install(|| {
                (
                    best(&mut || work.per_thread()),
                    best(&mut || work.per_body(&mut kept)),
                )
            });
            out += &format!(
                "| {n} | {vertices} | {threads} | {per_thread:.3e} | {:.1} | {per_body:.3e} |\n",
                1e9 / per_thread
            );
        }
    }
    out
}
