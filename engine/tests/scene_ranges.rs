//! The ranges a scene may give, fuzzed at their ends: the smallest
//! subnormal, each bound, the doubles just beyond, zero, the largest double,
//! NaN and the infinities. A value is accepted exactly when the guide's
//! table ("What the engine holds", whose bounds are written out here, not
//! read from the engine) holds it, and every accepted scene gives finite
//! figures: the ones `lightcone check` prints from it (c²/(μg), the
//! stopping distance (c²/μg)(γ − 1) and time (c/μg)|u|, the light-crossing
//! time, β and γ).

use lightcone_engine::scene::{self, BuildError, Scene};
use proptest::prelude::*;

/// The ends worth trying around a range `[lo, hi]` (and the values every
/// range must refuse or treat with care).
fn ends(lo: f64, hi: f64) -> Vec<f64> {
    vec![
        0.0,
        -0.0,
        5e-324,
        -5e-324,
        f64::MIN_POSITIVE,
        lo,
        lo.next_down(),
        lo.next_up(),
        hi,
        hi.next_down(),
        hi.next_up(),
        (lo * hi).sqrt(),
        -lo,
        f64::MAX,
        -f64::MAX,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
    ]
}

/// A TOML number that reads back as `x` (TOML spells `nan`, `inf`).
fn toml(x: f64) -> String {
    if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf".into() } else { "-inf".into() }
    } else {
        format!("{x:e}")
    }
}

/// One field of a scene file and the guide's range for it (docs/guide/src/scenes.md).
#[derive(Clone, Copy, Debug)]
enum Field {
    C,
    Friction,
    Gravity,
    Radius,
    Height,
    Mass,
    Side,
    Restitution,
    CushionRestitution,
    U,
}

impl Field {
    const ALL: [Field; 10] = [
        Field::C,
        Field::Friction,
        Field::Gravity,
        Field::Radius,
        Field::Height,
        Field::Mass,
        Field::Side,
        Field::Restitution,
        Field::CushionRestitution,
        Field::U,
    ];

    /// The guide's bounds.
    fn bounds(self) -> (f64, f64) {
        match self {
            Field::C => (1e-6, 1e9),
            Field::Friction => (1e-6, 100.0),
            Field::Gravity => (1e-6, 1e6),
            Field::Radius | Field::Height | Field::Side => (1e-6, 1e6),
            Field::Mass => (1e-9, 1e9),
            Field::Restitution | Field::CushionRestitution => (0.0, 1.0),
            Field::U => (0.0, 1e12),
        }
    }

    /// Whether the guide's table accepts `x` for this field (in a scene
    /// where nothing else stops it: a puck of radius up to half the
    /// largest table fits).
    fn accepts(self, x: f64) -> bool {
        let (lo, hi) = self.bounds();
        match self {
            // 0 (frictionless) or a real cloth.
            Field::Friction => x == 0.0 || (lo..=hi).contains(&x),
            // |u| up to 10¹², either sign.
            Field::U => x.is_finite() && x.abs() <= hi,
            // On a table of 10⁶ m a puck of radius 10⁶ m does not fit.
            Field::Radius => (lo..=hi / 2.0).contains(&x),
            _ => (lo..=hi).contains(&x),
        }
    }

    /// A scene holding `x` in this field, the others at ordinary values,
    /// on the largest table (so every puck fits) with light at 10³ m/s (so
    /// every puck brakes rigidly under the strongest cloth). `extreme`:
    /// with the smallest friction and gravity the guide allows and the
    /// fastest light, so the braking figures are at their largest.
    fn scene(self, x: f64, extreme: bool) -> String {
        let v = toml(x);
        let (mut c, mut friction, mut gravity) = ("1e3".to_owned(), "0.0", "9.80665".to_owned());
        if extreme {
            (c, friction, gravity) = ("1e9".to_owned(), "1e-6", "1e-6".to_owned());
        }
        let mut size = "[1e6, 1e6]".to_owned();
        let mut extra = String::new();
        let mut puck = Some("position = [5e5, 5e5]\n".to_owned());
        let mut physics = String::new();
        let add = |p: &mut Option<String>, line: String| {
            if let Some(p) = p {
                p.push_str(&line);
            }
        };
        match self {
            Field::C => c = v,
            Field::Friction => {
                return format!(
                    "c = 1e3\n[table]\nsize = [1e6, 1e6]\nfriction = {v}\n[[puck]]\nposition = [5e5, 5e5]\n"
                );
            }
            Field::Gravity => {
                friction = "1e-6";
                gravity = v;
            }
            Field::Radius => add(&mut puck, format!("radius = {v}\n")),
            Field::Height => add(&mut puck, format!("height = {v}\n")),
            Field::Mass => add(&mut puck, format!("mass = {v}\n")),
            Field::Side => {
                size = format!("[{v}, 1.0]");
                puck = None;
            }
            Field::Restitution => physics = format!("[physics]\nrestitution = {v}\n"),
            Field::CushionRestitution => extra = format!("cushion_restitution = {v}\n"),
            Field::U => add(&mut puck, format!("u = [{v}, 0.0]\n")),
        }
        let puck = puck.map(|p| format!("[[puck]]\n{p}")).unwrap_or_default();
        format!(
            "c = {c}\n[table]\nsize = {size}\nfriction = {friction}\ngravity = {gravity}\n{extra}{physics}{puck}"
        )
    }
}

/// Every figure `lightcone check` derives from a scene, each finite.
fn figures_are_finite(s: &Scene) -> Result<(), String> {
    let mut figures = vec![
        ("c", s.c),
        ("crossing time", s.table.size.x.max(s.table.size.y) / s.c),
    ];
    let a = s.table.deceleration();
    if s.table.friction > 0.0 {
        figures.push(("μg", a));
        figures.push(("c²/(μg)", s.c * s.c / a));
    }
    for p in &s.pucks {
        let u = p.u;
        figures.push(("γ", u.gamma()));
        figures.push(("|β|", u.beta().length()));
        figures.push(("1 − |β|", u.speed_deficit()));
        if s.table.friction > 0.0 {
            figures.push(("stopping distance", s.c * s.c / a * u.gamma_minus_one()));
            figures.push(("stopping time", s.c / a * u.0.length()));
        }
    }
    match figures.iter().find(|(_, x)| !x.is_finite()) {
        Some((what, x)) => Err(format!("{what} = {x}")),
        None => Ok(()),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// Each field at each of its ends: accepted exactly when the guide's
    /// range holds it, refused with a located error naming the field
    /// otherwise, and finite figures whenever accepted.
    #[test]
    fn every_range_end_is_accepted_as_documented_with_finite_figures(
        field in proptest::sample::select(Field::ALL.to_vec()),
        pick in 0usize..18,
        // With the slowest cloth and the fastest light, or ordinary ones.
        extreme in any::<bool>(),
    ) {
        let (lo, hi) = field.bounds();
        let x = ends(lo, hi)[pick];
        let text = field.scene(x, extreme);
        match scene::parse(&text, "ends.toml") {
            Ok(s) => {
                prop_assert!(field.accepts(x), "{field:?} = {x:e} accepted:\n{text}");
                prop_assert_eq!(figures_are_finite(&s), Ok(()), "{}", text);
            }
            Err(errors) => {
                prop_assert!(!field.accepts(x), "{field:?} = {x:e} refused: {errors}\n{text}");
                let e = &errors.0[0];
                prop_assert!(e.line > 0, "{e}");
                prop_assert!(e.rule.is_some(), "{e}: a range is a rule");
            }
        }
    }
}

/// The case: the smallest double as friction is refused (it made
/// c²/(μg) infinite), saying what to give; the guide's smallest friction
/// with the slowest gravity and the fastest light gives finite figures.
#[test]
fn a_subnormal_friction_is_refused_and_the_smallest_allowed_is_finite() {
    let e = scene::parse("[table]\nfriction = 5e-324\n", "tiny.toml").unwrap_err();
    assert_eq!(
        e.to_string(),
        "tiny.toml:2:12: table.friction: 5e-324 is too small a friction to brake with: give 0 \
         (frictionless) or from 1e-6 to 100 (a carom cloth slides at about 0.2)"
    );
    assert!(matches!(
        e.0[0].rule,
        Some(BuildError::OutOfRange {
            quantity: scene::Quantity::Friction,
            ..
        })
    ));
    let s = scene::parse(
        "c = 1e9\n[table]\nfriction = 1e-6\ngravity = 1e-6\n[[puck]]\nposition = [0.5, 0.5]\nu = [1e12, 0]\n",
        "slow.toml",
    )
    .unwrap();
    // c²/(μg) = 10¹⁸ / 10⁻¹² = 10³⁰ m; the stopping distance 10⁴² m.
    assert_eq!(figures_are_finite(&s), Ok(()));
    let horizon = s.c * s.c / s.table.deceleration();
    assert!((horizon / 1e30 - 1.0).abs() < 1e-12, "{horizon:e}");
    // In code, the same rule.
    let mut built = Scene::empty(glam::DVec2::new(1.0, 1.0), None).unwrap();
    assert!(built.set_friction(5e-324, 9.81).is_err());
    built.set_friction(1e-6, 1e-6).unwrap();
}
