//! Contacts per second of the event loop in a dense gas, one thread:
//! `cargo run --release -p lightcone-engine --example gas_rate -- N [CONTACTS] [MU_G] [UNTIL] [REPEAT]`
//! (β < 0.8, pucks 3R apart, elastic, c = 1.42: the gas of BENCHMARKS.md).
//! With `MU_G` (m/s², sliding friction μg; 1.96 is a cloth's μ = 0.2) every
//! worldline brakes, and the run stops at board time `UNTIL` (0.2 s unless
//! given) if it has not made `CONTACTS` by then (the gas of `lightcone
//! bench physics`'s friction table: at μg = 1.96 a puck at 0.8 c stops in
//! about 1 s). With `REPEAT`, the same gas is run that many times and the
//! rates are of them all (the state printed is the last run's, the same
//! as each's).

use std::time::Instant;

use lightcone_engine::physics::gas::dense_box;

fn main() {
    let mut args = std::env::args().skip(1);
    let n: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(10_000);
    let target: u64 = args
        .next()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1_000_000);
    let mu_g: f64 = args.next().and_then(|s| s.parse().ok()).unwrap_or(0.0);
    let until: f64 = args.next().and_then(|s| s.parse().ok()).unwrap_or(0.2);
    let repeat: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(1).max(1);
    let r = 0.0305;
    // The same gas run `repeat` times (each built anew, its building not
    // timed): a small gas's run is a few ms, shorter than this machine's
    // noise, and the sum of several is not.
    let (mut wall, mut cpu, mut built, mut contacts) = (0.0, 0.0, 0.0, 0);
    let mut last = None;
    for _ in 0..repeat {
        let build = Instant::now();
        let mut b = dense_box(n, r, 3.0 * r, 0.8, 1.42, 7);
        if mu_g > 0.0 {
            b.set_sliding_friction(mu_g);
        }
        b.set_recording(false);
        b.set_keep_history(false);
        built += build.elapsed().as_secs_f64();
        let start = Instant::now();
        let cpu0 = cpu_seconds();
        let mut t = 0.0;
        while b.stats().contacts() < target && (mu_g <= 0.0 || t < until) {
            t += 0.01;
            b.advance_to(t);
        }
        wall += start.elapsed().as_secs_f64();
        cpu += cpu_seconds() - cpu0;
        contacts += b.stats().contacts();
        last = Some(b);
    }
    let b = last.expect("at least one run");
    let c = contacts;
    let runs = if repeat > 1 {
        format!(" ({repeat} runs)")
    } else {
        String::new()
    };
    println!(
        "N = {n}: {c} contacts{runs} in {wall:.2} s wall, {cpu:.2} s CPU (build {built:.2} s): \
         {:.0} contacts/s ({:.0} per CPU second), {:.3} µs/contact; {:?}; state {:016x}",
        c as f64 / wall,
        c as f64 / cpu,
        wall / c as f64 * 1e6,
        b.stats(),
        fingerprint(&b)
    );
}

/// A hash of every bit of the final state (each puck's current segment's
/// start and proper velocity, its mass, the board time): equal before and
/// after a change of the loop that keeps the physics unchanged bit for bit.
fn fingerprint(b: &lightcone_engine::physics::Billiard) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    let mut eat = |x: f64| {
        for byte in x.to_bits().to_le_bytes() {
            h = (h ^ u64::from(byte)).wrapping_mul(0x100_0000_01b3);
        }
    };
    eat(b.time());
    for i in 0..b.len() {
        let s = b.worldline(i).last();
        eat(s.start.t);
        for x in s
            .start
            .position
            .to_array()
            .into_iter()
            .chain(s.u.0.to_array())
        {
            eat(x);
        }
        eat(b.mass(i));
    }
    h
}

/// This process's CPU time, s (Linux; 0 elsewhere): on a shared machine
/// it is steadier than the wall clock. From the scheduler's count in
/// nanoseconds (`/proc/self/schedstat`: the loop is one thread), where
/// `/proc/self/stat`'s ticks are 10 ms, a twentieth of a short run.
fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(0.0, |ns| ns * 1e-9)
}
