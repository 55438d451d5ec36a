//! From the file as written to a [`Scene`]: every rule of [`super::rules`]
//! applied to the file's values, each failure located at its value.

use glam::{DVec2, DVec3};

use std::collections::{BTreeMap, HashSet};

use super::error::number;
use super::model::{DEFAULT_HEIGHT, DEFAULT_MASS, DEFAULT_RADIUS, DEFAULT_TABLE};
use super::overlap::first_overlaps;
use super::raw::{At, RawObserver, RawPuck, RawScene};
use super::rules::{self, BuildError, MAX_OBSERVERS, MAX_PUCKS, Quantity};
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
    /// An error at `at` that is no scene rule (a word not allowed, …).
    fn error<T>(&mut self, at: &At<T>, field: &str, message: String) {
        self.error_of_kind(at, field, message, None, kind_of(field));
    }

    /// `rule` broken at `at`: its message, and the rule kept.
    fn broke<T>(&mut self, at: &At<T>, field: &str, rule: BuildError) {
        self.error_of_kind(at, field, rule.to_string(), Some(rule), kind_of(field));
    }

    fn error_of_kind<T>(
        &mut self,
        at: &At<T>,
        field: &str,
        message: String,
        rule: Option<BuildError>,
        kind: String,
    ) {
        self.count += 1;
        let seen = self.seen.entry(kind).or_insert(0);
        *seen += 1;
        if *seen <= MAX_ERRORS_PER_KIND {
            let e = SceneError::at(self.file, self.text, at.span().start, field, message);
            self.errors.push(match rule {
                Some(rule) => e.breaking(rule),
                None => e,
            });
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

    /// The value of `quantity` at `v`, `default` when absent, `refused`
    /// (and an error) when out of range.
    fn in_range(
        &mut self,
        v: Option<&At<f64>>,
        field: &str,
        default: f64,
        quantity: Quantity,
        refused: f64,
    ) -> f64 {
        let Some(v) = v else { return default };
        quantity.check(*v.get_ref()).unwrap_or_else(|e| {
            self.broke(v, field, e);
            refused
        })
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
        match rules::finite(&a) {
            Ok(()) => Some(a),
            Err(e) => {
                self.broke(v, field, e);
                None
            }
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
            self.broke(at, &format!("{prefix}.beta"), BuildError::TwoSpeeds);
            return ProperVelocity::ZERO;
        }
        let to3 = |x: [f64; N]| DVec3::from_slice(&[x.as_slice(), &[0.0; 3]].concat()[..3]);
        let (given, field) = match (beta, velocity, u) {
            (Some(b), _, _) => (b, "beta"),
            (_, Some(v), _) => (v, "velocity"),
            (_, _, Some(u)) => (u, "u"),
            _ => return ProperVelocity::ZERO,
        };
        let field = format!("{prefix}.{field}");
        let Some(x) = self.finite::<N>(given, &field) else {
            return ProperVelocity::ZERO;
        };
        let x = Some(to3(x));
        let pick = |g: Option<&At<Vec<f64>>>| if g.is_some() { x } else { None };
        rules::motion(pick(beta), pick(velocity), pick(u), c).unwrap_or_else(|e| {
            self.broke(given, &field, e);
            ProperVelocity::ZERO
        })
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
        match rules::name(&s, |s| taken.contains(s)) {
            Ok(()) => {
                taken.insert(s.clone());
                s
            }
            Err(e) => {
                let empty = e == BuildError::EmptyName;
                self.broke(n, field, e);
                if empty { fallback } else { s }
            }
        }
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
    for (what, spans, max) in [
        (
            "puck",
            raw.puck.iter().map(At::span).collect::<Vec<_>>(),
            MAX_PUCKS,
        ),
        (
            "observer",
            raw.observer.iter().map(At::span).collect(),
            MAX_OBSERVERS,
        ),
    ] {
        if spans.len() > max {
            let rule = BuildError::TooMany {
                what: if what == "puck" { "pucks" } else { "observers" },
                count: spans.len(),
                max,
            };
            let e = SceneError::at(
                file,
                text,
                spans[max].start,
                &format!("{what}[{max}]"),
                rule.to_string(),
            );
            return Err(SceneErrors::single(e.breaking(rule)));
        }
    }

    let size = match raw.table.as_ref().and_then(|t| t.size.as_ref()) {
        Some(s) => match ck.finite::<2>(s, "table.size") {
            Some(x) => rules::table_size(DVec2::from(x)).unwrap_or_else(|e| {
                ck.broke(s, "table.size", e);
                DVec2::from(DEFAULT_TABLE)
            }),
            None => DVec2::from(DEFAULT_TABLE),
        },
        None => DVec2::from(DEFAULT_TABLE),
    };
    let table_raw = raw.table.as_ref();
    let cushion_restitution = ck.in_range(
        table_raw.and_then(|t| t.cushion_restitution.as_ref()),
        "table.cushion_restitution",
        1.0,
        Quantity::Restitution,
        1.0,
    );
    let friction = ck.in_range(
        table_raw.and_then(|t| t.friction.as_ref()),
        "table.friction",
        TableSpec::CAROM_CLOTH_FRICTION,
        Quantity::Friction,
        0.0,
    );
    let gravity = ck.in_range(
        table_raw.and_then(|t| t.gravity.as_ref()),
        "table.gravity",
        TableSpec::STANDARD_GRAVITY,
        Quantity::Gravity,
        TableSpec::STANDARD_GRAVITY,
    );
    let table = TableSpec {
        size,
        cushion_restitution,
        friction,
        gravity,
    };
    let default_c = Scene::default_c(size);
    let c = ck.in_range(raw.c.as_ref(), "c", default_c, Quantity::C, default_c);
    let restitution = ck.in_range(
        raw.physics.as_ref().and_then(|p| p.restitution.as_ref()),
        "physics.restitution",
        1.0,
        Quantity::Restitution,
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
        if let Err(e) = rules::on_table(&table, &p) {
            ck.broke(&at.get_ref().position, &format!("puck[{i}].position"), e);
        }
        pucks.push(p);
        puck_spans.push((i, at));
    }
    // Born-rigid braking needs every puck shorter than c²/(μg) (the
    // braking's Rindler horizon; see worldline::sliding). Located at the
    // table's `friction` when the file gives it, else at the puck's radius
    // (or position), naming the default.
    if let Some((k, rule)) = rules::braking_horizon(c, table.friction, table.gravity, &pucks) {
        match table_raw.and_then(|t| t.friction.as_ref()) {
            Some(v) => ck.broke(v, "table.friction", rule),
            None => {
                let (i, at) = puck_spans[k];
                let puck = at.get_ref();
                let why = format!(
                    "{rule} (friction {} is the default, a carom cloth: write \
                     [table] friction = 0 for a frictionless table)",
                    number(table.friction)
                );
                match &puck.radius {
                    Some(r) => {
                        let field = format!("puck[{i}].radius");
                        ck.error_of_kind(r, &field, why, Some(rule), kind_of(&field));
                    }
                    None => {
                        let field = format!("puck[{i}].position");
                        ck.error_of_kind(&puck.position, &field, why, Some(rule), kind_of(&field));
                    }
                }
            }
        }
    }
    for (i, j) in first_overlaps(&pucks) {
        let (a, b) = (&pucks[i], &pucks[j]);
        let rule = BuildError::Overlap {
            puck: b.name.clone(),
            other: a.name.clone(),
            other_line: Some(super::error::line_column(text, puck_spans[i].1.span().start).0),
            distance: a.position.distance(b.position),
            reach: a.radius + b.radius,
        };
        ck.error_of_kind(
            &puck_spans[j].1.get_ref().position,
            &format!("puck[{}].position", puck_spans[j].0),
            rule.to_string(),
            Some(rule),
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
    /// [`rules::MAX_OBSERVER_DISTANCE`] of the board's origin.
    fn near<T>(&mut self, at: &At<T>, field: &str, p: DVec3) {
        if let Err(e) = rules::near(p) {
            self.broke(at, field, e);
        }
    }
}

/// The kind an error of `field` is counted under: the field with its
/// indices removed (`puck[].mass`).
fn kind_of(field: &str) -> String {
    field
        .split('[')
        .map(|part| part.split_once(']').map_or(part, |(_, rest)| rest))
        .collect::<Vec<_>>()
        .join("[]")
}

/// `[a, b, …]` with each number as [`number`] writes it.
fn list(x: &[f64]) -> String {
    rules::list(x)
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
    // Counts: exact as f64 up to 2⁵³, far beyond both bounds.
    if let Some(f) = &raw.history_frames {
        match Quantity::HistoryFrames.check(*f.get_ref() as f64) {
            Ok(n) => o.history_frames = n as usize,
            Err(e) => ck.broke(f, "optics.history_frames", e),
        }
    }
    if let Some(d) = &raw.dichotomy_steps {
        match Quantity::DichotomySteps.check(*d.get_ref() as f64) {
            Ok(n) => o.dichotomy_steps = n as u32,
            Err(e) => ck.broke(d, "optics.dichotomy_steps", e),
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
        Quantity::Length,
        DEFAULT_RADIUS,
    );
    let height = ck.in_range(
        p.height.as_ref(),
        &format!("{prefix}.height"),
        DEFAULT_HEIGHT,
        Quantity::Length,
        DEFAULT_HEIGHT,
    );
    let mass = ck.in_range(
        p.mass.as_ref(),
        &format!("{prefix}.mass"),
        DEFAULT_MASS,
        Quantity::Mass,
        DEFAULT_MASS,
    );
    let color = match &p.color {
        None => Color::default_for(i),
        Some(s) => rules::color(s.get_ref()).unwrap_or_else(|e| {
            ck.broke(s, &format!("{prefix}.color"), e);
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
                ck.broke(l, &format!("{prefix}.look_at"), BuildError::LookAtEye);
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
