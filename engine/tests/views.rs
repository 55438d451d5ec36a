//! The frame schedule's views (issue 12): several views in one frame, each
//! effect's system running only for the views that have it, observers with
//! worldlines (replay shows what that observer saw then), and the
//! schedule's output equal to the composed optics to 1e-12.

use glam::DVec3;
use lightcone_engine::camera::{self, FIT_MARGIN};
use lightcone_engine::ecs::components::{BodyContraction, Mesh, ProperTime};
use lightcone_engine::ecs::{Apparent, BodyRef, Framing, Simulation, Vantage};
use lightcone_engine::optics::view::{Method, observe};
use lightcone_engine::report::ObserveReport;
use lightcone_engine::scene::{self, Effect, Effects, Scene};
use lightcone_engine::spacetime::ProperVelocity;
use lightcone_engine::worldline::mesh::{CUSHION_HEIGHT, CUSHION_WIDTH};
use lightcone_engine::worldline::{ContractedShape, SegmentShape};

/// Two fast pucks that collide, a moving observer.
const SCENE: &str = r#"
    [table]
    size = [2.84, 1.42]
    friction = 0.0
    [[puck]]
    name = "a"
    position = [0.6, 0.7]
    beta = [0.8, 0.1]
    [[puck]]
    name = "b"
    position = [2.0, 0.75]
    beta = [-0.6, 0.0]
    [[observer]]
    name = "eye"
    position = [1.42, -1.25, 1.6]
    look_at = [1.42, 0.71, 0.0]
    beta = [0.3, 0.2, 0.0]
"#;

fn scene() -> Scene {
    scene::parse(SCENE, "views.toml").unwrap()
}

fn with(effects: &[Effect]) -> Effects {
    let mut e = Effects::NONE;
    for &x in effects {
        e.set(x, true);
    }
    e
}

fn all() -> Effects {
    with(&Effect::ALL)
}

/// A simulation with two views of the scene's observer: `on` (every effect)
/// and `off` (every effect but `effect`).
fn pair(effect: Effect) -> (Simulation, Apparent, Apparent) {
    let mut sim = Simulation::new(&scene());
    let eye = sim.entity("eye").unwrap();
    let camera = Framing::default();
    let on = sim.add_view("on", eye, all(), camera, Vantage::OnWorldline);
    let mut fx = all();
    fx.set(effect, false);
    let off = sim.add_view("off", eye, fx, camera, Vantage::OnWorldline);
    // Long enough for the light seen to have left after the start.
    for f in 1..=60 {
        sim.advance_to(f64::from(f) * 0.05);
    }
    let a = sim.apparent(on).unwrap().clone();
    let b = sim.apparent(off).unwrap().clone();
    assert!(
        a.applied.is_on(effect),
        "{effect:?} ran for the view with it"
    );
    assert!(
        !b.applied.is_on(effect),
        "{effect:?} did not run for the view without it"
    );
    (sim, a, b)
}

#[test]
fn light_delay_runs_only_for_views_with_it() {
    let (sim, on, off) = pair(Effect::LightDelay);
    let t = sim.time();
    for b in &off.bodies {
        assert!(b.emissions.iter().all(|e| e.event.t == t));
    }
    assert!(on.bodies[0].emissions.iter().all(|e| e.event.t < t));
}

#[test]
fn aberration_runs_only_for_views_with_it() {
    let (_, on, off) = pair(Effect::Aberration);
    let eye = off.eye.unwrap();
    for b in &off.bodies {
        for (e, s) in b.emissions.iter().zip(&b.seen) {
            assert_eq!(s.position, e.event.position - eye.event.position);
        }
    }
    // The moving eye sees the aberrated directions elsewhere.
    let (a, b) = (&on.bodies[0].seen[0], &off.bodies[0].seen[0]);
    assert!((a.direction() - b.direction()).length() > 1e-3);
}

#[test]
fn doppler_runs_only_for_views_with_it() {
    let (_, on, off) = pair(Effect::Doppler);
    assert!(
        off.bodies
            .iter()
            .flat_map(|b| &b.seen)
            .all(|s| s.doppler == 1.0)
    );
    assert!(
        on.bodies[0]
            .seen
            .iter()
            .any(|s| (s.doppler - 1.0).abs() > 1e-3)
    );
}

#[test]
fn searchlight_runs_only_for_views_with_it() {
    let (_, on, off) = pair(Effect::Searchlight);
    assert!(
        off.bodies
            .iter()
            .flat_map(|b| &b.intensity)
            .all(|&i| i == 1.0)
    );
    // D⁴ of the view with both doppler and searchlight.
    for b in &on.bodies {
        for (s, i) in b.seen.iter().zip(&b.intensity) {
            assert!((i - s.doppler.powi(4)).abs() <= 1e-12 * i);
        }
    }
}

#[test]
fn time_dilation_runs_only_for_views_with_it() {
    let (sim, on, off) = pair(Effect::TimeDilation);
    for b in &off.bodies {
        assert_eq!(b.seen_proper_time, b.emissions[b.centre()].event.t);
    }
    // With it: the proper time at the centre's emission (γ > 1: behind).
    let b = &on.bodies[0];
    let w = sim.physics().worldline(0);
    let te = b.emissions[b.centre()].event.t;
    assert_eq!(b.seen_proper_time, w.proper_time_at(te));
    assert!(b.seen_proper_time < te);
}

#[test]
fn contraction_runs_only_for_views_with_it() {
    let (mut sim, on, off) = pair(Effect::Contraction);
    assert_ne!(on.bodies[0].emissions, off.bodies[0].emissions);
    // Measured on board-simultaneous views (no light delay): the extent of
    // puck "a" along its motion, from its centre.
    let eye = sim.entity("eye").unwrap();
    let camera = Framing::default();
    let rigid = sim.add_view("rigid", eye, Effects::NONE, camera, Vantage::OnWorldline);
    let contracted = sim.add_view(
        "contracted",
        eye,
        with(&[Effect::Contraction]),
        camera,
        Vantage::OnWorldline,
    );
    sim.advance_to(0.1); // before any collision
    let extent = |a: &Apparent| {
        let b = &a.bodies[0];
        let c = b.emissions[b.centre()].event.position;
        b.emissions[..b.vertex_count()]
            .iter()
            .map(|e| {
                (e.event.position - c)
                    .dot(DVec3::new(0.8, 0.1, 0.0).normalize())
                    .abs()
            })
            .fold(0.0, f64::max)
    };
    let r = sim.physics().radius(0);
    let gamma = ProperVelocity::try_from_beta(DVec3::new(0.8, 0.1, 0.0))
        .unwrap()
        .gamma();
    let rigid_view = sim.apparent(rigid).unwrap();
    assert!(!rigid_view.applied.contraction);
    let rigid_extent = extent(rigid_view);
    assert!(rigid_extent <= r * (1.0 + 1e-12) && rigid_extent > 0.99 * r);
    let contracted_view = sim.apparent(contracted).unwrap();
    assert!(contracted_view.applied.contraction);
    assert!((extent(contracted_view) * gamma / rigid_extent - 1.0).abs() < 1e-12);
}

#[test]
fn a_system_no_view_needs_is_not_in_the_frame() {
    // Only a truth view: the kinematics of time dilation and contraction
    // never run, nor do the optics of the effects.
    let mut s = scene();
    s.effects = Effects::NONE;
    let mut sim = Simulation::new(&s);
    for f in 1..=10 {
        sim.advance_to(f64::from(f) * 0.1);
    }
    let a = sim.entity("a").unwrap();
    assert_eq!(sim.world.get::<ProperTime>(a).unwrap().0, 0.0);
    assert!(
        sim.world
            .get::<BodyContraction>(a)
            .unwrap()
            .0
            .maps()
            .is_empty()
    );
    let view = sim.view("eye").unwrap();
    assert_eq!(sim.apparent(view).unwrap().applied, Effects::NONE);
    // Turned on for the view, they run from the next frame on.
    sim.set_view_effect(view, Effect::TimeDilation, true);
    sim.set_view_effect(view, Effect::Contraction, true);
    sim.advance_to(1.1);
    assert!(sim.world.get::<ProperTime>(a).unwrap().0 > 0.0);
    assert_eq!(
        sim.world.get::<BodyContraction>(a).unwrap().0.maps().len(),
        sim.physics().worldline(0).segments().len()
    );
}

/// The contraction system (kinematics: each body's contracted shape along
/// its worldline) does not run for a view without contraction: with no
/// such view it is not in the frame (the shapes stay empty); with one, the
/// views without it see what they saw before, bit for bit, the rest shape.
#[test]
fn the_contraction_system_does_not_run_for_a_view_without_contraction() {
    let mut s = scene();
    s.effects = Effects::NONE;
    s.effects.light_delay = true;
    s.effects.aberration = true;
    let run = |sim: &mut Simulation| {
        for f in 1..=40 {
            sim.advance_to(f64::from(f) * 0.05);
        }
    };
    let mut alone = Simulation::new(&s);
    run(&mut alone);
    let a = alone.entity("a").unwrap();
    // Puck "a" collided: several segments, none of them mapped.
    assert!(alone.physics().worldline(0).segments().len() > 1);
    assert!(
        alone
            .world
            .get::<BodyContraction>(a)
            .unwrap()
            .0
            .maps()
            .is_empty()
    );
    let view = alone.view("eye").unwrap();
    assert!(!alone.apparent(view).unwrap().applied.contraction);
    // The same run with a second, contracted view of the same eye.
    let mut both = Simulation::new(&s);
    let eye = both.entity("eye").unwrap();
    let mut fx = s.effects;
    fx.contraction = true;
    let contracted = both.add_view(
        "contracted",
        eye,
        fx,
        Framing::default(),
        Vantage::OnWorldline,
    );
    run(&mut both);
    let a = both.entity("a").unwrap();
    let w = both.physics().worldline(0);
    let maps = both
        .world
        .get::<BodyContraction>(a)
        .unwrap()
        .0
        .maps()
        .to_vec();
    assert_eq!(maps.len(), w.segments().len());
    for (m, seg) in maps.iter().zip(w.segments()) {
        assert_eq!(*m, SegmentShape::contracted(seg));
    }
    assert!(both.apparent(contracted).unwrap().applied.contraction);
    let rigid = both.apparent(both.view("eye").unwrap()).unwrap();
    assert!(!rigid.applied.contraction);
    assert_eq!(rigid, alone.apparent(view).unwrap());
    assert_ne!(
        rigid.bodies[0].emissions,
        both.apparent(contracted).unwrap().bodies[0].emissions
    );
    // Another run of the scene put in place: its shapes are built afresh.
    let mut other = lightcone_engine::physics::Billiard::from_scene(&s);
    other.advance_to(1.5);
    both.replace_physics(other);
    both.advance_to(1.5);
    let w = both.physics().worldline(0);
    let maps = both.world.get::<BodyContraction>(a).unwrap().0.maps();
    assert_eq!(maps, ContractedShape::of(w).maps());
}

#[test]
fn the_schedule_equals_the_composed_optics_to_1e_12() {
    let s = scene();
    let mut sim = Simulation::new(&s);
    let view = sim.view("eye").unwrap();
    let shapes: Vec<_> = (0..2)
        .map(|i| {
            let e = sim.entity(&s.pucks[i].name).unwrap();
            sim.world.get::<Mesh>(e).unwrap().shape.clone()
        })
        .collect();
    let heights: Vec<f64> = s.pucks.iter().map(|p| p.height).collect();
    let fx_sets = [
        Effects::NONE,
        s.effects,
        all(),
        with(&[Effect::LightDelay, Effect::Doppler]),
        with(&[
            Effect::Aberration,
            Effect::Searchlight,
            Effect::TimeDilation,
        ]),
    ];
    for (k, fx) in fx_sets.into_iter().enumerate() {
        for e in Effect::ALL {
            sim.set_view_effect(view, e, fx.is_on(e));
        }
        let t = 0.4 + 0.5 * k as f64;
        sim.advance_to(t);
        let a = sim.apparent(view).unwrap();
        let eye = a.eye.unwrap();
        let reference = observe(
            sim.physics(),
            &shapes,
            &heights,
            eye,
            fx,
            Method::Exact,
            true,
        );
        for (b, r) in a.bodies.iter().zip(&reference.bodies) {
            assert_eq!(b.body, BodyRef::Puck(r.puck));
            assert_eq!(b.vertex_count(), r.vertices.len());
            let points = r.vertices.iter().chain(std::iter::once(&r.centre));
            for (i, p) in points.enumerate() {
                let close = |x: DVec3, y: DVec3| (x - y).length() <= 1e-12 * (1.0 + y.length());
                assert!(close(
                    b.emissions[i].event.position,
                    p.emission.event.position
                ));
                assert!((b.emissions[i].event.t - p.emission.event.t).abs() <= 1e-12);
                assert!(close(b.seen[i].position, p.seen.position), "{fx:?}");
                assert!((b.seen[i].doppler - p.seen.doppler).abs() <= 1e-12 * p.seen.doppler);
                assert!((b.intensity[i] - p.intensity).abs() <= 1e-12 * p.intensity);
            }
            assert!((b.seen_proper_time - r.seen_proper_time).abs() <= 1e-12);
        }
        // The report built from the view lists the same numbers.
        let report = ObserveReport::of_view(&sim, view, false).unwrap();
        assert_eq!(report.pucks.len(), 2);
        assert_eq!(
            report.pucks[0].seen_proper_time,
            a.bodies[0].seen_proper_time
        );
    }
}

#[test]
fn the_table_is_seen_like_any_resting_body() {
    let mut sim = Simulation::new(&scene());
    sim.advance_to(0.7);
    let view = sim.view("eye").unwrap();
    let a = sim.apparent(view).unwrap();
    let eye = a.eye.unwrap();
    let c = sim.c();
    let fixtures: Vec<_> = a
        .bodies
        .iter()
        .filter(|b| matches!(b.body, BodyRef::Fixture(_)))
        .collect();
    assert_eq!(fixtures.len(), 6); // cloth, four cushions, framing marks
    for b in fixtures {
        for (e, s) in b.emissions.iter().zip(&b.seen) {
            let expected = eye.see_static(e.event.position, c, true);
            assert!((s.position - expected.position).length() < 1e-12);
        }
    }
}

#[test]
fn two_views_of_one_frame_seen_and_truth() {
    let mut sim = Simulation::new(&scene());
    let eye = sim.entity("eye").unwrap();
    let truth = sim.add_view(
        "eye: truth",
        eye,
        with(&[Effect::Contraction]),
        Framing::default(),
        Vantage::OnWorldline,
    );
    sim.advance_to(1.0);
    let seen = sim.apparent(sim.view("eye").unwrap()).unwrap();
    let truth = sim.apparent(truth).unwrap();
    assert_eq!(seen.eye, truth.eye);
    assert!(truth.bodies[0].emissions.iter().all(|e| e.event.t == 1.0));
    assert!(seen.bodies[0].emissions.iter().all(|e| e.event.t < 1.0));
}

/// An observer that flew during the run: a replay at time t shows exactly
/// what it saw live at t; "replay and move" shows the past from where it
/// is now instead.
#[test]
fn replay_shows_what_the_flying_observer_saw_then() {
    let mut sim = Simulation::new(&scene());
    let eye = sim.entity("eye").unwrap();
    let view = sim.view("eye").unwrap();
    let mut live = Vec::new();
    for f in 1..=120 {
        let t = f64::from(f) / 60.0;
        // Thrust every half second: a kink on the eye's worldline.
        if f % 30 == 0 {
            let u = ProperVelocity::try_from_beta(DVec3::new(-0.2 * f64::from(f / 30), 0.4, 0.1))
                .unwrap();
            sim.steer_observer(eye, t, u).unwrap();
        }
        sim.advance_to(t);
        if f % 20 == 5 {
            live.push((t, sim.apparent(view).unwrap().clone()));
        }
    }
    assert!(sim.observer_worldline(eye).unwrap().segments().len() >= 4);
    for (t, then) in &live {
        sim.advance_to(*t);
        assert_eq!(sim.apparent(view).unwrap(), then, "replay at {t}");
    }
    // The second mode: the same past light from the eye's state now.
    let now = 2.0;
    sim.set_vantage(view, Vantage::ReplayAndMove { now });
    let (t, then) = &live[0];
    sim.advance_to(*t);
    let moved = sim.apparent(view).unwrap();
    let eye_now = sim.observer_worldline(eye).unwrap().state_at(now);
    assert_eq!(moved.eye.unwrap().event.position, eye_now.position);
    assert_eq!(moved.eye.unwrap().u, eye_now.u);
    assert_eq!(moved.eye.unwrap().event.t, *t);
    assert_ne!(moved, then);
}

#[test]
fn a_tracked_head_follows_its_samples() {
    let mut sim = Simulation::new(&scene());
    let eye = sim.entity("eye").unwrap();
    let start = sim.observer_worldline(eye).unwrap().position_at(0.0);
    let dt = 1.0 / 90.0;
    // The head moves 0.2 m/s along y (slow): the worldline follows one
    // sample behind.
    let head = |t: f64| start + DVec3::new(0.0, 0.2 * t, 0.0);
    for k in 0..=90 {
        let t = f64::from(k) * dt;
        sim.follow_observer(eye, t, head(t), dt).unwrap();
        sim.advance_to(t);
    }
    let w = sim.observer_worldline(eye).unwrap();
    let t = 89.0 * dt;
    assert!((w.position_at(t + dt) - head(t)).length() < 1e-9);
}

#[test]
fn the_sampled_history_is_recorded_only_when_the_scene_asks() {
    use lightcone_engine::ecs::resources::History;
    let exact = Simulation::new(&scene());
    assert!(exact.world.get_resource::<History>().is_none());
    let text = format!("{SCENE}\n[optics]\nmethod = \"sampled\"\nhistory_frames = 500\n");
    let mut sim = Simulation::new(&scene::parse(&text, "sampled.toml").unwrap());
    for f in 1..=180 {
        sim.advance_to(f64::from(f) / 60.0);
    }
    assert_eq!(sim.world.resource::<History>().0.len(), 181);
    // The sampled view is close to the exact one (interpolated, 60/s).
    let mut exact = exact;
    exact.advance_to(3.0);
    let sampled = sim.apparent(sim.view("eye").unwrap()).unwrap();
    let reference = exact.apparent(exact.view("eye").unwrap()).unwrap();
    for (a, b) in sampled.bodies[0]
        .emissions
        .iter()
        .zip(&reference.bodies[0].emissions)
    {
        assert!((a.event.position - b.event.position).length() < 1e-3);
    }
}

/// The fitted camera of a view is the window's: the table's corners as the
/// eye sees them (`see_static`, with or without aberration), fitted.
#[test]
fn a_fitted_view_frames_the_table_as_the_window_does() {
    let mut sim = Simulation::new(&scene());
    let view = sim.view("eye").unwrap();
    for (aberration, aspect, zoom) in [(true, 1.6, 1.0), (false, 0.8, 2.0)] {
        sim.set_view_effect(view, Effect::Aberration, aberration);
        sim.set_framing(
            view,
            Framing::Fit {
                aspect,
                zoom,
                follow: None,
            },
        );
        sim.advance_to(0.9);
        let eye = sim.apparent(view).unwrap().eye.unwrap();
        let size = sim.table_size();
        let points: Vec<DVec3> = camera::table_corners(size, CUSHION_HEIGHT, CUSHION_WIDTH)
            .into_iter()
            .map(|p| eye.see_static(p, sim.c(), aberration).position)
            .collect();
        let expected = camera::fit(&points, aspect, FIT_MARGIN, zoom);
        let got = sim.camera(view).unwrap();
        assert!((got.forward - expected.forward).length() < 1e-12);
        assert!((got.fovy - expected.fovy).abs() < 1e-12);
    }
    // Following puck "b": its apparent centre in the middle.
    sim.set_framing(
        view,
        Framing::Fit {
            aspect: 1.0,
            zoom: 1.0,
            follow: Some(1),
        },
    );
    sim.advance_to(1.0);
    let a = sim.apparent(view).unwrap();
    let b = &a.bodies[1];
    let dir = b.seen[b.centre()].direction();
    assert!((sim.camera(view).unwrap().forward - dir).length() < 1e-12);
}

/// The seen trails read a view's history: at each past time, the point the
/// view's frame showed then (the observer flew meanwhile), for each effect
/// set the trail's kernels depend on, to 1e-12.
#[test]
fn a_views_seen_history_is_what_its_frames_showed() {
    let fx_sets = [
        all(),
        Effects::NONE,
        with(&[Effect::LightDelay]),
        with(&[Effect::LightDelay, Effect::Contraction]),
        with(&[Effect::Aberration, Effect::Contraction]),
    ];
    for fx in fx_sets {
        let mut sim = Simulation::new(&scene());
        let eye = sim.entity("eye").unwrap();
        let view = sim.view("eye").unwrap();
        for e in Effect::ALL {
            sim.set_view_effect(view, e, fx.is_on(e));
        }
        let puck = sim.entity("a").unwrap();
        let centre = *sim.world.get::<Mesh>(puck).unwrap().points.last().unwrap();
        let mut live = Vec::new();
        for f in 1..=90 {
            let t = f64::from(f) / 60.0;
            if f % 30 == 0 {
                let u =
                    ProperVelocity::try_from_beta(DVec3::new(0.1, -0.3 * f64::from(f / 30), 0.0))
                        .unwrap();
                sim.steer_observer(eye, t, u).unwrap();
            }
            sim.advance_to(t);
            if f % 10 == 3 {
                let a = sim.apparent(view).unwrap();
                let b = &a.bodies[0];
                live.push((
                    t,
                    a.eye.unwrap(),
                    b.seen[b.centre()],
                    b.emissions[b.centre()],
                ));
            }
        }
        let times: Vec<f64> = live.iter().map(|l| l.0).collect();
        let history = sim.seen_history(view, 0, centre, &times);
        for ((t, eye_then, seen_then, emission_then), h) in live.iter().zip(&history) {
            let then = h.unwrap();
            let (e, s) = (then.eye, then.seen);
            assert_eq!(e, *eye_then, "{fx:?} at {t}");
            let d = then.emission.event.position - emission_then.event.position;
            assert!(
                d.length() <= 1e-12 * (1.0 + emission_then.event.position.length())
                    && (then.emission.event.t - emission_then.event.t).abs() <= 1e-12,
                "{fx:?} at {t}: emission {:?} vs {:?}",
                then.emission.event,
                emission_then.event
            );
            assert!(
                (s.position - seen_then.position).length()
                    <= 1e-12 * (1.0 + seen_then.position.length()),
                "{fx:?} at {t}: {} vs {}",
                s.position,
                seen_then.position
            );
        }
        // No such puck: nothing, not a panic.
        assert!(
            sim.seen_history(view, 7, centre, &times)
                .iter()
                .all(Option::is_none)
        );
    }
}

/// A headless picture far in time (`run_far_to`) keeps only the history
/// its views can still see: memory bounded however far, the same picture
/// as with the whole history kept (bit for bit), for a resting and a
/// moving observer. A whole history of 10⁵ s of ten pucks once took
/// 0.8 GB.
#[test]
fn a_picture_far_in_time_keeps_only_what_its_views_can_see() {
    let resting = scene::parse(
        &SCENE.replace("beta = [0.3, 0.2, 0.0]", "beta = [0.0, 0.0, 0.0]"),
        "resting.toml",
    )
    .unwrap();
    for (scene, t) in [(resting, 6000.0), (scene(), 3000.0)] {
        let mut whole = Simulation::new(&scene);
        whole.advance_to(t);
        let mut far = Simulation::new(&scene);
        let view = far.views()[0];
        let keep = far.history_needed(view, 0.0, t);
        far.run_far_to(view, t);
        assert_eq!(
            ObserveReport::of_view(&whole, whole.views()[0], true),
            ObserveReport::of_view(&far, view, true),
            "t = {t}"
        );
        let segments = |s: &Simulation| -> usize {
            (0..2)
                .map(|i| s.physics().worldline(i).segments().len())
                .sum()
        };
        let (all, kept) = (segments(&whole), segments(&far));
        let records = far.physics().collisions().len();
        // Bounces every few seconds for t: what the horizon holds is the
        // horizon's share of them, with slack for the current segment.
        let share = keep / t;
        assert!(
            (kept as f64) < all as f64 * share * 1.5 + 4.0,
            "t = {t}: {kept} of {all} segments kept, horizon {keep} s"
        );
        assert!(
            (records as f64) < whole.physics().collisions().len() as f64 * share * 1.5 + 4.0,
            "t = {t}: {records} collision records kept"
        );
        assert!(
            all > 1000,
            "t = {t}: only {all} segments: the test needs a long run"
        );
    }
    // The resting eye, 3 m away, needs only the game's replay window.
    let resting = Simulation::new(
        &scene::parse(
            &SCENE.replace("beta = [0.3, 0.2, 0.0]", "beta = [0.0, 0.0, 0.0]"),
            "resting.toml",
        )
        .unwrap(),
    );
    assert_eq!(
        resting.history_needed(resting.views()[0], 0.0, 1e6),
        lightcone_engine::ecs::simulation::HEADLESS_HISTORY
    );
    // Another observer flying away needs ever more, but only for its view.
    let text = SCENE.replace("beta = [0.3, 0.2, 0.0]", "beta = [0.0, 0.0, 0.0]")
        + "[[observer]]\nname = \"away\"\nposition = [1.42, -1.25, 1.6]\nbeta = [0.0, -0.9, 0.0]\n";
    let two = Simulation::new(&scene::parse(&text, "two.toml").unwrap());
    let (here, away) = (two.views()[0], two.views()[1]);
    assert_eq!(
        two.history_needed(here, 0.0, 1e4),
        lightcone_engine::ecs::simulation::HEADLESS_HISTORY
    );
    // At 1e4 s it is 0.9 c · 1e4 s away: twice that delay, and more.
    assert!(two.history_needed(away, 0.0, 1e4) > 1.8e4);
}
