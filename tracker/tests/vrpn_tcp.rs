//! A VRPN server on loopback, as a CAVE's tracking PC runs one: the
//! recorded head track (`tests/tracks/dtrack_head.txt`, the head's pose in
//! each frame where it was tracked) is served as `vrpn_Tracker Pos_Quat`
//! reports of the device `Head`, mixed with another device's reports,
//! another sensor's, a report that is not finite and, half way, a header
//! whose length is impossible. The publisher (`--vrpn Head@…`, a child
//! process) sends the head's poses, in order, to the game side's
//! subscriber; refuses the bad report alone, with its content; on the
//! broken header drops the connection, says why, connects again, and
//! takes the rest from the server's new connection (whose ids differ).

use glam::{DQuat, DVec3};
use lightcone_tracker::follow::{Follower, TrackerStatus};
use lightcone_tracker::vrpn::{self, POS_QUAT, SENDER_DESCRIPTION, TYPE_DESCRIPTION};
use lightcone_tracker::{Subscriber, TrackerSample, dtrack};
use std::io::{Read, Write};
use std::net::{TcpListener, TcpStream};
use std::time::{Duration, Instant};

mod common;

/// The head's pose in each recorded frame where it was tracked.
fn recorded_head() -> Vec<(DVec3, DQuat)> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/tracks/dtrack_head.txt"
    );
    let text = std::fs::read_to_string(path).expect("recorded head track");
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .collect::<Vec<_>>()
        .join("\n")
        .split("\n--")
        .filter(|p| !p.trim().is_empty())
        .filter_map(|p| {
            let packet = dtrack::parse(p.trim().as_bytes()).expect("the recording parses");
            let b = packet.bodies.iter().find(|b| b.id == 0)?;
            Some((b.position, dtrack::quaternion(b.rotation)))
        })
        .collect()
}

/// Accepts one connection and does VRPN's handshake; `Head` is sender
/// `head`, the reports type `pos_quat`.
fn accept(listener: &TcpListener, head: i32, pos_quat: i32) -> TcpStream {
    // Within 10 s (a publisher that never connects fails the test, not
    // hangs it).
    listener.set_nonblocking(true).expect("non-blocking");
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut tcp = loop {
        match listener.accept() {
            Ok((tcp, _)) => break tcp,
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {
                assert!(Instant::now() < deadline, "the publisher never connected");
                std::thread::sleep(Duration::from_millis(10));
            }
            Err(e) => panic!("accept: {e}"),
        }
    };
    tcp.set_nonblocking(false).expect("blocking");
    tcp.write_all(&vrpn::cookie()).expect("cookie");
    let mut theirs = [0u8; vrpn::COOKIE_LEN];
    tcp.read_exact(&mut theirs).expect("the client's cookie");
    assert_eq!(vrpn::check_cookie(&theirs), Ok((7, 35)));
    let mut hello = Vec::new();
    hello.extend(vrpn::encode_description(
        SENDER_DESCRIPTION,
        head + 1,
        "Wand",
    ));
    hello.extend(vrpn::encode_description(SENDER_DESCRIPTION, head, "Head"));
    hello.extend(vrpn::encode_description(
        TYPE_DESCRIPTION,
        pos_quat,
        POS_QUAT,
    ));
    tcp.write_all(&hello).expect("descriptions");
    tcp
}

#[test]
fn vrpn_reports_reach_the_tracked_head_and_a_broken_stream_reconnects() {
    lightcone_tracker::transport::quiet_iceoryx_logs();
    let poses = recorded_head();
    assert!(poses.len() > 60, "{}", poses.len());
    let listener = TcpListener::bind("127.0.0.1:0").expect("listen");
    let port = listener.local_addr().expect("port").port();
    let (publisher, rx) = common::Publisher::spawn(
        "vrpn",
        &[
            "--vrpn",
            &format!("Head@127.0.0.1:{port}"),
            "--duration",
            "30",
        ],
    );
    let sub = Subscriber::open(&publisher.service).expect("open subscriber");

    // The server: the first half, a bad report at 10, a broken header at
    // the half; then, on the new connection (other ids), the rest.
    let half = poses.len() / 2;
    let served = poses.clone();
    let server = std::thread::spawn(move || {
        let report = |sensor: i32, (p, q): (DVec3, DQuat)| vrpn::encode_pos_quat(sensor, p, q);
        let mut tcp = accept(&listener, 0, 3);
        for (k, pose) in served[..half].iter().enumerate() {
            let mut out = Vec::new();
            out.extend(vrpn::encode(
                1,
                3,
                (k as i32, 0),
                &report(0, (DVec3::ONE, DQuat::IDENTITY)),
            ));
            out.extend(vrpn::encode(
                0,
                3,
                (k as i32, 1),
                &report(1, (DVec3::ZERO, DQuat::IDENTITY)),
            ));
            if k == 10 {
                let nan = report(0, (DVec3::new(0.5, f64::NAN, 1.5), DQuat::IDENTITY));
                out.extend(vrpn::encode(0, 3, (k as i32, 2), &nan));
            }
            out.extend(vrpn::encode(0, 3, (k as i32, 3), &report(0, *pose)));
            tcp.write_all(&out).expect("reports");
            std::thread::sleep(Duration::from_millis(2));
        }
        let mut broken = vrpn::encode(0, 3, (0, 0), &[]);
        broken[..4].copy_from_slice(&(1_000_000_000i32).to_be_bytes());
        tcp.write_all(&broken).expect("broken header");
        let mut tcp = accept(&listener, 6, 9);
        for (k, pose) in served[half..].iter().enumerate() {
            let out = vrpn::encode(6, 9, (k as i32, 0), &report(0, *pose));
            tcp.write_all(&out).expect("reports");
            std::thread::sleep(Duration::from_millis(2));
        }
        tcp // kept open until joined
    });

    let mut follower = Follower::default();
    let mut got: Vec<TrackerSample> = Vec::new();
    let deadline = Instant::now() + Duration::from_secs(15);
    while got.len() < poses.len() && Instant::now() < deadline {
        let now = Instant::now();
        for s in sub.drain().expect("drain").iter() {
            got.push(*s);
            follower.push(s, now);
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    let _open = server.join().expect("the server ran");
    assert_eq!(
        got.len(),
        poses.len(),
        "one sample per report of Head's sensor 0"
    );
    for (k, (s, (p, q))) in got.iter().zip(&poses).enumerate() {
        assert!(s.has_fix());
        assert_eq!(
            s.sequence as usize,
            k + 1,
            "one sequence over both connections"
        );
        assert!((s.position_vec() - *p).length() < 1e-12, "{k}");
        assert!(s.orientation_quat().dot(*q).abs() > 1.0 - 1e-12, "{k}");
    }
    assert_eq!(follower.status(Instant::now()), TrackerStatus::Live);

    drop(publisher);
    let mut lines = Vec::new();
    while let Ok(l) = rx.recv_timeout(Duration::from_millis(500)) {
        lines.push(l);
    }
    let has = |text: &str| lines.iter().filter(|l| l.contains(text)).count();
    assert_eq!(has("connected to VRPN 07.35"), 2, "{lines:#?}");
    assert_eq!(has("dropped a malformed VRPN report"), 1, "{lines:#?}");
    assert_eq!(
        has("Pos_Quat.position: [0.5, NaN, 1.5] is not finite"),
        1,
        "{lines:#?}"
    );
    assert_eq!(
        has("lost the framing: header.length: 1000000000 is not 24"),
        1,
        "{lines:#?}"
    );
    assert_eq!(has("connecting again in 1 s"), 1, "{lines:#?}");
}

/// A server that goes silent (its machine stopped: no reset reaches the
/// client) is taken as lost after 5 s, and connected to again.
#[test]
fn a_silent_vrpn_server_is_connected_to_again() {
    lightcone_tracker::transport::quiet_iceoryx_logs();
    let listener = TcpListener::bind("127.0.0.1:0").expect("listen");
    let port = listener.local_addr().expect("port").port();
    let (publisher, rx) = common::Publisher::spawn(
        "vrpn-silent",
        &[
            "--vrpn",
            &format!("Head@127.0.0.1:{port}"),
            "--duration",
            "20",
        ],
    );
    let _first = accept(&listener, 0, 3); // then nothing, socket open
    let started = Instant::now();
    let _second = accept(&listener, 0, 3);
    let waited = started.elapsed();
    assert!(
        waited >= Duration::from_secs(5) && waited < Duration::from_secs(9),
        "{waited:?}"
    );
    drop(publisher);
    let mut lines = Vec::new();
    while let Ok(l) = rx.recv_timeout(Duration::from_millis(500)) {
        lines.push(l);
    }
    assert!(
        lines
            .iter()
            .any(|l| l.contains("nothing from the server for 5 s; connecting again in 1 s")),
        "{lines:#?}"
    );
}

/// A hostile VRPN server: reports the guide says are dropped (a
/// position of 1e300 m and of 1e6 m, a zero quaternion, a non-finite one)
/// between good ones, then 10 000 sender descriptions with 32 kB names and
/// 10 000 with distinct 220-byte ones, then a good report. Only the good
/// reports reach the subscriber, each bad one is reported with its field
/// and content, and the publisher's memory stays within a few MB of what
/// it was before the flood (it grew by 317 MB when it kept every name).
#[cfg(target_os = "linux")]
#[test]
fn a_flooding_vrpn_server_neither_grows_the_tracker_nor_gets_bad_poses_through() {
    lightcone_tracker::transport::quiet_iceoryx_logs();
    let listener = TcpListener::bind("127.0.0.1:0").expect("listen");
    let port = listener.local_addr().expect("port").port();
    let (publisher, rx) = common::Publisher::spawn(
        "vrpn-flood",
        &[
            "--vrpn",
            &format!("Head@127.0.0.1:{port}"),
            "--duration",
            "60",
        ],
    );
    let sub = Subscriber::open(&publisher.service).expect("open subscriber");
    let good = |k: usize| {
        (
            DVec3::new(0.1 * k as f64, 1.7, -0.5),
            DQuat::from_rotation_y(0.1 * k as f64),
        )
    };
    let (go, flood) = std::sync::mpsc::channel::<()>();
    let server = std::thread::spawn(move || {
        let mut tcp = accept(&listener, 0, 3);
        let report =
            |(p, q): (DVec3, DQuat)| vrpn::encode(0, 3, (0, 0), &vrpn::encode_pos_quat(0, p, q));
        let zero = DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0);
        let nan = DQuat::from_xyzw(f64::NAN, 0.0, 0.0, 1.0);
        let mut out = report(good(0));
        for (k, bad) in [
            (DVec3::new(1e300, 0.0, 0.0), DQuat::IDENTITY),
            (DVec3::new(0.0, 1e6, 0.0), DQuat::IDENTITY),
            (DVec3::new(0.5, 1.7, 0.0), zero),
            (DVec3::new(0.5, 1.7, 0.0), nan),
        ]
        .into_iter()
        .enumerate()
        {
            out.extend(report(bad));
            out.extend(report(good(k + 1)));
        }
        tcp.write_all(&out).expect("reports");
        flood.recv().expect("go");
        let long = "n".repeat(32 * 1024);
        for id in 0..10_000 {
            tcp.write_all(&vrpn::encode_description(
                SENDER_DESCRIPTION,
                100 + id,
                &long,
            ))
            .expect("long description");
        }
        for id in 0..10_000 {
            let name = format!("Body{id:05}-{}", "m".repeat(210));
            tcp.write_all(&vrpn::encode_description(
                SENDER_DESCRIPTION,
                20_000 + id,
                &name,
            ))
            .expect("description");
        }
        tcp.write_all(&report(good(5))).expect("last report");
        tcp // kept open until joined
    });

    let mut got: Vec<TrackerSample> = Vec::new();
    let drain_until = |got: &mut Vec<TrackerSample>, n: usize| {
        let deadline = Instant::now() + Duration::from_secs(30);
        while got.len() < n && Instant::now() < deadline {
            got.extend(sub.drain().expect("drain").iter().copied());
            std::thread::sleep(Duration::from_millis(5));
        }
    };
    drain_until(&mut got, 5);
    assert_eq!(got.len(), 5, "the good reports before the flood");
    let before = publisher.resident_kb();
    go.send(()).expect("flood");
    drain_until(&mut got, 6);
    std::thread::sleep(Duration::from_millis(200));
    got.extend(sub.drain().expect("drain").iter().copied());
    let after = publisher.resident_kb();
    let _open = server.join().expect("the server ran");
    assert!(
        after < before + 16 * 1024,
        "the publisher grew from {before} kB to {after} kB"
    );
    if got.len() != 6 {
        drop(publisher);
        let lines: Vec<String> = rx.try_iter().collect();
        panic!("the good reports only: {got:?}\n{lines:#?}");
    }
    for (k, s) in got.iter().enumerate() {
        let (p, q) = good(k);
        assert!((s.position_vec() - p).length() < 1e-12, "{k}: {s:?}");
        assert!(s.orientation_quat().dot(q).abs() > 1.0 - 1e-12, "{k}");
    }

    drop(publisher);
    let mut lines = Vec::new();
    while let Ok(l) = rx.recv_timeout(Duration::from_millis(500)) {
        lines.push(l);
    }
    let has = |text: &str| lines.iter().filter(|l| l.contains(text)).count();
    for says in [
        "Pos_Quat.position: [1e300, 0.0, 0.0] m is beyond ±1 km",
        "Pos_Quat.position: [0.0, 1000000.0, 0.0] m is beyond ±1 km",
        "Pos_Quat.quaternion: (0.0, 0.0, 0.0, 0.0) is not a rotation",
        "Pos_Quat.quaternion: (NaN, 0.0, 0.0, 1.0) is not a rotation",
    ] {
        assert_eq!(
            has(&format!("dropped a malformed VRPN report: {says}")),
            1,
            "{says}: {lines:#?}"
        );
    }
    // The first 20 refusals one by one (4 reports, 16 descriptions), then
    // one line per 1000.
    assert_eq!(
        has("dropped a malformed VRPN description: description.name: 32768 bytes, longer than 255"),
        16,
        "{lines:#?}"
    );
    assert_eq!(
        has("malformed VRPN reports and descriptions dropped"),
        10,
        "{lines:#?}"
    );
    assert_eq!(has("lost the framing"), 0, "{lines:#?}");
}
