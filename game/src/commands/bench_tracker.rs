//! `lightcone bench tracker`: on-screen jitter from tracker noise, with and
//! without the One-Euro filter, and the publish → observer-update latency
//! between two processes. The figures of BENCHMARKS.md, "Tracker".

use std::process::{Command, ExitCode, Stdio};
use std::time::{Duration, Instant};

use glam::{DQuat, DVec3};
use lightcone_engine::scene::{self, Effects};
use lightcone_tracker::follow::{Follower, FollowerConfig};
use lightcone_tracker::motion::Prng;
use lightcone_tracker::{TrackerSample, latency_stats};

use crate::cave::TrackedHead;
use crate::model::GameState;

/// Pixels per radian of a 720-pixel-high picture with a 60° field of view.
const PX_PER_RAD: f64 = 720.0 / std::f64::consts::FRAC_PI_3;

/// One jitter measurement.
pub struct Jitter {
    /// RMS frame-to-frame change of the apparent-direction error, px.
    pub jitter_px: f64,
    /// Mean apparent-direction error, px (what filtering costs in lag).
    pub error_px: f64,
}

/// Apparent directions (unit vectors, observer's frame) of the pucks'
/// centres for an eye at `position` with velocity `v` (board frame).
fn directions(game: &mut GameState, position: DVec3, v: DVec3, effects: &Effects) -> Vec<DVec3> {
    // The game's own way of setting a tracked eye (capped below c).
    crate::cave::set_eye(game, position, v);
    game.effects = *effects;
    let view = game.run_seen();
    game.centres(view)
        .iter()
        .map(|c| c.seen.position.normalize_or_zero())
        .collect()
}

/// Simulates `seconds` of a head circling the table at `beta` with Gaussian
/// position noise `sigma` (m), tracked at `rate` Hz and drawn at 60 fps,
/// and measures the jitter of the pucks' apparent directions, filtered
/// (`filtered`: the Follower's One-Euro position and velocity) or raw
/// (last sample, finite-difference velocity).
pub fn jitter(beta: f64, sigma: f64, rate: f64, seconds: f64, filtered: bool) -> Jitter {
    let scene = match crate::assets::default_scene() {
        Ok(s) => s,
        Err(_) => scene::Scene::empty(glam::DVec2::new(2.84, 1.42), None)
            .unwrap_or_else(|_| unreachable!("a carom table is a valid scene")),
    };
    let mut game = GameState::new(scene);
    game.step(1.0);
    let c = game.scene.c;
    let effects = game.effects;
    // The observer circles the table's centre at 2 m, 0.9 m above the
    // cloth: its distance to the pucks stays the same at every speed.
    let centre = DVec3::new(1.42, 0.71, 0.9);
    let radius = 2.0;
    let omega = beta * c / radius;
    let path = |t: f64| {
        let a = omega * t;
        (
            centre + DVec3::new(a.cos(), a.sin(), 0.0) * radius,
            DVec3::new(-a.sin(), a.cos(), 0.0) * beta * c,
        )
    };
    let mut rng = Prng::new(42);
    let mut follower = Follower::new(FollowerConfig::default());
    let t0 = Instant::now();
    let base_ns = 1_000_000_000u64;
    let fps = 60.0;
    let (mut sample_t, mut seq) = (0.0, 0u64);
    let mut raw: Vec<(f64, DVec3)> = Vec::new();
    let (mut sum_j2, mut sum_e, mut n_j, mut n_e) = (0.0, 0.0, 0usize, 0usize);
    let mut last_err: Option<Vec<DVec3>> = None;
    let frames = (seconds * fps) as usize;
    for k in 1..=frames {
        let t = k as f64 / fps;
        // The tracker's samples up to this frame.
        while sample_t <= t {
            let truth = path(sample_t).0;
            let noise = DVec3::new(rng.gaussian(), rng.gaussian(), rng.gaussian()) * sigma;
            let p = truth + noise;
            seq += 1;
            let s = TrackerSample::new(
                base_ns + (sample_t * 1e9) as u64,
                seq,
                p,
                DQuat::IDENTITY,
                true,
            );
            follower.push(&s, t0 + Duration::from_secs_f64(sample_t));
            raw.push((sample_t, p));
            sample_t += 1.0 / rate;
        }
        let (p, v) = if filtered {
            let out = follower.output(t0 + Duration::from_secs_f64(t));
            match out.pose {
                Some(pose) => (pose.position, out.velocity),
                None => continue,
            }
        } else {
            let n = raw.len();
            if n < 2 {
                continue;
            }
            let ((ta, a), (tb, b)) = (raw[n - 2], raw[n - 1]);
            (b, (b - a) / (tb - ta))
        };
        // The truth at the newest sample's time (what a perfect tracker
        // would give with the same latency).
        let t_last = raw.last().map_or(0.0, |r| r.0);
        let (true_p, true_v) = path(t_last);
        let truth = directions(&mut game, true_p, true_v, &effects);
        let seen = directions(&mut game, p, v, &effects);
        let err: Vec<DVec3> = seen.iter().zip(&truth).map(|(s, t)| *s - *t).collect();
        for e in &err {
            sum_e += e.length() * PX_PER_RAD;
            n_e += 1;
        }
        if let Some(last) = &last_err
            && k > (fps as usize)
        {
            // Skip the first second: the filter settles.
            for (e, l) in err.iter().zip(last) {
                sum_j2 += ((*e - *l).length() * PX_PER_RAD).powi(2);
                n_j += 1;
            }
        }
        last_err = Some(err);
    }
    Jitter {
        jitter_px: (sum_j2 / n_j.max(1) as f64).sqrt(),
        error_px: sum_e / n_e.max(1) as f64,
    }
}

/// How the game side reads the tracker in [`latency`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reader {
    /// The game's way: a `tracker-bridge` child forwards over a pipe.
    Bridge,
    /// For comparison, what the game did before (and must not: random
    /// bytes in shared memory can crash the reader): iceoryx2 mapped in
    /// this process.
    InProcess,
}

/// Latency of one two-process run: a `lightcone tracker` child publishing
/// at `rate` Hz, this process polling every `poll` and updating a game's
/// observer (or, [`Reader::InProcess`], accepting samples into a
/// follower). Returns (p50, p99, max) in µs and the sample count.
pub fn latency(
    rate: f64,
    seconds: f64,
    poll: Duration,
    reader: Reader,
) -> Result<(f64, f64, f64, usize), String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let service = format!("lightcone/bench/{}", std::process::id());
    let mut child = Command::new(exe)
        .args([
            "tracker",
            "--service",
            &service,
            "--path",
            "circle",
            "--rate",
            &rate.to_string(),
            "--duration",
            &(seconds + 1.0).to_string(),
            "--quiet",
        ])
        .stdin(Stdio::null())
        .spawn()
        .map_err(|e| format!("cannot start the publisher: {e}"))?;
    let scene = scene::Scene::empty(glam::DVec2::new(2.84, 1.42), None)
        .unwrap_or_else(|_| unreachable!("a carom table is a valid scene"));
    let mut game = GameState::new(scene);
    let start = Instant::now();
    let latencies = match reader {
        Reader::Bridge => {
            let mut head = TrackedHead::new(&service, Default::default());
            while start.elapsed().as_secs_f64() < seconds + 0.5 {
                head.poll(Instant::now());
                head.drive(&mut game, DVec3::ZERO, DVec3::ZERO);
                std::thread::sleep(poll);
            }
            head.latencies().to_vec()
        }
        Reader::InProcess => {
            lightcone_tracker::transport::quiet_iceoryx_logs();
            let sub = lightcone_tracker::Subscriber::open(&service).map_err(|e| e.to_string())?;
            let mut follower = Follower::new(FollowerConfig::default());
            let (mut batch, mut l) = (Vec::new(), Vec::new());
            while start.elapsed().as_secs_f64() < seconds + 0.5 {
                batch.clear();
                sub.drain_into(&mut batch).map_err(|e| e.to_string())?;
                let now = Instant::now();
                for s in &batch {
                    if follower.push(s, now) == lightcone_tracker::follow::Verdict::Accepted {
                        l.push(lightcone_tracker::unix_now_ns().saturating_sub(s.timestamp_ns));
                    }
                }
                std::thread::sleep(poll);
            }
            l
        }
    };
    let _ = child.kill();
    let _ = child.wait();
    // Drop the first half second: process start-up.
    let skip = (rate * 0.5) as usize;
    let l: Vec<u64> = latencies.iter().skip(skip).copied().collect();
    let zeros = vec![0u64; l.len()];
    let stats = latency_stats(&zeros, &l).map_err(|e| e.to_string())?;
    let us = |ns: u64| ns as f64 / 1e3;
    Ok((
        us(stats.p50_ns),
        us(stats.p99_ns),
        us(stats.max_ns),
        l.len(),
    ))
}

/// Prints the tables.
pub fn run(quick: bool) -> ExitCode {
    let seconds = if quick { 3.0 } else { 20.0 };
    crate::sayln!(
        "## On-screen jitter (px at 720 px / 60°), tracker at 120 Hz, 60 fps, c = 1.42 m/s"
    );
    crate::sayln!();
    crate::sayln!(
        "| head noise σ | observer β | jitter raw | jitter filtered | mean error raw | mean error filtered |"
    );
    crate::sayln!("| --- | --- | --- | --- | --- | --- |");
    let sigmas: &[f64] = if quick {
        &[0.001]
    } else {
        &[0.0005, 0.001, 0.002]
    };
    let betas: &[f64] = if quick { &[0.5] } else { &[0.0, 0.5, 0.9] };
    let runs: &[(f64, u64)] = if quick {
        &[(1000.0, 50)]
    } else {
        &[(1000.0, 50), (1000.0, 0), (120.0, 50)]
    };
    let readers: &[Reader] = if quick {
        &[Reader::Bridge]
    } else {
        &[Reader::Bridge, Reader::InProcess]
    };
    let progress = crate::progress::steps(
        (sigmas.len() * betas.len() + runs.len() * readers.len()) as u64,
        "bench tracker",
    );
    for &sigma in sigmas {
        for &beta in betas {
            progress.step(&format!("jitter at σ = {:.1} mm, β = {beta}", sigma * 1e3));
            let raw = jitter(beta, sigma, 120.0, seconds, false);
            let filtered = jitter(beta, sigma, 120.0, seconds, true);
            progress.inc();
            progress.suspend(|| {
                crate::sayln!(
                    "| {:.1} mm | {beta:.1} | {:.2} | {:.3} | {:.2} | {:.2} |",
                    sigma * 1e3,
                    raw.jitter_px,
                    filtered.jitter_px,
                    raw.error_px,
                    filtered.error_px
                )
            });
        }
    }
    progress.suspend(|| {
        crate::sayln!();
        crate::sayln!("## Publish → observer update, two processes (µs)");
        crate::sayln!();
        crate::sayln!("| reader | tracker rate | poll period | samples | p50 | p99 | max |");
        crate::sayln!("| --- | --- | --- | --- | --- | --- | --- |");
    });
    for &reader in readers {
        for &(rate, poll_us) in runs {
            progress.step(&format!("latency at {rate:.0} Hz"));
            let measured = latency(
                rate,
                seconds.min(10.0),
                Duration::from_micros(poll_us),
                reader,
            );
            progress.inc();
            match measured {
                Ok((p50, p99, max, n)) => progress.suspend(|| {
                    crate::sayln!(
                        "| {} | {rate:.0} Hz | {} | {n} | {p50:.0} | {p99:.0} | {max:.0} |",
                        match reader {
                            Reader::Bridge => "bridge child",
                            Reader::InProcess => "in-process (before)",
                        },
                        if poll_us == 0 {
                            "busy spin".to_owned()
                        } else {
                            format!("{poll_us} µs")
                        }
                    )
                }),
                Err(e) => {
                    progress.finish();
                    crate::errln!("latency: {e}");
                    return ExitCode::FAILURE;
                }
            }
        }
    }
    progress.finish();
    ExitCode::SUCCESS
}
