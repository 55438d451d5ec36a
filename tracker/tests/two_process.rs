//! Two real processes: the simulated tracker publisher (a child process) and
//! this test as the game-side subscriber. Covers ordered delivery, latency,
//! a killed publisher (Stale then Lost while the pose is held) and a
//! publisher restarted under the same service name (Live again).

use lightcone_tracker::follow::{Follower, TrackerStatus};
use lightcone_tracker::latency::latency_stats;
use lightcone_tracker::{Subscriber, TrackerSample, unix_now_ns};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// Kills the child on drop so a failing assertion never leaks a publisher.
struct ChildGuard(Option<Child>);

impl ChildGuard {
    fn spawn(service: &str, first_seq: u64) -> Self {
        let child = Command::new(env!("CARGO_BIN_EXE_lightcone-tracker-publisher"))
            .args([
                "--service",
                service,
                "--rate",
                "1000",
                "--path",
                "circle",
                "--noise",
                "0.0005",
                "--first-seq",
                &first_seq.to_string(),
                "--duration",
                "30",
                "--quiet",
            ])
            .stdin(Stdio::null())
            .spawn()
            .expect("spawn publisher");
        Self(Some(child))
    }

    /// SIGKILL: the publisher gets no chance to clean up, like a crash.
    fn kill(&mut self) {
        if let Some(mut c) = self.0.take() {
            let _ = c.kill();
            let _ = c.wait();
        }
    }
}

impl Drop for ChildGuard {
    fn drop(&mut self) {
        self.kill();
    }
}

/// Drains into the follower; returns the received samples with receive
/// timestamps.
fn pump(sub: &Subscriber, follower: &mut Follower, log: &mut Vec<(TrackerSample, u64)>) {
    let batch = sub.drain().expect("drain");
    let rx = unix_now_ns();
    let now = Instant::now();
    for s in &batch {
        log.push((*s, rx));
        follower.push(s, now);
    }
}

/// Polls (~50 µs spin-sleep) until `cond` or `timeout`.
fn poll_until(
    sub: &Subscriber,
    follower: &mut Follower,
    log: &mut Vec<(TrackerSample, u64)>,
    timeout: Duration,
    mut cond: impl FnMut(&Follower, &[(TrackerSample, u64)]) -> bool,
) -> bool {
    let deadline = Instant::now() + timeout;
    while Instant::now() < deadline {
        pump(sub, follower, log);
        if cond(follower, log) {
            return true;
        }
        std::thread::sleep(Duration::from_micros(50));
    }
    false
}

#[test]
fn publisher_kill_and_restart_across_processes() {
    lightcone_tracker::transport::quiet_iceoryx_logs();
    let t_start = Instant::now();
    let service = format!(
        "lightcone/test/two_process/{}/{}",
        std::process::id(),
        unix_now_ns()
    );
    let sub = Subscriber::open(&service).expect("open subscriber");
    let mut follower = Follower::default();
    let mut log = Vec::new();

    // Phase 1: live stream.
    let mut p1 = ChildGuard::spawn(&service, 0);
    assert!(
        poll_until(
            &sub,
            &mut follower,
            &mut log,
            Duration::from_secs(10),
            |_, l| l.len() >= 300
        ),
        "received only {} samples",
        log.len()
    );
    let seqs: Vec<u64> = log.iter().map(|(s, _)| s.sequence).collect();
    assert!(
        seqs.windows(2).all(|w| w[1] > w[0]),
        "sequence not strictly increasing: {seqs:?}"
    );
    let gaps = seqs.windows(2).filter(|w| w[1] != w[0] + 1).count();
    assert_eq!(follower.status(Instant::now()), TrackerStatus::Live);
    assert_eq!(follower.stats().accepted as usize, log.len());

    // Latency: skip the first sample (history delivered on connect).
    let pairs = &log[1..];
    let publish: Vec<u64> = pairs.iter().map(|(s, _)| s.timestamp_ns).collect();
    let receive: Vec<u64> = pairs.iter().map(|(_, r)| *r).collect();
    let stats = latency_stats(&publish, &receive).expect("latency");
    println!(
        "publish->receive latency ({} samples, {gaps} gaps): {stats}",
        log.len()
    );
    println!(
        "latency_ns p50={} p99={} max={}",
        stats.p50_ns, stats.p99_ns, stats.max_ns
    );
    assert!(stats.p99_ns < 50_000_000, "p99 {stats}");

    // Phase 2: kill -9 the publisher; the follower must go Stale then Lost
    // while holding the last pose.
    p1.kill();
    let killed = Instant::now();
    // Drain anything still buffered from before the kill.
    pump(&sub, &mut follower, &mut log);
    let held = follower.output(Instant::now()).pose.expect("pose");
    let n_before = log.len();
    assert!(
        poll_until(
            &sub,
            &mut follower,
            &mut log,
            Duration::from_secs(2),
            |f, _| { f.status(Instant::now()) == TrackerStatus::Stale }
        ),
        "never went Stale"
    );
    let stale_after = killed.elapsed();
    assert_eq!(follower.output(Instant::now()).pose, Some(held));
    assert!(
        poll_until(
            &sub,
            &mut follower,
            &mut log,
            Duration::from_secs(3),
            |f, _| { f.status(Instant::now()) == TrackerStatus::Lost }
        ),
        "never went Lost"
    );
    let lost_after = killed.elapsed();
    let out = follower.output(Instant::now());
    assert_eq!(out.pose, Some(held));
    assert!(out.status_line().contains("LOST"), "{}", out.status_line());
    assert_eq!(log.len(), n_before, "no samples from a dead publisher");
    println!("stale after {stale_after:?}, lost after {lost_after:?}");
    // The SIGKILLed publisher's port is still registered until some node
    // runs dead-node cleanup; the game can trigger it when Lost.
    let before_cleanup = sub.publisher_count();
    let report = sub.cleanup_dead_nodes().expect("cleanup");
    println!(
        "publishers registered after kill: {before_cleanup}, after cleanup: {} ({report:?})",
        sub.publisher_count()
    );
    assert_eq!(sub.publisher_count(), 0);

    // Phase 3: a new publisher process on the same service name, sequence
    // back to 0: accepted as a restart, status Live again.
    let restart_at = Instant::now();
    let mut p2 = ChildGuard::spawn(&service, 0);
    assert!(
        poll_until(
            &sub,
            &mut follower,
            &mut log,
            Duration::from_secs(10),
            |f, l| { f.status(Instant::now()) == TrackerStatus::Live && l.len() >= n_before + 50 }
        ),
        "did not resume after restart"
    );
    println!("resumed {:?} after restart", restart_at.elapsed());
    let resumed = &log[n_before..];
    assert!(resumed[0].0.sequence < 50, "restart stream starts near 0");
    assert!(follower.stats().restarts >= 1, "{:?}", follower.stats());
    let new_pose = follower.output(Instant::now()).pose.expect("pose");
    assert_ne!(new_pose.sequence, held.sequence);
    assert!(new_pose.position.is_finite());
    assert_eq!(sub.publisher_count(), 1);
    p2.kill();
    println!("two_process test took {:?}", t_start.elapsed());
}

/// The subscriber joins after the publisher is already running, and the
/// publisher is then killed and replaced at once (faster than `stale_after`):
/// the sequence drop back to 0 with time moving on must be taken as a
/// restart, without ever reporting Lost.
#[test]
fn late_subscriber_and_immediate_restart() {
    lightcone_tracker::transport::quiet_iceoryx_logs();
    let service = format!(
        "lightcone/test/two_process_fast/{}/{}",
        std::process::id(),
        unix_now_ns()
    );
    let mut p1 = ChildGuard::spawn(&service, 0);
    std::thread::sleep(Duration::from_millis(300));
    let sub = Subscriber::open(&service).expect("open subscriber");
    let mut follower = Follower::default();
    let mut log = Vec::new();
    assert!(
        poll_until(
            &sub,
            &mut follower,
            &mut log,
            Duration::from_secs(10),
            |_, l| l.len() >= 100
        ),
        "late subscriber received only {} samples",
        log.len()
    );
    // Usually the first sample is the publisher's history slot (its latest
    // sample), so it is well past 0; not asserted, as a slow machine may
    // start the publisher late.
    println!(
        "late subscriber: first sequence received {}",
        log[0].0.sequence
    );
    let seqs: Vec<u64> = log.iter().map(|(s, _)| s.sequence).collect();
    assert!(seqs.windows(2).all(|w| w[1] > w[0]), "{seqs:?}");

    p1.kill();
    let mut p2 = ChildGuard::spawn(&service, 0);
    let n_before = log.len();
    let mut worst = TrackerStatus::Live;
    assert!(
        poll_until(
            &sub,
            &mut follower,
            &mut log,
            Duration::from_secs(10),
            |f, l| {
                let st = f.status(Instant::now());
                if st == TrackerStatus::Lost {
                    worst = st;
                }
                l.len() >= n_before + 50 && st == TrackerStatus::Live
            }
        ),
        "did not resume"
    );
    assert_ne!(worst, TrackerStatus::Lost);
    assert!(follower.stats().restarts >= 1, "{:?}", follower.stats());
    assert_eq!(follower.stats().out_of_order, 0, "{:?}", follower.stats());
    p2.kill();
}
