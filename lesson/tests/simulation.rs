//! `SimulationCore` (Python's `lightcone.Simulation`, the browser's
//! stand-in) sees what `lightcone observe` sees: its own persistent views,
//! asked in any order, at any effects, after pictures of other aspects,
//! with exact or the paper's sampled optics, give the report a fresh
//! simulation run to that time gives.

use lightcone_engine::scene::{self, Effect, Effects};
use lightcone_lesson::simulation::SimulationCore;
use lightcone_render::frame::ViewKind;

fn shipped(name: &str) -> scene::Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets/scenes")
        .join(name);
    scene::load(&path).unwrap()
}

/// Every observer, every effect alone and all together, at times asked
/// out of order: equal to `lightcone observe`'s report (a fresh world run
/// to the time), field for field.
#[test]
fn persistent_views_report_what_a_fresh_world_reports() {
    for (name, sampled) in [
        ("paper_carom.toml", false),
        ("flyby.toml", false),
        ("contraction.toml", false),
        // The paper's sampled optics, whose samples must not depend on
        // earlier questions either.
        ("paper_carom.toml", true),
    ] {
        let mut scene = shipped(name);
        if sampled {
            scene.optics.sampled = true;
            scene.optics.history_frames = 4;
        }
        let mut core = SimulationCore::new(&scene, None).unwrap();
        core.advance_to(3.0);
        let mut sets = vec![scene.effects, Effects::NONE, Effects::default()];
        for e in Effect::ALL {
            let mut one = Effects::NONE;
            one.set(e, true);
            sets.push(one);
        }
        for (k, &t) in [2.5, 0.0, 1.25, 3.0, 0.5].iter().enumerate() {
            for (i, o) in scene.observers.iter().enumerate() {
                // (Sampled optics is the light delay's: keep it on.)
                let fx = if sampled {
                    scene.effects
                } else {
                    sets[(k + i) % sets.len()]
                };
                if k == 2 {
                    // A picture of another aspect in between changes nothing.
                    let _ = core
                        .picture(Some(&o.name), t, ViewKind::Truth, 0.5)
                        .unwrap();
                }
                let got = core.observe(Some(&o.name), t, true, fx).unwrap();
                let want = lightcone_render::observe::report_at(&scene, i, t, fx, true).unwrap();
                assert_eq!(got, want, "{name}, observer {}, t = {t}, {fx:?}", o.name);
            }
        }
        assert_eq!(core.time(), 3.0, "{name}: observing moves no board time");
    }
}

/// The history horizon is checked as Python's `Simulation(history=…)` is.
#[test]
fn a_history_that_is_not_a_time_is_refused() {
    let scene = shipped("paper_carom.toml");
    for h in [-1.0, f64::NAN, f64::INFINITY] {
        let e = SimulationCore::new(&scene, Some(h)).err().unwrap();
        assert!(e.message.contains("history"), "{h}: {}", e.message);
    }
    let core = SimulationCore::new(&scene, Some(2.0)).unwrap();
    assert_eq!(core.billiard().history(), Some(2.0));
}
