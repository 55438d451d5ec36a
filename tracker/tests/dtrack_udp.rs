//! DTrack over UDP on loopback, as a CAVE's tracking PC would send it: a
//! recorded DTrack2 ASCII stream (`tests/tracks/dtrack_head.txt`) is sent
//! packet by packet to the publisher (`--dtrack-udp`, a child process),
//! with malformed packets mixed in. The head poses reach the game side's
//! subscriber and follower in order; frames where the head is not tracked
//! arrive without a fix (the pose held); every malformed packet is reported
//! with its content on stderr and dropped, and the stream goes on.

use lightcone_tracker::follow::{Follower, TrackerStatus};
use lightcone_tracker::{Subscriber, TrackerSample, dtrack};
use std::net::UdpSocket;
use std::time::{Duration, Instant};

mod common;

fn recorded_packets() -> Vec<String> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/tracks/dtrack_head.txt"
    );
    let text = std::fs::read_to_string(path).expect("recorded DTrack stream");
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .collect::<Vec<_>>()
        .join("\n")
        .split("\n--")
        .map(|p| p.trim().replace('\n', "\r\n") + "\r\n")
        .filter(|p| p.len() > 2)
        .collect()
}

#[test]
fn dtrack_packets_reach_the_tracked_head_and_bad_ones_are_reported() {
    lightcone_tracker::transport::quiet_iceoryx_logs();
    let packets = recorded_packets();
    assert_eq!(packets.len(), 120);
    let expected: Vec<dtrack::Packet> = packets
        .iter()
        .map(|p| dtrack::parse(p.as_bytes()).expect("the recording parses"))
        .collect();

    // A free port on loopback (bound, read, released).
    let port = UdpSocket::bind("127.0.0.1:0")
        .and_then(|s| s.local_addr())
        .expect("free port")
        .port();
    let (publisher, rx) = common::Publisher::spawn(
        "dtrack",
        &[
            "--dtrack-udp",
            &port.to_string(),
            "--dtrack-bind",
            "127.0.0.1",
            "--dtrack-body",
            "0",
            "--duration",
            "30",
        ],
    );
    let sub = Subscriber::open(&publisher.service).expect("open subscriber");
    let mut lines = Vec::new();
    let deadline = Instant::now() + Duration::from_secs(10);
    while !lines
        .iter()
        .any(|l: &String| l.contains("publishing DTrack"))
    {
        assert!(
            Instant::now() < deadline,
            "publisher never listened: {lines:?}"
        );
        if let Ok(l) = rx.recv_timeout(Duration::from_millis(100)) {
            lines.push(l);
        }
    }

    let malformed: [&[u8]; 3] = [
        b"fr 5\r\n6d 1 [0 1.000][1 2 nan 0 0 0][1 0 0 0 1 0 0 0 1]\r\n",
        b"GET / HTTP/1.1\r\n\r\n",
        b"\x00\x01\xfe\xff garbage",
    ];
    let sender = UdpSocket::bind("127.0.0.1:0").expect("sender");
    let target = ("127.0.0.1", port);
    let mut follower = Follower::default();
    let mut got: Vec<TrackerSample> = Vec::new();
    let drain = |follower: &mut Follower, got: &mut Vec<TrackerSample>| {
        let now = Instant::now();
        for s in sub.drain().expect("drain").iter() {
            got.push(*s);
            follower.push(s, now);
        }
    };
    for (k, p) in packets.iter().enumerate() {
        if k % 40 == 20 {
            sender.send_to(malformed[k / 40], target).expect("send");
        }
        sender.send_to(p.as_bytes(), target).expect("send");
        std::thread::sleep(Duration::from_millis(2));
        drain(&mut follower, &mut got);
    }
    let deadline = Instant::now() + Duration::from_secs(5);
    while got.len() < packets.len() && Instant::now() < deadline {
        drain(&mut follower, &mut got);
        std::thread::sleep(Duration::from_millis(5));
    }
    assert_eq!(got.len(), packets.len(), "every packet is one sample");
    for (s, p) in got.iter().zip(&expected) {
        assert_eq!(
            Some(s.sequence),
            p.frame,
            "DTrack's frame counter is the sequence"
        );
        match p.bodies.iter().find(|b| b.id == 0) {
            Some(b) => {
                assert!(s.has_fix());
                assert!((s.position_vec() - b.position).length() < 1e-12);
                let q = dtrack::quaternion(b.rotation);
                assert!(s.orientation_quat().dot(q).abs() > 1.0 - 1e-12);
            }
            // The head not tracked: no fix.
            None => assert!(!s.has_fix(), "frame {:?}", p.frame),
        }
    }
    // The follower took them as a live head, holding the pose while lost.
    assert_eq!(follower.status(Instant::now()), TrackerStatus::Live);
    let last = expected
        .last()
        .and_then(|p| p.bodies.first())
        .expect("last pose");
    let pose = follower.output(Instant::now()).pose.expect("a pose");
    assert!(
        (pose.raw_position - last.position).length() < 1e-12,
        "{pose:?}"
    );

    drop(publisher);
    while let Ok(l) = rx.recv_timeout(Duration::from_millis(500)) {
        lines.push(l);
    }
    let reports: Vec<&String> = lines
        .iter()
        .filter(|l| l.contains("dropped a malformed DTrack packet"))
        .collect();
    assert_eq!(reports.len(), 3, "{lines:#?}");
    assert!(
        reports[0].contains("body 0 sz: `nan` is not finite"),
        "{}",
        reports[0]
    );
    assert!(
        reports[0].contains("content: \"fr 5\\r\\n6d 1"),
        "{}",
        reports[0]
    );
    assert!(reports[1].contains("not a DTrack packet"), "{}", reports[1]);
    assert!(
        reports[1].contains("GET / HTTP/1.1\\r\\n"),
        "{}",
        reports[1]
    );
    assert!(reports[2].contains("not text"), "{}", reports[2]);
}
