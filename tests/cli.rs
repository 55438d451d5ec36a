//! End-to-end tests that drive the `lightcone` binary.

mod common;

use common::{cloth_pixels, lightcone, play_under_xvfb, repo};

fn shipped_scenes() -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(repo().join("assets/scenes"))
        .expect("assets/scenes exists")
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| format!("assets/scenes/{}", p.file_name().unwrap().to_string_lossy()))
        .collect();
    v.sort();
    v
}

#[test]
fn check_accepts_every_shipped_scene() {
    let scenes = shipped_scenes();
    assert!(scenes.len() >= 5, "{scenes:?}");
    let args: Vec<&str> = std::iter::once("check")
        .chain(scenes.iter().map(String::as_str))
        .collect();
    let out = lightcone(&args);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}\n{}",
        stdout,
        String::from_utf8_lossy(&out.stderr)
    );
    for s in &scenes {
        assert!(
            stdout.contains(&format!("{s}: ok")),
            "{s} missing from:\n{stdout}"
        );
    }
}

#[test]
fn check_summarises_speeds_as_beta_and_gamma() {
    let out = lightcone(&["check", "assets/scenes/paper_carom.toml"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success());
    // white: β = (0.8, 0.12), |β| = 0.8089499366, γ = 1/√(1 − 0.6544) = 1.701035.
    let white = stdout
        .lines()
        .find(|l| l.contains("white"))
        .expect("white listed");
    assert!(white.contains("|β| = 0.808949937"), "{white}");
    assert!(white.contains("γ = 1.701035"), "{white}");
    assert!(stdout.contains("effects on: contraction, light_delay, aberration, time_dilation"));
}

#[test]
fn check_reports_a_bad_scene_with_file_line_and_field() {
    let dir = std::env::temp_dir().join(format!("lightcone-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        "[[puck]]\nname = \"x\"\nposition = [0.5, 0.5]\nbeta = [1.2, 0.0]\n",
    )
    .unwrap();
    let bad = bad.to_string_lossy().into_owned();
    let out = lightcone(&["check", "assets/scenes/paper_carom.toml", &bad]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains(&format!("{bad}:4:8: puck[0].beta:")),
        "{stderr}"
    );
    assert!(stderr.contains("1 of 2 scene(s) have errors"), "{stderr}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn check_without_a_scene_checks_the_default_scene() {
    let out = lightcone(&["check"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("paper_carom.toml: ok"));
}

/// Parses JSON lines.
fn json_lines(stdout: &[u8]) -> Vec<serde_json::Value> {
    String::from_utf8_lossy(stdout)
        .lines()
        .map(|l| serde_json::from_str(l).expect("each line is JSON"))
        .collect()
}

fn xy(v: &serde_json::Value) -> [f64; 2] {
    let a = v.as_array().expect("a 2-vector");
    assert_eq!(a.len(), 2);
    [a[0].as_f64().unwrap(), a[1].as_f64().unwrap()]
}

#[test]
fn simulate_prints_the_documented_schema() {
    let out = lightcone(&[
        "simulate",
        "assets/scenes/paper_carom.toml",
        "--until",
        "20",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let lines = json_lines(&out.stdout);
    assert!(lines.len() >= 3);
    let (last, collisions) = lines.split_last().unwrap();
    let mut previous = f64::NEG_INFINITY;
    let mut kinds = std::collections::BTreeSet::new();
    for c in collisions {
        let kind = c["kind"].as_str().unwrap();
        kinds.insert(kind.to_owned());
        let t = c["t"].as_f64().unwrap();
        // In the order processed: that of each collision's first velocity
        // change; a contact lies between its two kicks (pair frame
        // simultaneity, see README "Collision convention").
        let kicks: Vec<f64> = c["pucks"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| p["t"].as_f64().unwrap())
            .collect();
        let first = kicks.iter().copied().fold(f64::INFINITY, f64::min);
        let last_kick = kicks.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert!(first >= previous && first <= 20.0, "collisions in the order processed");
        assert!(first <= t + 1e-12 && t <= last_kick + 1e-12, "{c}");
        previous = first;
        xy(&c["contact"]);
        let pucks = c["pucks"].as_array().unwrap();
        match kind {
            "puck_puck" => assert_eq!(pucks.len(), 2),
            "cushion" => {
                assert_eq!(pucks.len(), 1);
                assert!(["x0", "x1", "y0", "y1"].contains(&c["cushion"].as_str().unwrap()));
            }
            other => panic!("unknown kind {other}"),
        }
        for p in pucks {
            assert!(p["name"].is_string());
            xy(&p["position"]);
            // u and beta describe the same velocity: β = u / √(1 + u²).
            for (u, b) in [("u_before", "beta_before"), ("u_after", "beta_after")] {
                let (u, b) = (xy(&p[u]), xy(&p[b]));
                let g = (1.0 + u[0] * u[0] + u[1] * u[1]).sqrt();
                assert!((u[0] / g - b[0]).abs() < 1e-15 && (u[1] / g - b[1]).abs() < 1e-15);
            }
        }
    }
    assert!(
        kinds.contains("puck_puck") && kinds.contains("cushion"),
        "{kinds:?}"
    );
    assert_eq!(last["kind"], "state");
    assert_eq!(last["t"].as_f64(), Some(20.0));
    let pucks = last["pucks"].as_array().unwrap();
    assert_eq!(pucks.len(), 3);
    for p in pucks {
        for key in ["position", "u", "beta"] {
            xy(&p[key]);
        }
        let tau = p["proper_time"].as_f64().unwrap();
        assert!(tau > 0.0 && tau <= 20.0, "proper time runs slow: {tau}");
    }
}

#[test]
fn simulate_writes_to_a_file_and_rejects_bad_input() {
    let dir = std::env::temp_dir().join(format!("lightcone-sim-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("out.jsonl");
    let f = file.to_string_lossy().into_owned();
    let out = lightcone(&[
        "simulate",
        "assets/scenes/ten_pucks.toml",
        "--until",
        "5",
        "--out",
        &f,
    ]);
    assert!(out.status.success());
    assert!(out.stdout.is_empty());
    let text = std::fs::read(&file).unwrap();
    assert!(json_lines(&text).last().unwrap()["kind"] == "state");
    let out = lightcone(&[
        "simulate",
        "assets/scenes/paper_carom.toml",
        "--until",
        "nan",
    ]);
    assert!(!out.status.success());
    let out = lightcone(&["simulate", "no/such.toml", "--until", "1"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("no/such.toml"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bench_physics_quick_prints_the_three_tables() {
    let out = lightcone(&["bench", "physics", "--quick"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for heading in [
        "Physics time per frame",
        "Collision events per second",
        "What exactness costs",
    ] {
        assert!(stdout.contains(heading), "{heading} missing");
    }
}

#[test]
fn observe_prints_the_documented_json() {
    let out = lightcone(&[
        "observe",
        "assets/scenes/parallel_tracks.toml",
        "--at",
        "1.0",
        "--observer",
        "side",
        "--vertices",
        "--effects",
        "all",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("one JSON object");
    assert_eq!(v["t"].as_f64(), Some(1.0));
    let o = &v["observer"];
    assert_eq!(o["name"], "side");
    assert_eq!(o["position"].as_array().unwrap().len(), 3);
    assert_eq!(o["beta"].as_array().unwrap().len(), 3);
    assert_eq!(o["proper_time"].as_f64(), Some(1.0));
    let pucks = v["pucks"].as_array().unwrap();
    assert_eq!(pucks.len(), 5);
    let c = 1.42;
    for p in pucks {
        let e = &p["emission"];
        let te = e["t"].as_f64().unwrap();
        let pos: Vec<f64> = e["position"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        // On the observer's past light cone (observer at rest): c (t − tₑ) = |x − xₑ|.
        let eye = [1.42, -1.2, 0.6];
        let d = ((pos[0] - eye[0]).powi(2) + (pos[1] - eye[1]).powi(2) + (pos[2] - eye[2]).powi(2))
            .sqrt();
        assert!((c * (1.0 - te) - d).abs() < 1e-12);
        // Observer at rest: apparent distance is that light path.
        assert!((p["distance"].as_f64().unwrap() - d).abs() < 1e-12);
        let dir: Vec<f64> = p["direction"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert!((dir.iter().map(|x| x * x).sum::<f64>() - 1.0).abs() < 1e-12);
        assert!(p["doppler"].as_f64().unwrap() > 0.0);
        // Proper time runs slow: |τ(tₑ)| ≤ |tₑ| (tₑ may precede t = 0).
        assert!(p["seen_proper_time"].as_f64().unwrap().abs() <= te.abs() + 1e-12);
        assert!(p["vertices"].as_array().unwrap().len() > 90);
    }
    // Without --vertices there is no vertex list; an unknown observer is
    // an error that lists the known ones.
    let out = lightcone(&["observe", "assets/scenes/paper_carom.toml", "--at", "2"]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(v["pucks"][0].get("vertices").is_none());
    let out = lightcone(&[
        "observe",
        "assets/scenes/paper_carom.toml",
        "--at",
        "2",
        "--observer",
        "nobody",
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("the scene has: eye"));
    let out = lightcone(&[
        "observe",
        "assets/scenes/paper_carom.toml",
        "--at",
        "2",
        "--effects",
        "redshift",
    ]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("unknown effect `redshift`"));
}

#[test]
fn bench_optics_quick_prints_its_tables_and_csv() {
    let dir = std::env::temp_dir().join(format!("lightcone-bo-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("acc.csv");
    let csv_s = csv.to_string_lossy().into_owned();
    let out = lightcone(&["bench", "optics", "--quick", "--csv", &csv_s]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for heading in [
        "Accuracy and cost",
        "History memory",
        "Exact emission solves",
        "What each effect costs",
    ] {
        assert!(stdout.contains(heading), "{heading} missing");
    }
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.lines().count() >= 10);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `play` under Xvfb (a virtual X display): the window opens, the game
/// runs 20 frames, and its screenshot shows the green table cloth.
#[test]
fn play_runs_under_xvfb_and_shows_the_table() {
    let dir = std::env::temp_dir().join(format!("lightcone-play-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let shot = dir.join("play.png");
    let (out, img) = play_under_xvfb(&["play", "assets/scenes/paper_carom.toml"], &shot, 20);
    let img = img.unwrap_or_else(|| panic!("{}", String::from_utf8_lossy(&out.stderr)));
    assert_eq!((img.width, img.height), (1280, 720));
    let cloth = cloth_pixels(&img);
    assert!(cloth > 1280 * 720 / 10, "only {cloth} cloth-green pixels");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bench_render_quick_reports_cpu_and_gpu_time() {
    let out = lightcone(&["bench", "render", "--quick"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("Headless frame time") && stdout.contains("frames/s"),
        "{stdout}"
    );
}
