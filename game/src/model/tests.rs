//! The game's rules against closed forms and against the headless paths:
//! time and replay, strokes and thrust below c, a change of c, and the
//! pictures the window's views see.

use super::*;
use lightcone_engine::ecs::Apparent;
use lightcone_engine::scene::Effect;
use lightcone_render::frame::ViewKind;

fn game() -> GameState {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/paper_carom.toml");
    GameState::new(lightcone_engine::scene::load(&path).unwrap())
}

#[test]
fn time_runs_pauses_and_replays() {
    let mut g = game();
    g.step(0.5);
    g.time_scale = 2.0;
    g.step(0.5);
    assert!((g.live_time - 1.5).abs() < 1e-12);
    g.replay_to(0.4);
    assert!(g.paused && g.replaying());
    g.step(1.0);
    assert_eq!(g.view_time, 0.4); // paused
    g.paused = false;
    g.step(0.1);
    assert!((g.view_time - 0.6).abs() < 1e-12); // replay plays forward
    assert!((g.live_time - 1.5).abs() < 1e-12);
    g.go_live();
    assert!(!g.replaying());
}

#[test]
fn no_stroke_reaches_c_and_replays_refuse_strokes() {
    let mut g = game();
    let after = g.aim(1, DVec2::new(-1e9, 0.0));
    assert!(
        (after.speed_deficit() * 2.0 * after.0.length_squared() - 1.0).abs()
            < 1.0 / after.0.length_squared()
    ); // 1 − |β| ≈ 1/(2u²), to 3/(4u²)
    assert!((after.0.x - MAX_STROKE).abs() < 1e-12);
    g.strike().unwrap();
    g.step(0.1);
    assert!(g.physics().worldline(1).proper_velocity_at(g.live_time).0.x > 9.0);
    g.replay_to(0.05);
    g.aim(0, DVec2::new(1.0, 0.0));
    assert!(g.strike().is_err());
}

#[test]
fn thrust_never_reaches_c_and_flies_the_eye() {
    let mut g = game();
    for _ in 0..1000 {
        g.thrust(DVec3::new(1e6, 0.0, 0.0), DVec3::ZERO);
    }
    // Proper velocities add: u = 10⁹ along x, so β = u/√(1+u²) and
    // 1 − β = 1/(2u²) to first order (the speed deficit).
    let u = g.eye_velocity();
    assert_eq!(u.0, DVec3::new(1e9, 0.0, 0.0));
    assert!(
        (u.speed_deficit() * 2e18 - 1.0).abs() < 1e-6,
        "{}",
        u.speed_deficit()
    );
    g.halt();
    assert_eq!(g.eye_velocity(), ProperVelocity::ZERO);
}

#[test]
fn the_eye_the_window_uses_is_its_worldline_in_uniform_motion() {
    let mut g = game();
    let (x0, t0) = (g.eye_position(), g.live_time);
    // u = (0.6, 0, 0.8): |u| = 1, γ = √2, v = c u/γ.
    g.thrust(DVec3::new(0.6, 0.0, 0.8), DVec3::ZERO);
    let c = g.scene.c;
    let v = DVec3::new(0.6, 0.0, 0.8) * c / 2f64.sqrt();
    for _ in 0..30 {
        g.step(1.0 / 60.0);
        g.run_seen();
    }
    let t = g.live_time;
    let w = g.sim.observer_worldline(g.you).unwrap();
    // The eye's position and velocity are the worldline's event at the
    // live time, and that is uniform motion from the thrust on.
    assert_eq!(g.eye_position(), w.position_at(t));
    assert_eq!(g.eye_velocity(), w.proper_velocity_at(t));
    let want = x0 + v * (t - t0);
    assert!(
        (g.eye_position() - want).length() < 1e-12 * (1.0 + want.length()),
        "{} vs {want}",
        g.eye_position()
    );
    // The picture's eye is that event too.
    let eye = g.eye();
    assert_eq!(eye.event.t, t);
    assert!((eye.event.position - want).length() < 1e-12 * (1.0 + want.length()));
    assert!((eye.u.0 - DVec3::new(0.6, 0.0, 0.8)).length() < 1e-15);
    // Paused, a thrust is a step: a jump on the worldline, no velocity
    // change.
    g.paused = true;
    g.thrust(DVec3::X, DVec3::new(0.0, 0.5, 0.0));
    assert!((g.eye_position() - want - DVec3::new(0.0, 0.5, 0.0)).length() < 1e-9);
    assert_eq!(g.eye_velocity(), ProperVelocity(DVec3::new(0.6, 0.0, 0.8)));
}

#[test]
fn a_tracked_pose_puts_the_eye_on_its_worldline() {
    let mut g = game();
    g.step(0.25);
    let p = DVec3::new(1.0, -0.5, 1.2);
    // 0.5 m/s; capped at 0.99 c beyond.
    assert!(!crate::cave::set_eye(&mut g, p, DVec3::new(0.5, 0.0, 0.0)));
    assert_eq!(g.eye_position(), p);
    let v = g.eye_velocity().velocity(g.scene.c);
    assert!((v - DVec3::new(0.5, 0.0, 0.0)).length() < 1e-12);
    let w = g.sim.observer_worldline(g.you).unwrap();
    assert_eq!(w.state_at(g.live_time).position, p);
    // A second frame later the eye is where that velocity took it.
    g.step(0.1);
    let want = p + DVec3::new(0.05, 0.0, 0.0);
    assert!((g.eye_position() - want).length() < 1e-12);
}

#[test]
fn changing_c_keeps_each_pucks_proper_velocity_in_metres_per_second() {
    let mut g = game();
    let before: Vec<DVec3> = g.scene.pucks.iter().map(|p| p.u.0 * g.scene.c).collect();
    g.restart_with_c(1e6);
    for (p, b) in g.scene.pucks.iter().zip(&before) {
        assert!((p.u.0 * 1e6 - *b).length() < 1e-12 * (1.0 + b.length()));
    }
    // Slow light on the cloth: below √(R μ g) ≈ 0.245 m/s a puck would
    // not fit inside the braking's Rindler horizon; refused, with the
    // reason shown, and the game keeps its scene.
    g.restart_with_c(0.01);
    assert_eq!(g.scene.c, 1e6);
    assert!(g.message.contains("c must be above"), "{}", g.message);
    // Frictionless, slow light: the same momentum, never c.
    g.scene.table.friction = 0.0;
    g.restart_with_c(0.01);
    assert!(
        (g.scene.pucks[0].u.speed_deficit() * 2.0 * g.scene.pucks[0].u.0.length_squared() - 1.0)
            .abs()
            < 1.0 / g.scene.pucks[0].u.0.length_squared()
    ); // 1 − |β| ≈ 1/(2u²), to 3/(4u²)
    assert!((g.scene.pucks[0].u.0 * 0.01 - before[0]).length() < 1e-12);
}

#[test]
fn changing_c_restarts() {
    let mut g = game();
    g.step(1.0);
    g.restart_with_c(3.0);
    assert_eq!(g.physics().c(), 3.0);
    assert_eq!(g.live_time, 0.0);
    g.restart_with_c(-1.0);
    assert_eq!(g.physics().c(), 3.0);
    assert!(!g.message.is_empty());
}

/// The pictures of `a` and `b` agree to `tol` (m): same eye, same bodies,
/// every point seen at the same place.
fn same_picture(a: &Apparent, b: &Apparent, tol: f64) {
    let (ea, eb) = (a.eye.unwrap(), b.eye.unwrap());
    assert!((ea.event.position - eb.event.position).length() < tol);
    assert_eq!(ea.event.t, eb.event.t);
    assert_eq!(a.bodies.len(), b.bodies.len());
    for (x, y) in a.bodies.iter().zip(&b.bodies) {
        assert_eq!(x.body, y.body);
        assert_eq!(x.seen.len(), y.seen.len());
        for (p, q) in x.seen.iter().zip(&y.seen) {
            assert!(
                (p.position - q.position).length() < tol,
                "{:?}: {} vs {}",
                x.body,
                p.position,
                q.position
            );
            assert!((p.doppler - q.doppler).abs() < tol);
        }
        assert!((x.seen_proper_time - y.seen_proper_time).abs() < tol);
    }
}

#[test]
fn a_replay_shows_what_the_flying_eye_saw_then() {
    let mut g = game();
    for e in Effect::ALL {
        g.effects.set(e, true);
    }
    // Frames of 1/60 s; the eye thrusts, then is orbited (a jump).
    let frame = |g: &mut GameState| {
        g.step(1.0 / 60.0);
        g.run_seen()
    };
    for _ in 0..12 {
        g.thrust(DVec3::new(0.05, 0.02, 0.0), DVec3::ZERO);
        frame(&mut g);
    }
    let v = frame(&mut g);
    let t1 = g.live_time;
    let live = g.apparent(v).unwrap().clone();
    assert!(live.eye.unwrap().u.0.length() > 0.5);
    // The next thrust must come a frame later: a thrust at the live time
    // puts a kink at exactly t1, and at a kink the worldline gives the
    // later segment's velocity, which the picture taken at t1 (before
    // the thrust) did not have.
    frame(&mut g);
    for _ in 0..20 {
        g.thrust(DVec3::new(-0.04, 0.03, 0.01), DVec3::ZERO);
        frame(&mut g);
    }
    g.orbit(0.4, 0.1);
    for _ in 0..10 {
        frame(&mut g);
    }
    g.replay_to(t1);
    let v = g.run_seen();
    same_picture(&live, g.apparent(v).unwrap(), 1e-12);
    // Moving the eye during the replay watches the past from where it
    // now is ("replay and move"): another picture of the same time.
    g.thrust(DVec3::ZERO, DVec3::new(0.0, 0.0, 0.3));
    let v = g.run_seen();
    let moved = g.apparent(v).unwrap();
    assert!(g.replay_and_move);
    assert_eq!(moved.eye.unwrap().event.t, t1);
    assert!((moved.eye.unwrap().event.position - live.eye.unwrap().event.position).length() > 0.1);
    g.go_live();
    assert!(!g.replay_and_move);
}

#[test]
fn the_window_sees_what_headless_render_and_observe_see() {
    // The window's picture through the scene's observer, after a run of
    // frames, against a fresh simulation advanced straight to that time
    // (the path of `lightcone render` and `observe`).
    let mut g = game();
    g.observer = Some(0);
    for _ in 0..45 {
        g.step(1.0 / 60.0);
        g.run_seen();
    }
    let v = g.run_seen();
    let (sim, view) =
        lightcone_render::frame::scene_view(&g.scene, 0, g.view_time, ViewKind::Seen, 16.0 / 9.0);
    same_picture(g.apparent(v).unwrap(), sim.apparent(view).unwrap(), 1e-12);
}

#[test]
fn several_pictures_run_in_one_frame_each_with_its_eye_and_effects() {
    let mut g = game();
    g.panes = Some(Pane::parse_list("seen,truth,you:truth", &g.scene).unwrap());
    g.step(0.5);
    let panes: Vec<(Pane, f64)> = g.pane_list().into_iter().map(|p| (p, 1.0)).collect();
    let views = g.run_frame(&panes);
    assert_eq!(views.len(), 3);
    // The free eye looked through: "truth" and "you: truth" are one view.
    assert_eq!(views[1], views[2]);
    assert_eq!(g.view_effects(views[0]), g.effects);
    assert_eq!(g.view_effects(views[1]), ViewKind::Truth.effects(g.effects));
    assert!(Pane::parse_list("nobody", &g.scene).is_err());
    assert!(Pane::parse_list("you:sideways", &g.scene).is_err());
    // Fewer pictures drop the others' views.
    let one = g.run_frame(&panes[..1]);
    assert_eq!(g.sim.views(), &one[..]);
}

#[test]
fn the_truth_panes_clocks_read_each_pucks_proper_time_at_board_time() {
    // Frictionless: puck a moves at β = 0.8 (γ = 5/3) and has lived
    // τ = 0.6 t at board time t; puck b rests, τ = t. The truth pane shows
    // the board at t, so its clocks read these (the panel's proper times),
    // not board time for every puck.
    let text = "c = 1.42\n[table]\nfriction = 0\nsize = [20.0, 2.0]\n\
                [[puck]]\nname = \"a\"\nposition = [1.0, 0.5]\nbeta = [0.8, 0.0]\n\
                [[puck]]\nname = \"b\"\nposition = [1.0, 1.5]\n";
    let scene = lightcone_engine::scene::parse(text, "clocks.toml").expect("scene");
    let mut g = GameState::new(scene);
    g.panes = Some(Pane::parse_list("truth", &g.scene).unwrap());
    g.step(2.0);
    let t = g.view_time;
    assert!((t - 2.0).abs() < 1e-12);
    let views = g.run_frame(&[(g.pane_list()[0], 16.0 / 9.0)]);
    let centres = g.centres(views[0]);
    assert_eq!(centres.len(), 2);
    for c in &centres {
        let want = if c.puck == 0 { 0.6 * t } else { t };
        assert!(
            (c.clock - want).abs() < 1e-12 * t,
            "puck {}: truth clock {} against τ = {want}",
            c.puck,
            c.clock
        );
    }
}

#[test]
fn a_stroke_is_hinted_until_its_light_reaches_a_resting_eye() {
    let mut g = game();
    g.paused = false;
    g.effects.aberration = false;
    g.aim(1, DVec2::new(-0.2, 0.0));
    g.strike().unwrap();
    let s = g.last_stroke.expect("a stroke");
    let eye = g.eye().event.position;
    assert!(g.eye().u.0.length() < 1e-12, "the scene's eye rests");
    // Closed form for a resting eye: the light arrives at t_s + d / c.
    let arrival = s.t + (s.position - eye).length() / g.scene.c;
    let left = g.stroke_light_in().expect("light on its way");
    assert!((left - (arrival - g.view_time)).abs() < 1e-12);
    assert!(g.hints(&[]).iter().any(|h| h.contains("on its way")));
    g.step(arrival - g.view_time + 1e-6);
    assert_eq!(g.stroke_light_in(), None);
    assert!(g.hints(&[1.0]).is_empty());
    assert!(g.hints(&[-0.5])[0].contains("below 0 s"));
}
