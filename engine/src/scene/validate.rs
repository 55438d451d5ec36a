//! From the file as written to a [`Scene`]: every physical check, each
//! failure located at its value.

use glam::{DVec2, DVec3};

use std::collections::{BTreeMap, HashSet};

use super::error::number;
use super::model::{
    C_RANGE, DEFAULT_HEIGHT, DEFAULT_MASS, DEFAULT_RADIUS, DEFAULT_TABLE, GRAVITY_RANGE,
    LENGTH_RANGE, MASS_RANGE, MAX_DICHOTOMY_STEPS, MAX_FRICTION, MAX_HISTORY_FRAMES,
    MAX_OBSERVER_DISTANCE, MAX_OBSERVERS, MAX_PUCKS, MAX_U, first_overlaps, magnitude,
};
use super::raw::{At, RawObserver, RawPuck, RawScene};
use super::{Color, Effects, ObserverSpec, PuckSpec, Scene, SceneError, SceneErrors, TableSpec};
use crate::spacetime::ProperVelocity;

/// Errors of one kind shown before the rest are only counted.
pub const MAX_ERRORS_PER_KIND: usize = 20;

/// Collects located errors while a scene is checked, keeping the first
/// [`MAX_ERRORS_PER_KIND`] of each kind and counting the rest.
struct Checker<'a> {
    text: &'a str,
    file: &'a str,
    errors: Vec<SceneError>,
    /// Errors seen per kind (the field with its indices removed, or
    /// "overlaps").
    seen: BTreeMap<String, usize>,
    /// Errors seen in all.
    count: usize,
}

impl Checker<'_> {
    fn error<T>(&mut self, at: &At<T>, field: &str, message: String) {
        let kind: String = field
            .split('[')
            .map(|part| part.split_once(']').map_or(part, |(_, rest)| rest))
            .collect::<Vec<_>>()
            .join("[]");
        self.error_of_kind(at, field, message, kind);
    }

    fn error_of_kind<T>(&mut self, at: &At<T>, field: &str, message: String, kind: String) {
        self.count += 1;
        let seen = self.seen.entry(kind).or_insert(0);
        *seen += 1;
        if *seen <= MAX_ERRORS_PER_KIND {
            self.errors.push(SceneError::at(
                self.file,
                self.text,
                at.span().start,
                field,
                message,
            ));
        }
    }

    /// Whether any error was found (shown or only counted).
    fn failed(&self) -> bool {
        !self.seen.is_empty()
    }

    /// The shown errors in file order, then one line per kind that had
    /// more.
    fn into_errors(mut self) -> SceneErrors {
        self.errors.sort_by_key(|e| (e.line, e.column));
        for (kind, n) in &self.seen {
            if *n > MAX_ERRORS_PER_KIND {
                let more = n - MAX_ERRORS_PER_KIND;
                let message = if kind == "overlaps" {
                    format!("… and {more} more overlaps")
                } else {
                    format!("… and {more} more errors in `{kind}`")
                };
                self.errors.push(SceneError::whole_file(self.file, message));
            }
        }
        SceneErrors(self.errors)
    }

    /// A finite number in `range` (or `default` when absent), with `unit`
    /// for the message.
    fn in_range(
        &mut self,
        v: Option<&At<f64>>,
        field: &str,
        default: f64,
        range: std::ops::RangeInclusive<f64>,
        unit: &str,
    ) -> f64 {
        let Some(v) = v else { return default };
        let x = *v.get_ref();
        if range.contains(&x) {
            x
        } else {
            self.error(
                v,
                field,
                format!(
                    "{} must be a positive finite number from {} to {} {unit}",
                    number(x),
                    number(*range.start()),
                    number(*range.end())
                ),
            );
            default
        }
    }

    /// An array of `N` finite numbers, else an error and `None`.
    fn finite<const N: usize>(&mut self, v: &At<Vec<f64>>, field: &str) -> Option<[f64; N]> {
        let x = v.get_ref();
        let Ok(a) = <[f64; N]>::try_from(x.as_slice()) else {
            self.error(
                v,
                field,
                format!("{} has {} numbers; give {N}", list(x), x.len()),
            );
            return None;
        };
        if a.iter().all(|c| c.is_finite()) {
            Some(a)
        } else {
            self.error(
                v,
                field,
                format!("{} has a component that is not a finite number", list(x)),
            );
            None
        }
    }

    /// A number in [0, 1] (or `default` when absent).
    fn unit_interval(&mut self, v: Option<&At<f64>>, field: &str, default: f64) -> f64 {
        let Some(v) = v else { return default };
        let x = *v.get_ref();
        if (0.0..=1.0).contains(&x) {
            x
        } else {
            self.error(v, field, format!("{} must lie in [0, 1]", number(x)));
            default
        }
    }

    /// The proper velocity from exactly one of `beta`, `velocity` (m/s) or
    /// `u` (γβ); at rest when none is given.
    fn motion<const N: usize>(
        &mut self,
        at: &At<impl Sized>,
        prefix: &str,
        beta: Option<&At<Vec<f64>>>,
        velocity: Option<&At<Vec<f64>>>,
        u: Option<&At<Vec<f64>>>,
        c: f64,
    ) -> ProperVelocity {
        let given = [beta.is_some(), velocity.is_some(), u.is_some()];
        if given.iter().filter(|g| **g).count() > 1 {
            self.error(
                at,
                &format!("{prefix}.beta"),
                "give at most one of `beta`, `velocity` and `u`".to_owned(),
            );
            return ProperVelocity::ZERO;
        }
        let to3 = |x: [f64; N]| DVec3::from_slice(&[x.as_slice(), &[0.0; 3]].concat()[..3]);
        if let Some(b) = beta {
            let field = format!("{prefix}.beta");
            let Some(x) = self.finite::<N>(b, &field) else {
                return ProperVelocity::ZERO;
            };
            match ProperVelocity::try_from_beta(to3(x)) {
                Ok(u) => u,
                Err(_) => {
                    self.error(
                        b,
                        &field,
                        format!(
                            "speed |β| = {} is not below the speed of light (|β| must be < 1); \
                             to state γ beyond ~10⁷ give `u` = γβ instead",
                            number(magnitude(to3(x)))
                        ),
                    );
                    ProperVelocity::ZERO
                }
            }
        } else if let Some(v) = velocity {
            let field = format!("{prefix}.velocity");
            let Some(x) = self.finite::<N>(v, &field) else {
                return ProperVelocity::ZERO;
            };
            let speed = magnitude(to3(x));
            match ProperVelocity::try_from_velocity(to3(x), c) {
                Ok(u) => u,
                Err(_) => {
                    self.error(
                        v,
                        &field,
                        format!(
                            "speed {} m/s is not below c = {} m/s",
                            number(speed),
                            number(c)
                        ),
                    );
                    ProperVelocity::ZERO
                }
            }
        } else if let Some(v) = u {
            let field = format!("{prefix}.u");
            let Some(x) = self.finite::<N>(v, &field) else {
                return ProperVelocity::ZERO;
            };
            let u = ProperVelocity(to3(x));
            if magnitude(u.0) > MAX_U {
                self.error(
                    v,
                    &field,
                    format!(
                        "|u| = {} is beyond what the engine holds: give |u| = γ|β| ≤ {}",
                        number(magnitude(u.0)),
                        number(MAX_U)
                    ),
                );
                return ProperVelocity::ZERO;
            }
            u
        } else {
            ProperVelocity::ZERO
        }
    }

    /// A unique name, or `fallback` when absent.
    fn name(
        &mut self,
        name: Option<&At<String>>,
        field: &str,
        fallback: String,
        taken: &mut HashSet<String>,
    ) -> String {
        let Some(n) = name else {
            taken.insert(fallback.clone());
            return fallback;
        };
        let s = n.get_ref().trim().to_owned();
        if s.is_empty() {
            self.error(n, field, "a name must not be empty".to_owned());
            return fallback;
        }
        if !taken.insert(s.clone()) {
            self.error(
                n,
                field,
                format!("duplicate name \"{s}\": names must be unique"),
            );
        }
        s
    }
}

/// Checks a parsed scene and builds the engine's [`Scene`].
pub fn validate(raw: RawScene, text: &str, file: &str) -> Result<Scene, SceneErrors> {
    let mut ck = Checker {
        text,
        file,
        errors: Vec::new(),
        seen: BTreeMap::new(),
        count: 0,
    };
    if raw.puck.len() > MAX_PUCKS {
        return Err(SceneErrors::single(SceneError::at(
            file,
            text,
            raw.puck[MAX_PUCKS].span().start,
            &format!("puck[{MAX_PUCKS}]"),
            format!(
                "{} pucks: a scene holds at most {MAX_PUCKS}",
                raw.puck.len()
            ),
        )));
    }
    if raw.observer.len() > MAX_OBSERVERS {
        return Err(SceneErrors::single(SceneError::at(
            file,
            text,
            raw.observer[MAX_OBSERVERS].span().start,
            &format!("observer[{MAX_OBSERVERS}]"),
            format!(
                "{} observers: a scene holds at most {MAX_OBSERVERS}",
                raw.observer.len()
            ),
        )));
    }

    let size = match raw.table.as_ref().and_then(|t| t.size.as_ref()) {
        Some(s) => match ck.finite::<2>(s, "table.size") {
            Some([x, y]) if LENGTH_RANGE.contains(&x) && LENGTH_RANGE.contains(&y) => {
                DVec2::new(x, y)
            }
            Some(x) => {
                ck.error(
                    s,
                    "table.size",
                    format!(
                        "{}: both sides must be positive, from {} to {} m",
                        list(&x),
                        number(*LENGTH_RANGE.start()),
                        number(*LENGTH_RANGE.end())
                    ),
                );
                DVec2::from(DEFAULT_TABLE)
            }
            None => DVec2::from(DEFAULT_TABLE),
        },
        None => DVec2::from(DEFAULT_TABLE),
    };
    let cushion_restitution = ck.unit_interval(
        raw.table
            .as_ref()
            .and_then(|t| t.cushion_restitution.as_ref()),
        "table.cushion_restitution",
        1.0,
    );
    let table_raw = raw.table.as_ref();
    let friction = match table_raw.and_then(|t| t.friction.as_ref()) {
        None => TableSpec::CAROM_CLOTH_FRICTION,
        Some(v) => {
            let x = *v.get_ref();
            if (0.0..=MAX_FRICTION).contains(&x) {
                x
            } else {
                ck.error(
                    v,
                    "table.friction",
                    format!(
                        "{} must be a finite number from 0 (frictionless) to {MAX_FRICTION} \
                         (a carom cloth slides at about 0.2)",
                        number(x)
                    ),
                );
                0.0
            }
        }
    };
    let gravity = ck.in_range(
        table_raw.and_then(|t| t.gravity.as_ref()),
        "table.gravity",
        TableSpec::STANDARD_GRAVITY,
        GRAVITY_RANGE,
        "m/s²",
    );
    let table = TableSpec {
        size,
        cushion_restitution,
        friction,
        gravity,
    };
    let c = ck.in_range(raw.c.as_ref(), "c", Scene::default_c(size), C_RANGE, "m/s");
    let restitution = ck.unit_interval(
        raw.physics.as_ref().and_then(|p| p.restitution.as_ref()),
        "physics.restitution",
        1.0,
    );
    let before_start = match &raw.before_start {
        None => super::model::BeforeStart::default(),
        Some(b) => match b.get_ref().as_str() {
            "rest" => super::model::BeforeStart::Rest,
            "moving" => super::model::BeforeStart::Moving,
            other => {
                ck.error(
                    b,
                    "before_start",
                    format!("\"{other}\" is not allowed: use \"rest\" or \"moving\""),
                );
                super::model::BeforeStart::default()
            }
        },
    };
    let effects = effects(raw.effects.unwrap_or_default());
    let optics = optics(&mut ck, raw.optics.unwrap_or_default());

    let mut names = HashSet::new();
    let mut pucks = Vec::with_capacity(raw.puck.len());
    let mut puck_spans = Vec::with_capacity(raw.puck.len());
    for (i, at) in raw.puck.iter().enumerate() {
        let errors_before = ck.count;
        let p = puck(&mut ck, at, i, c, &mut names);
        if ck.count > errors_before {
            continue; // a puck with a bad field is not placed
        }
        if let Some(why) = table.misplaced(&p) {
            ck.error(&at.get_ref().position, &format!("puck[{i}].position"), why);
        }
        pucks.push(p);
        puck_spans.push((i, at));
    }
    // Born-rigid braking needs every puck shorter than c²/(μg) (the
    // braking's Rindler horizon; see worldline::sliding). Located at the
    // table's `friction` when the file gives it, else at the puck's radius
    // (or position), naming the default.
    if let Some((k, why)) =
        super::model::braking_horizon_error(c, table.friction, table.gravity, &pucks)
    {
        match table_raw.and_then(|t| t.friction.as_ref()) {
            Some(v) => ck.error(v, "table.friction", why),
            None => {
                let (i, at) = puck_spans[k];
                let puck = at.get_ref();
                let why = format!(
                    "{why} (friction {} is the default, a carom cloth: write \
                     [table] friction = 0 for a frictionless table)",
                    number(table.friction)
                );
                match &puck.radius {
                    Some(r) => ck.error(r, &format!("puck[{i}].radius"), why),
                    None => ck.error(&puck.position, &format!("puck[{i}].position"), why),
                }
            }
        }
    }
    for (i, j) in first_overlaps(&pucks) {
        let (a, b) = (&pucks[i], &pucks[j]);
        ck.error_of_kind(
            &puck_spans[j].1.get_ref().position,
            &format!("puck[{}].position", puck_spans[j].0),
            format!(
                "puck \"{}\" overlaps puck \"{}\" (line {}): centres {} m apart, radii add to {} m",
                b.name,
                a.name,
                super::error::line_column(text, puck_spans[i].1.span().start).0,
                number(a.position.distance(b.position)),
                number(a.radius + b.radius)
            ),
            "overlaps".to_owned(),
        );
    }

    let mut observer_names = HashSet::new();
    let mut observers: Vec<ObserverSpec> = raw
        .observer
        .iter()
        .enumerate()
        .map(|(i, at)| observer(&mut ck, at, i, c, &mut observer_names))
        .collect();
    if observers.is_empty() {
        observers.push(Scene::default_observer(size));
    }

    if ck.failed() {
        return Err(ck.into_errors());
    }
    Ok(Scene {
        title: raw.title.unwrap_or_else(|| file.to_owned()),
        description: raw.description.unwrap_or_default(),
        c,
        table,
        restitution,
        effects,
        optics,
        before_start,
        pucks,
        observers,
    })
}

impl Checker<'_> {
    /// An error unless every component of `p` is within
    /// [`MAX_OBSERVER_DISTANCE`] of the board's origin.
    fn near<T>(&mut self, at: &At<T>, field: &str, p: DVec3) {
        if p.abs().max_element() > MAX_OBSERVER_DISTANCE {
            self.error(
                at,
                field,
                format!(
                    "({}, {}, {}) m is too far: keep each coordinate within ±{} m",
                    number(p.x),
                    number(p.y),
                    number(p.z),
                    number(MAX_OBSERVER_DISTANCE)
                ),
            );
        }
    }
}

/// `[a, b, …]` with each number as [`number`] writes it.
fn list(x: &[f64]) -> String {
    let parts: Vec<String> = x.iter().map(|v| number(*v)).collect();
    format!("[{}]", parts.join(", "))
}

fn effects(raw: super::raw::RawEffects) -> Effects {
    let d = Effects::default();
    Effects {
        contraction: raw.contraction.unwrap_or(d.contraction),
        light_delay: raw.light_delay.unwrap_or(d.light_delay),
        aberration: raw.aberration.unwrap_or(d.aberration),
        doppler: raw.doppler.unwrap_or(d.doppler),
        searchlight: raw.searchlight.unwrap_or(d.searchlight),
        time_dilation: raw.time_dilation.unwrap_or(d.time_dilation),
    }
}

fn optics(ck: &mut Checker, raw: super::raw::RawOptics) -> super::model::OpticsSpec {
    let mut o = super::model::OpticsSpec::default();
    if let Some(m) = &raw.method {
        match m.get_ref().as_str() {
            "exact" => o.sampled = false,
            "sampled" => o.sampled = true,
            other => ck.error(
                m,
                "optics.method",
                format!("\"{other}\" is not a method: use \"exact\" or \"sampled\""),
            ),
        }
    }
    if let Some(f) = &raw.history_frames {
        match usize::try_from(*f.get_ref()) {
            Ok(n) if (2..=MAX_HISTORY_FRAMES).contains(&n) => o.history_frames = n,
            _ => ck.error(
                f,
                "optics.history_frames",
                format!(
                    "{} must be at least 2 and at most {MAX_HISTORY_FRAMES}",
                    f.get_ref()
                ),
            ),
        }
    }
    if let Some(d) = &raw.dichotomy_steps {
        match u32::try_from(*d.get_ref()) {
            Ok(n) if n <= MAX_DICHOTOMY_STEPS => o.dichotomy_steps = n,
            _ => ck.error(
                d,
                "optics.dichotomy_steps",
                format!(
                    "{} must be 0 (full) or more, at most {MAX_DICHOTOMY_STEPS}",
                    d.get_ref()
                ),
            ),
        }
    }
    if let Some(i) = raw.interpolate {
        o.interpolate = i;
    }
    o
}

fn puck(
    ck: &mut Checker,
    at: &At<RawPuck>,
    i: usize,
    c: f64,
    names: &mut HashSet<String>,
) -> PuckSpec {
    let p = at.get_ref();
    let prefix = format!("puck[{i}]");
    let name = ck.name(
        p.name.as_ref(),
        &format!("{prefix}.name"),
        format!("puck{}", i + 1),
        names,
    );
    let position = ck
        .finite::<2>(&p.position, &format!("{prefix}.position"))
        .map_or(DVec2::ZERO, DVec2::from);
    let u = ck.motion::<2>(
        at,
        &prefix,
        p.beta.as_ref(),
        p.velocity.as_ref(),
        p.u.as_ref(),
        c,
    );
    let radius = ck.in_range(
        p.radius.as_ref(),
        &format!("{prefix}.radius"),
        DEFAULT_RADIUS,
        LENGTH_RANGE,
        "m",
    );
    let height = ck.in_range(
        p.height.as_ref(),
        &format!("{prefix}.height"),
        DEFAULT_HEIGHT,
        LENGTH_RANGE,
        "m",
    );
    let mass = ck.in_range(
        p.mass.as_ref(),
        &format!("{prefix}.mass"),
        DEFAULT_MASS,
        MASS_RANGE,
        "kg",
    );
    let color = match &p.color {
        None => Color::default_for(i),
        Some(s) => Color::parse(s.get_ref()).unwrap_or_else(|| {
            ck.error(
                s,
                &format!("{prefix}.color"),
                format!(
                    "\"{}\" is not a colour: use \"#rrggbb\" or a name such as \"red\"",
                    s.get_ref()
                ),
            );
            Color::default_for(i)
        }),
    };
    PuckSpec {
        name,
        position,
        u,
        radius,
        height,
        mass,
        color,
    }
}

fn observer(
    ck: &mut Checker,
    at: &At<RawObserver>,
    i: usize,
    c: f64,
    names: &mut HashSet<String>,
) -> ObserverSpec {
    let o = at.get_ref();
    let prefix = format!("observer[{i}]");
    let name = ck.name(
        o.name.as_ref(),
        &format!("{prefix}.name"),
        format!("observer{}", i + 1),
        names,
    );
    let position = ck
        .finite::<3>(&o.position, &format!("{prefix}.position"))
        .map_or(DVec3::ZERO, DVec3::from);
    ck.near(&o.position, &format!("{prefix}.position"), position);
    let look_at = match &o.look_at {
        None => None,
        Some(l) => match ck
            .finite::<3>(l, &format!("{prefix}.look_at"))
            .map(DVec3::from)
        {
            Some(p) if p.distance(position) > 0.0 => {
                ck.near(l, &format!("{prefix}.look_at"), p);
                Some(p)
            }
            Some(_) => {
                ck.error(
                    l,
                    &format!("{prefix}.look_at"),
                    "must differ from `position`".to_owned(),
                );
                None
            }
            None => None,
        },
    };
    let u = ck.motion::<3>(at, &prefix, o.beta.as_ref(), None, o.u.as_ref(), c);
    ObserverSpec {
        name,
        position,
        look_at,
        u,
    }
}
