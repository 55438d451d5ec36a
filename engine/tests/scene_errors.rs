//! Every bad input a scene file can hold gets a message that names the
//! file, the line and the field.

use lightcone_engine::scene::{self, BuildError, Quantity, SceneError, TableSpec};

const GOOD_PUCK: &str = "[[puck]]\nname = \"a\"\nposition = [0.5, 0.5]\n";

/// Parses `text`, expects failure, returns the errors.
fn errors(text: &str) -> Vec<SceneError> {
    match scene::parse(text, "bad.toml") {
        Ok(s) => panic!("accepted a bad scene: {s:?}"),
        Err(e) => e.0,
    }
}

/// The single error must be at `line`, name `field`, and say `words`.
fn expect_one(text: &str, line: usize, field: &str, words: &str) {
    let errs = errors(text);
    assert_eq!(errs.len(), 1, "{errs:?}");
    let e = &errs[0];
    let shown = e.to_string();
    assert_eq!(e.file, "bad.toml");
    assert_eq!(e.line, line, "{shown}");
    assert!(
        e.field.contains(field),
        "field `{}` lacks `{field}`: {shown}",
        e.field
    );
    assert!(shown.contains(words), "`{shown}` lacks `{words}`");
    assert!(shown.starts_with(&format!("bad.toml:{line}:")), "{shown}");
}

#[test]
fn speed_at_or_above_c() {
    expect_one(
        "[[puck]]\nposition = [0.5, 0.5]\nbeta = [0.8, 0.6]\n",
        3,
        "puck[0].beta",
        "not below the speed of light",
    );
    expect_one(
        "c = 2.0\n[[puck]]\nposition = [0.5, 0.5]\nvelocity = [3.0, 0.0]\n",
        4,
        "puck[0].velocity",
        "not below c = 2 m/s",
    );
    expect_one(
        "[[observer]]\nposition = [0.5, 0.5, 1.0]\nbeta = [0.0, 0.0, 1.5]\n",
        3,
        "observer[0].beta",
        "not below the speed of light",
    );
}

#[test]
fn speed_given_twice() {
    expect_one(
        "[[puck]]\nposition = [0.5, 0.5]\nbeta = [0.1, 0.0]\nu = [0.1, 0.0]\n",
        1,
        "puck[0]",
        "at most one of",
    );
}

#[test]
fn overlapping_pucks() {
    let text = format!("{GOOD_PUCK}[[puck]]\nname = \"b\"\nposition = [0.55, 0.5]\n");
    expect_one(&text, 6, "puck[1].position", "overlaps puck \"a\" (line 1)");
}

#[test]
fn pucks_in_contact_are_not_overlapping() {
    let text = format!("{GOOD_PUCK}[[puck]]\nname = \"b\"\nposition = [0.561, 0.5]\n");
    assert!(scene::parse(&text, "ok.toml").is_ok());
}

#[test]
fn puck_outside_the_table() {
    expect_one(
        "[table]\nsize = [2.0, 1.0]\n[[puck]]\nposition = [1.99, 0.5]\n",
        4,
        "puck[0].position",
        "outside the table",
    );
    expect_one(
        "[[puck]]\nposition = [-3.0, 0.5]\n",
        2,
        "puck[0].position",
        "outside the table",
    );
}

#[test]
fn a_fast_puck_is_judged_by_its_contracted_width() {
    // Rest radius 0.1 would cross x = 0 at x = 0.06, but at β = 0.8 along x
    // the puck is 0.06 wide on each side: it just fits.
    let text = "[[puck]]\nposition = [0.0601, 0.5]\nradius = 0.1\nbeta = [0.8, 0.0]\n";
    assert!(scene::parse(text, "ok.toml").is_ok());
}

#[test]
fn nan_and_infinity() {
    expect_one(
        "[[puck]]\nposition = [nan, 0.5]\n",
        2,
        "puck[0].position",
        "not a finite number",
    );
    expect_one(
        "[[puck]]\nposition = [0.5, 0.5]\nu = [inf, 0.0]\n",
        3,
        "puck[0].u",
        "not a finite number",
    );
    expect_one("c = inf\n", 1, "c", "positive finite");
    expect_one(
        "[[observer]]\nposition = [0.5, 0.5, 1.0]\nlook_at = [0.0, -inf, 0.0]\n",
        3,
        "observer[0].look_at",
        "not a finite number",
    );
}

#[test]
fn non_positive_radius_mass_and_c() {
    expect_one(
        "[[puck]]\nposition = [0.5, 0.5]\nradius = 0.0\n",
        3,
        "puck[0].radius",
        "positive",
    );
    expect_one(
        "[[puck]]\nposition = [0.5, 0.5]\nmass = -1.0\n",
        3,
        "puck[0].mass",
        "positive",
    );
    expect_one("c = 0\n", 1, "c", "positive");
    expect_one("c = -3.0\n", 1, "c", "positive");
    expect_one("[table]\nsize = [2.0, 0.0]\n", 2, "table.size", "positive");
}

#[test]
fn restitution_out_of_range() {
    expect_one(
        "[physics]\nrestitution = 1.5\n",
        2,
        "physics.restitution",
        "[0, 1]",
    );
    expect_one(
        "[table]\ncushion_restitution = -0.1\n",
        2,
        "table.cushion_restitution",
        "[0, 1]",
    );
}

#[test]
fn unknown_keys() {
    // Unknown keys are reported by the parser at the key, with the list of
    // keys that would be right.
    let errs = errors("[[puck]]\nposition = [0.5, 0.5]\nbta = [0.1, 0.0]\n");
    let shown = errs[0].to_string();
    assert_eq!(errs[0].line, 3, "{shown}");
    assert!(
        shown.contains("unknown field `bta`") && shown.contains("`beta`"),
        "{shown}"
    );
    let errs = errors("speed_of_light = 3.0\n");
    assert_eq!(errs[0].line, 1);
    assert!(
        errs[0]
            .to_string()
            .contains("unknown field `speed_of_light`")
    );
    let errs = errors("[effects]\nredshift = true\n");
    assert_eq!(errs[0].line, 2);
}

#[test]
fn duplicate_names() {
    let text = format!("{GOOD_PUCK}[[puck]]\nname = \"a\"\nposition = [1.5, 0.5]\n");
    expect_one(&text, 5, "puck[1].name", "duplicate name \"a\"");
    expect_one(
        "[[observer]]\nname = \"o\"\nposition = [0, 0, 1]\n[[observer]]\nname = \"o\"\nposition = [1, 0, 1]\n",
        5,
        "observer[1].name",
        "duplicate",
    );
}

#[test]
fn syntax_and_type_errors_are_located() {
    let errs = errors("[[puck]]\nposition = [0.5, 0.5\n");
    assert_eq!(errs[0].line, 2, "{}", errs[0]);
    let errs = errors("[[puck]]\nposition = [0.5, 0.5, 0.5]\n");
    assert_eq!(errs[0].line, 2, "{}", errs[0]);
    let errs = errors("[[puck]]\nposition = \"middle\"\n");
    assert_eq!(errs[0].line, 2, "{}", errs[0]);
    let errs = errors("[[puck]]\nname = \"nowhere\"\n");
    assert!(
        errs[0].to_string().contains("missing field `position`"),
        "{}",
        errs[0]
    );
    assert_eq!(errs[0].line, 1);
}

#[test]
fn several_errors_are_all_reported() {
    let errs = errors("c = -1\n[[puck]]\nposition = [0.5, 0.5]\nradius = -2\ncolor = \"plaid\"\n");
    assert_eq!(errs.len(), 3, "{errs:?}");
}

#[test]
fn unreadable_file_names_the_file() {
    let e = scene::load(std::path::Path::new("no/such/scene.toml")).unwrap_err();
    assert!(
        e.to_string().starts_with("no/such/scene.toml: cannot read"),
        "{e}"
    );
}

#[test]
fn defaults_follow_the_paper() {
    let s = scene::parse(GOOD_PUCK, "ok.toml").unwrap();
    assert_eq!(s.c, 1.42); // light crosses the 2.84 m side in 2 s
    assert_eq!(s.pucks[0].radius, 0.0305);
    assert_eq!(s.observers.len(), 1);
    assert_eq!(s.restitution, 1.0);
}

#[test]
fn u_states_speeds_beyond_what_beta_can() {
    let s = scene::parse(
        "[[puck]]\nposition = [0.5, 0.5]\nu = [1e8, 0.0]\n",
        "ok.toml",
    )
    .unwrap();
    let u = s.pucks[0].u;
    assert!((u.gamma() / 1e8 - 1.0).abs() < 1e-15);
    // 1 − |β| = 1/(2u²) (1 − 3/(4u²) + …) = 5e-17 at u = 10⁸, where β
    // itself rounds to 1.
    assert!(
        (u.speed_deficit() / 5e-17 - 1.0).abs() < 1e-15,
        "{}",
        u.speed_deficit()
    );
}

#[test]
fn optics_table() {
    let s = scene::parse("[optics]\nmethod = \"sampled\"\nhistory_frames = 300\ndichotomy_steps = 4\ninterpolate = false\n", "ok.toml").unwrap();
    assert!(
        s.optics.sampled
            && s.optics.history_frames == 300
            && s.optics.dichotomy_steps == 4
            && !s.optics.interpolate
    );
    expect_one(
        "[optics]\nmethod = \"guess\"\n",
        2,
        "optics.method",
        "use \"exact\" or \"sampled\"",
    );
    expect_one(
        "[optics]\nhistory_frames = 1\n",
        2,
        "optics.history_frames",
        "at least 2",
    );
    expect_one(
        "[optics]\ndichotomy_steps = -3\n",
        2,
        "optics.dichotomy_steps",
        "0 (full) or more",
    );
}

#[test]
fn scenes_built_in_code_get_the_same_checks() {
    use glam::{DVec2, DVec3};
    use lightcone_engine::scene::{Color, ObserverSpec, PuckSpec, Scene};
    use lightcone_engine::spacetime::ProperVelocity;
    let mut s = Scene::empty(DVec2::new(2.0, 1.0), None).unwrap();
    assert_eq!(s.c, 1.0);
    let puck = |name: &str, x: f64| PuckSpec {
        name: name.into(),
        position: DVec2::new(x, 0.5),
        u: ProperVelocity::ZERO,
        radius: 0.05,
        height: 0.02,
        mass: 0.2,
        color: Color::default_for(0),
    };
    s.add_puck(puck("a", 0.5)).unwrap();
    // The rule broken, told apart by variant; the message names the body.
    let e = s.add_puck(puck("a", 1.5)).unwrap_err();
    assert_eq!(e.rule(), &BuildError::DuplicateName("a".into()));
    assert!(e.to_string().contains("unique"), "{e}");
    let e = s.add_puck(puck("b", 0.55)).unwrap_err();
    assert!(
        matches!(
            &e,
            BuildError::Overlap { puck, other, other_line: None, distance, reach: 0.1 }
                if puck == "b" && other == "a" && (distance - 0.05).abs() < 1e-15
        ),
        "{e:?}"
    );
    assert!(
        e.to_string()
            .starts_with("puck \"b\" overlaps puck \"a\": centres 0.05"),
        "{e}"
    );
    let e = s.add_puck(puck("c", 1.99)).unwrap_err();
    assert!(matches!(e, BuildError::OffTable { .. }), "{e}");
    assert!(e.to_string().contains("outside the table"), "{e}");
    // Contracted to fit a 1 m side at t = 0 (γ = 10 along y), but 1.2 m
    // across at rest: once slowed, it fits nowhere between the cushions.
    let e = s
        .add_puck(PuckSpec {
            radius: 0.6,
            u: ProperVelocity(DVec3::new(0.0, 99f64.sqrt(), 0.0)),
            position: DVec2::new(1.3, 0.5),
            ..puck("w", 1.3)
        })
        .unwrap_err();
    assert!(
        matches!(&e.rule(), BuildError::WiderThanTable { puck, side, .. } if puck == "w" && *side == 1.0),
        "{e:?}"
    );
    assert!(e.to_string().contains("1.2 m across at rest"), "{e}");
    let e = s
        .add_puck(PuckSpec {
            radius: -1.0,
            ..puck("d", 1.0)
        })
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "puck \"d\" radius: -1 must be a positive finite number from 1e-6 to 1e6 m"
    );
    assert_eq!(
        e.rule(),
        &BuildError::OutOfRange {
            quantity: Quantity::Length,
            value: -1.0
        }
    );
    let e = s
        .add_puck(PuckSpec {
            u: ProperVelocity(DVec3::new(0.0, 2e12, 0.0)),
            ..puck("e", 1.0)
        })
        .unwrap_err();
    assert_eq!(
        e.rule(),
        &BuildError::OutOfRange {
            quantity: Quantity::ProperSpeed,
            value: 2e12
        }
    );
    assert_eq!(s.pucks.len(), 1);
    let eye = ObserverSpec {
        name: "me".into(),
        position: DVec3::new(1.0, -1.0, 1.0),
        look_at: Some(DVec3::ZERO),
        u: ProperVelocity::ZERO,
    };
    s.add_observer(eye.clone()).unwrap();
    assert_eq!(s.observers.len(), 1);
    assert_eq!(
        s.add_observer(eye).unwrap_err().rule(),
        &BuildError::DuplicateName("me".into())
    );
    assert_eq!(
        Scene::empty(DVec2::new(-1.0, 1.0), None)
            .unwrap_err()
            .rule(),
        &BuildError::TableSize(DVec2::new(-1.0, 1.0))
    );
    assert_eq!(
        Scene::empty(DVec2::new(1.0, 1.0), Some(0.0))
            .unwrap_err()
            .to_string(),
        "c: 0 must be a positive finite number from 1e-6 to 1e9 m/s"
    );
}

/// Every error of `text`, shown.
fn shown(text: &str) -> String {
    match scene::parse(text, "bad.toml") {
        Ok(s) => panic!("accepted a bad scene: {s:?}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn type_errors_and_duplicate_keys_name_the_field() {
    expect_one(
        "[[puck]]\nposition = [0.5, 0.5]\nmass = \"heavy\"\n",
        3,
        "puck[0].mass",
        "invalid type: string \"heavy\", expected a number",
    );
    expect_one(
        "[[observer]]\nposition = [0, 0, 1]\nlook_at = nan\n",
        3,
        "observer[0].look_at",
        "invalid type",
    );
    expect_one(
        "[effects]\ndoppler = [true, false]\n",
        2,
        "effects.doppler",
        "expected true or false",
    );
    expect_one(
        "[[puck]]\nposition = [0.5, 0.5]\n[[puck]]\nposition = [1.5, 0.5]\nradius = 0.01\nradius = 0.02\n",
        6,
        "puck[1].radius",
        "duplicate key `radius`",
    );
}

#[test]
fn invalid_utf8_is_located() {
    let dir = std::env::temp_dir().join(format!("lightcone-utf8-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("latin1.toml");
    std::fs::write(&path, b"title = \"ok\"\ndescription = \"caf\xe9\"\n").unwrap();
    let e = scene::load(&path).unwrap_err().to_string();
    let name = path.display().to_string();
    assert!(e.starts_with(&format!("{name}:2:19: ")), "{e}");
    assert!(e.contains("byte 0xe9 is not UTF-8"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn messages_stay_on_one_line_and_numbers_stay_short() {
    // A newline inside a name does not split the message.
    let e = shown(
        "[[puck]]\nname = \"a\\nb\"\nposition = [0.5, 0.5]\n[[puck]]\nname = \"a\\nb\"\nposition = [1.5, 0.5]\n",
    );
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(e.contains("duplicate name \"a\\nb\""), "{e}");
    // 1e-300 prints as 1e-300, not as 300 digits.
    for text in [
        "[[puck]]\nposition = [0.5, 0.5]\nradius = 1e-300\n",
        "[[puck]]\nposition = [0.5, 1e-300]\n",
        "[table]\nsize = [1e-300, 1.0]\n",
        "c = 1e-300\n",
        "title = 1e-300\n",
    ] {
        let e = shown(text);
        assert!(e.contains("1e-300") && e.len() < 300, "{text}: {e}");
    }
}

#[test]
fn the_engine_range_is_enforced_with_located_errors() {
    expect_one(
        "[[puck]]\nposition = [0.5, 0.5]\nu = [1e13, 0.0]\n",
        3,
        "puck[0].u",
        "≤ 1e12",
    );
    expect_one(
        "[[observer]]\nposition = [0.5, 0.5, 1.0]\nu = [0.0, 1e200, 0.0]\n",
        3,
        "observer[0].u",
        "beyond what the engine holds",
    );
    // u = 10⁸ and 10¹² are held; β that rounds to 1 is not a speed below c.
    for u in ["1e8", "1e12"] {
        let text = format!("[[puck]]\nposition = [0.5, 0.5]\nu = [{u}, 3.0]\n");
        let s = scene::parse(&text, "ok.toml").unwrap();
        assert!(s.pucks[0].u.gamma().is_finite());
    }
    expect_one(
        "[[puck]]\nposition = [0.5, 0.5]\nbeta = [0.99999999999999999999, 0.0]\n",
        3,
        "puck[0].beta",
        "not below the speed of light",
    );
    expect_one("[table]\nsize = [2e6, 1.0]\n", 2, "table.size", "1e6 m");
    expect_one("c = 1e10\n", 1, "c", "1e9 m/s");
    expect_one(
        "[[puck]]\nposition = [0.5, 0.5]\nmass = 1e300\n",
        3,
        "puck[0].mass",
        "1e9 kg",
    );
    expect_one(
        "[[observer]]\nposition = [0.5, 0.5, 1e300]\n",
        2,
        "observer[0].position",
        "too far",
    );
    expect_one(
        "[optics]\nhistory_frames = 1000000000000\n",
        2,
        "optics.history_frames",
        "at most 100000",
    );
    expect_one(
        "[optics]\ndichotomy_steps = 4000000000\n",
        2,
        "optics.dichotomy_steps",
        "at most 64",
    );
}

/// `n` pucks of radius 0.01 m, centres `step` apart from (x0, y0) along
/// (dx, dy), on a table big enough.
fn row(n: usize, step: f64, dir: (f64, f64)) -> String {
    let mut text = format!(
        "c = 1.0\n[table]\nsize = [{}, {}]\n",
        1.0 + step * n as f64,
        1.0 + step * n as f64
    );
    for i in 0..n {
        let k = step * i as f64;
        text += &format!(
            "[[puck]]\nposition = [{}, {}]\nradius = 0.01\n",
            0.5 + k * dir.0,
            0.5 + k * dir.1
        );
    }
    text
}

#[test]
fn repeated_errors_are_capped() {
    // 2 000 pucks at one point: 20 overlaps shown, the rest counted.
    let errs = errors(&row(2000, 0.0, (1.0, 0.0)));
    assert_eq!(errs.len(), scene::MAX_ERRORS_PER_KIND + 1);
    assert_eq!(
        errs.last().unwrap().to_string(),
        "bad.toml: … and 1979 more overlaps"
    );
    // 100 negative masses: 20 shown, then one line for the rest.
    let mut text = String::from("c = 1.0\n[table]\nsize = [300.0, 1.0]\n");
    for i in 0..100 {
        text += &format!("[[puck]]\nposition = [{}.5, 0.5]\nmass = -1\n", i);
    }
    let errs = errors(&text);
    assert_eq!(errs.len(), 21);
    assert!(
        errs[20]
            .to_string()
            .ends_with("… and 80 more errors in `puck[].mass`"),
        "{}",
        errs[20]
    );
}

#[test]
fn a_hundred_thousand_pucks_check_in_well_under_a_second() {
    use std::time::Instant;
    // On a line across x (the worst case of a sweep along x), through the
    // whole loader: the TOML itself is most of the time.
    let text = row(100_000, 0.03, (0.0, 1.0));
    let start = Instant::now();
    let s = scene::parse(&text, "ok.toml").unwrap();
    let took = start.elapsed().as_secs_f64();
    assert_eq!(s.pucks.len(), 100_000);
    // Linear: ≈ 0.2 s here; a quadratic search would take minutes. The
    // bound leaves room for a loaded machine.
    assert!(took < 5.0, "{took} s");
    // The overlap search alone, along x, along y, diagonally, all at one
    // point (one pair per puck, not N²/2).
    let pucks = |step: f64, dir: (f64, f64)| -> Vec<scene::PuckSpec> {
        (0..100_000)
            .map(|i| {
                let k = step * i as f64;
                scene::PuckSpec {
                    position: glam::DVec2::new(0.5 + k * dir.0, 0.5 + k * dir.1),
                    radius: 0.01,
                    ..s.pucks[0].clone()
                }
            })
            .collect()
    };
    for dir in [(1.0, 0.0), (0.0, 1.0), (0.6, 0.8)] {
        let p = pucks(0.03, dir);
        let start = Instant::now();
        assert!(scene::first_overlaps(&p).is_empty());
        let took = start.elapsed().as_secs_f64();
        assert!(took < 1.5, "{dir:?}: overlap search {took} s");
    }
    let p = pucks(0.0, (1.0, 0.0));
    let start = Instant::now();
    assert_eq!(scene::first_overlaps(&p).len(), 100_000 - 1);
    assert!(start.elapsed().as_secs_f64() < 1.5);
}

#[test]
fn friction_and_gravity_out_of_range() {
    expect_one("[table]\nfriction = -0.2\n", 2, "table.friction", "from 0");
    expect_one("[table]\nfriction = nan\n", 2, "table.friction", "finite");
    expect_one("[table]\nfriction = inf\n", 2, "table.friction", "finite");
    expect_one("[table]\ngravity = 0.0\n", 2, "table.gravity", "positive");
    expect_one("[table]\ngravity = -9.81\n", 2, "table.gravity", "positive");
    expect_one("[table]\ngravity = nan\n", 2, "table.gravity", "positive");
    // A puck larger than the braking's Rindler horizon c²/(μg) cannot stop
    // rigidly: c = 0.1 m/s, μg ≈ 1.96 m/s², horizon ≈ 5 mm.
    expect_one(
        "c = 0.1\n[table]\nfriction = 0.2\n[[puck]]\nposition = [0.5, 0.5]\n",
        3,
        "table.friction",
        "cannot brake rigidly",
    );
    // The default friction, a carom cloth's, is checked too, and the
    // error, with no `friction` to point at, names the puck and the way out.
    expect_one(
        "c = 0.1\n[[puck]]\nposition = [0.5, 0.5]\nradius = 0.03\n",
        4,
        "puck[0].radius",
        "the default, a carom cloth: write [table] friction = 0",
    );
    expect_one(
        "c = 0.1\n[[puck]]\nposition = [0.5, 0.5]\n",
        3,
        "puck[0].position",
        "cannot brake rigidly",
    );
    assert!(
        lightcone_engine::scene::parse(
            "c = 0.1\n[table]\nfriction = 0\n[[puck]]\nposition = [0.5, 0.5]\n",
            "ok.toml"
        )
        .is_ok()
    );
    // Defaults: a carom cloth (μ = 0.2), standard gravity; given values are
    // kept.
    let s = lightcone_engine::scene::parse("", "ok.toml").unwrap();
    assert_eq!(s.table.friction, TableSpec::CAROM_CLOTH_FRICTION);
    assert_eq!(s.table.friction, 0.2);
    assert_eq!(s.table.gravity, 9.80665);
    let s = lightcone_engine::scene::parse("[table]\nfriction = 0.2\ngravity = 1.62\n", "ok.toml")
        .unwrap();
    assert_eq!((s.table.friction, s.table.gravity), (0.2, 1.62));
    assert!((s.table.deceleration() - 0.324).abs() < 1e-15);
}

#[test]
fn friction_set_in_code_is_checked_as_in_a_file() {
    let mut s = scene::Scene::empty(glam::DVec2::new(2.0, 1.0), Some(0.1)).unwrap();
    let puck = scene::PuckSpec {
        name: "a".to_owned(),
        position: glam::DVec2::new(1.0, 0.5),
        u: lightcone_engine::spacetime::ProperVelocity::ZERO,
        radius: 0.03,
        height: 0.02,
        mass: 0.2,
        color: scene::Color::default_for(0),
    };
    let out_of_range = |e: BuildError, q: Quantity| {
        assert!(
            matches!(e.rule(), BuildError::OutOfRange { quantity, .. } if *quantity == q),
            "{e}"
        );
        e.to_string()
    };
    let friction = s.set_friction(-0.1, 9.81).unwrap_err();
    assert!(out_of_range(friction, Quantity::Friction).starts_with("friction: -0.1 must be"));
    let gravity = s.set_friction(0.2, 0.0).unwrap_err();
    assert!(out_of_range(gravity, Quantity::Gravity).starts_with("gravity: 0 must be"));
    out_of_range(
        s.set_friction(f64::NAN, 9.81).unwrap_err(),
        Quantity::Friction,
    );
    out_of_range(
        s.set_friction(5e-324, 9.81).unwrap_err(),
        Quantity::Friction,
    );
    // c = 0.1 m/s, μg ≈ 1.96 m/s²: the Rindler horizon c²/(μg) ≈ 5 mm, so a
    // 30 mm puck cannot brake rigidly, whichever comes first.
    s.set_friction(0.2, 9.81).unwrap();
    let horizon = |e: BuildError| {
        assert!(
            matches!(e, BuildError::BeyondHorizon { ref puck, radius: 0.03, .. } if puck == "a"),
            "{e}"
        );
        // 0.1² / (0.2 · 9.81) m, as the message prints it.
        assert!(
            e.to_string().contains("c²/(μg) = 0.00509683995922528"),
            "{e}"
        );
    };
    horizon(s.add_puck(puck.clone()).unwrap_err());
    s.set_friction(0.0, 9.81).unwrap();
    s.add_puck(puck).unwrap();
    horizon(s.set_friction(0.2, 9.81).unwrap_err());
    assert_eq!(s.table.friction, 0.0, "unchanged by the refused value");
}
