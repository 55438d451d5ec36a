//! A clear start: with `before_start = "rest"` (the default) a puck rests
//! at its start position until it is struck at t = 0, so an observer sees
//! it at rest until light from the stroke arrives, d / c later; with
//! `"moving"` it was already moving and is seen behind its start.

use glam::DVec3;
use lightcone_engine::optics::emission;
use lightcone_engine::physics::Billiard;
use lightcone_engine::scene::{self, BeforeStart};
use lightcone_engine::spacetime::{Event, ProperVelocity};
use lightcone_engine::worldline::Rigid;

fn scene_text(before: &str) -> String {
    format!(
        r#"
c = 1.0
{before}
[table]
friction = 0.0
[[puck]]
name = "a"
position = [1.0, 0.7]
beta = [0.6, 0.0]
"#
    )
}

#[test]
fn a_puck_struck_at_zero_is_seen_at_rest_until_its_light_arrives() {
    let s = scene::parse(&scene_text(""), "rest.toml").unwrap();
    assert_eq!(s.before_start, BeforeStart::Rest);
    let b = Billiard::from_scene(&s);
    let start = DVec3::new(1.0, 0.7, 0.0);
    // An eye 1.5 m from the start: light from the stroke arrives at 1.5 s.
    let eye = start + DVec3::new(0.0, -1.2, 0.9);
    let d = eye.distance(start);
    assert!((d - 1.5).abs() < 1e-12);
    for t in [-2.0, 0.0, 0.5, 1.0, 1.49] {
        let e = emission::solve(b.worldline(0), DVec3::ZERO, &Rigid, Event::new(t, eye));
        assert_eq!(e.event.position, start, "at t = {t}");
        assert_eq!(e.u, ProperVelocity::ZERO, "at t = {t}");
        // Light travelled exactly from that event.
        assert!((c_dt(&e.event, t, eye) - 0.0).abs() < 1e-12);
    }
    // After its light arrives it is seen moving, ahead of its start.
    let e = emission::solve(b.worldline(0), DVec3::ZERO, &Rigid, Event::new(2.0, eye));
    assert!(e.event.t > 0.0 && e.event.position.x > start.x);
    assert!(e.u.0.x > 0.7);
    assert!(c_dt(&e.event, 2.0, eye).abs() < 1e-12);
    // Its clock, seen, stands still at rest before (board rate, negative
    // proper time) and the stroke happens at proper time 0.
    assert!((b.worldline(0).proper_time_at(-1.0) + 1.0).abs() < 1e-15);
    assert_eq!(b.worldline(0).proper_time_at(0.0), 0.0);
}

/// `c (t − tₑ) − |x − xₑ|` with c = 1: zero on the light cone.
fn c_dt(e: &Event, t: f64, eye: DVec3) -> f64 {
    (t - e.t) - eye.distance(e.position)
}

#[test]
fn moving_before_start_extends_the_first_motion_back() {
    let s = scene::parse(&scene_text("before_start = \"moving\""), "moving.toml").unwrap();
    assert_eq!(s.before_start, BeforeStart::Moving);
    let b = Billiard::from_scene(&s);
    let start = DVec3::new(1.0, 0.7, 0.0);
    let eye = start + DVec3::new(0.0, -1.2, 0.9);
    let e = emission::solve(b.worldline(0), DVec3::ZERO, &Rigid, Event::new(0.5, eye));
    assert!(e.event.t < 0.0 && e.event.position.x < start.x);
    assert!(c_dt(&e.event, 0.5, eye).abs() < 1e-12);
    // The position then is the back-extended line: x = 1 + 0.6 t.
    assert!((e.event.position.x - (1.0 + 0.6 * e.event.t)).abs() < 1e-12);
}

#[test]
fn a_bad_before_start_is_named() {
    let err = scene::parse(&scene_text("before_start = \"early\""), "bad.toml").unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.contains("bad.toml:3") && msg.contains("before_start"),
        "{msg}"
    );
    assert!(msg.contains("\"rest\" or \"moving\""), "{msg}");
}
