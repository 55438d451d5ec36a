//! The JSON shapes of what the physics did, shared by `lightcone simulate`
//! and the Python API. Documented in the guide (docs/guide/src/commands.md).
//!
//! Velocities are given twice: `u`, the proper velocity γβ (the engine's
//! exact state), and `beta`, for reading. Vectors on the board are `[x, y]`.

use serde::Serialize;

use crate::physics::{Billiard, Collision, CollisionKind, PuckOutcome};

/// One collision line.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CollisionLine {
    /// `"puck_puck"` or `"cushion"`.
    pub kind: &'static str,
    /// Which cushion (`"x0"`, `"x1"`, `"y0"`, `"y1"`), for a cushion hit.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cushion: Option<&'static str>,
    /// Board time of the contact, s.
    pub t: f64,
    /// Contact point, m.
    pub contact: [f64; 2],
    /// Each puck's own velocity-change event.
    pub pucks: Vec<PuckLine>,
    /// Present and `true` for several contacts at one board time,
    /// resolved together: `pucks` holds every puck of the group.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub simultaneous: bool,
    /// With `simultaneous`, each pair in contact, as indices into `pucks`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub pairs: Vec<[usize; 2]>,
}

/// One puck's part in a collision.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PuckLine {
    /// Puck name.
    pub name: String,
    /// Board time of this puck's velocity change, s.
    pub t: f64,
    /// Its centre then, m.
    pub position: [f64; 2],
    /// Proper velocity γβ before.
    pub u_before: [f64; 2],
    /// Proper velocity γβ after.
    pub u_after: [f64; 2],
    /// β before.
    pub beta_before: [f64; 2],
    /// β after.
    pub beta_after: [f64; 2],
    /// Rest mass before, kg: only when an inelastic collision changed it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mass_before: Option<f64>,
    /// Rest mass after, kg: only when an inelastic collision changed it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mass_after: Option<f64>,
    /// Rest-frame orientation after the change, radians counter-clockwise
    /// from the board's +x (the accumulated Thomas–Wigner rotation; 0 at
    /// t = 0).
    pub orientation: f64,
    /// Present and true when this puck's velocity change was still ahead
    /// at the end of the run (the second kick of a contact): `t` and
    /// `u_after` are the scheduled ones.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub pending: bool,
}

/// The last line: every puck at the end of the run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StateLine {
    /// Always `"state"`.
    pub kind: &'static str,
    /// Board time, s.
    pub t: f64,
    /// Every puck, in scene order.
    pub pucks: Vec<PuckState>,
}

/// A puck at one board time.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PuckState {
    /// Puck name.
    pub name: String,
    /// Centre, m.
    pub position: [f64; 2],
    /// Proper velocity γβ.
    pub u: [f64; 2],
    /// β.
    pub beta: [f64; 2],
    /// Proper time, s.
    pub proper_time: f64,
    /// Rest-frame orientation, radians counter-clockwise from the board's
    /// +x (the accumulated Thomas–Wigner rotation; 0 at t = 0).
    pub orientation: f64,
}

fn xy(v: glam::DVec3) -> [f64; 2] {
    [v.x, v.y]
}

impl PuckLine {
    fn new(billiard: &Billiard, o: &PuckOutcome) -> Self {
        let changed = o.mass_before != o.mass_after;
        Self {
            name: billiard.name(o.puck).to_owned(),
            t: o.t,
            position: xy(o.position),
            u_before: xy(o.u_before.0),
            u_after: xy(o.u_after.0),
            beta_before: xy(o.u_before.beta()),
            beta_after: xy(o.u_after.beta()),
            mass_before: changed.then_some(o.mass_before),
            mass_after: changed.then_some(o.mass_after),
            orientation: o.orientation_after,
            pending: o.pending,
        }
    }
}

impl CollisionLine {
    /// The line for `collision`.
    #[must_use]
    pub fn new(billiard: &Billiard, collision: &Collision) -> Self {
        let (kind, cushion) = match collision.kind {
            CollisionKind::PuckPuck => ("puck_puck", None),
            CollisionKind::Cushion(c) => ("cushion", Some(c.name())),
        };
        Self {
            kind,
            cushion,
            t: collision.t,
            contact: xy(collision.contact),
            pucks: collision
                .pucks
                .iter()
                .map(|o| PuckLine::new(billiard, o))
                .collect(),
            simultaneous: collision.simultaneous,
            pairs: collision.pairs.clone(),
        }
    }
}

impl StateLine {
    /// Every puck at board time `t` (≤ the billiard's time).
    #[must_use]
    pub fn new(billiard: &Billiard, t: f64) -> Self {
        Self {
            kind: "state",
            t,
            pucks: (0..billiard.len())
                .map(|i| {
                    let s = billiard.worldline(i).state_at(t);
                    PuckState {
                        name: billiard.name(i).to_owned(),
                        position: xy(s.position),
                        u: xy(s.u.0),
                        beta: xy(s.u.beta()),
                        proper_time: s.proper_time,
                        orientation: s.orientation,
                    }
                })
                .collect(),
        }
    }
}

/// `lightcone observe` output: what one observer sees at board time `t`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ObserveReport {
    /// Board time of the observation, s.
    pub t: f64,
    /// The observer then.
    pub observer: ObserverLine,
    /// Every puck as seen.
    pub pucks: Vec<SeenPuck>,
}

/// The observer at the observation event.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ObserverLine {
    /// Name.
    pub name: String,
    /// Eye position, board frame, m.
    pub position: [f64; 3],
    /// β.
    pub beta: [f64; 3],
    /// Proper time, s.
    pub proper_time: f64,
}

/// An emission event.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EmissionLine {
    /// Board time, s.
    pub t: f64,
    /// Board position, m.
    pub position: [f64; 3],
}

/// One point as seen.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SeenPoint {
    /// Where and when its light left.
    pub emission: EmissionLine,
    /// Unit vector from the observer, in its rest frame.
    pub direction: [f64; 3],
    /// Apparent distance in the observer's rest frame, m.
    pub distance: f64,
    /// Observed / emitted frequency (> 1 approaching); 1 when the doppler
    /// effect is off.
    pub doppler: f64,
    /// Searchlight intensity factor D⁴; 1 when the effect is off.
    pub intensity: f64,
}

/// One puck as seen.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SeenPuck {
    /// Name.
    pub name: String,
    /// Its centre at mid-height.
    #[serde(flatten)]
    pub centre: SeenPoint,
    /// The proper time its clock shows in the image, s.
    pub seen_proper_time: f64,
    /// Its rest-frame orientation in the image (at the centre's emission
    /// event), radians counter-clockwise from the board's +x: the
    /// accumulated Thomas–Wigner rotation, 0 at t = 0.
    pub orientation: f64,
    /// Every mesh vertex, only when asked for.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vertices: Option<Vec<SeenPoint>>,
}

fn xyz(v: glam::DVec3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

impl SeenPoint {
    /// Point `i` of a body as a view of the frame schedule saw it.
    #[must_use]
    pub fn of_apparent(body: &crate::ecs::ApparentBody, i: usize) -> Self {
        let e = body.emissions[i];
        let s = body.seen[i];
        Self {
            emission: EmissionLine {
                t: e.event.t,
                position: xyz(e.event.position),
            },
            direction: xyz(s.direction()),
            distance: s.distance,
            doppler: s.doppler,
            intensity: body.intensity[i],
        }
    }
}

impl ObserveReport {
    /// The report of what `view` of `sim` saw at its last frame (pucks
    /// only; the fixtures are not listed), with every vertex if
    /// `with_vertices`. `None` if `view` is not a view or saw nothing.
    pub fn of_view(
        sim: &crate::ecs::Simulation,
        view: bevy_ecs::entity::Entity,
        with_vertices: bool,
    ) -> Option<Self> {
        use crate::ecs::BodyRef;
        let apparent = sim.apparent(view)?;
        let eye = apparent.eye?;
        let observer = sim.observer_of(view)?;
        let worldline = sim.observer_worldline(observer)?;
        let name = sim
            .world
            .get::<crate::ecs::components::BodyName>(observer)?;
        let billiard = sim.physics();
        Some(Self {
            t: eye.event.t,
            observer: ObserverLine {
                name: name.0.clone(),
                position: xyz(eye.event.position),
                beta: xyz(eye.u.beta()),
                proper_time: worldline.proper_time_at(eye.event.t),
            },
            pucks: apparent
                .bodies
                .iter()
                .filter_map(|b| match b.body {
                    BodyRef::Puck(i) => Some((i, b)),
                    BodyRef::Fixture(_) => None,
                })
                .map(|(i, b)| SeenPuck {
                    name: billiard.name(i).to_owned(),
                    centre: SeenPoint::of_apparent(b, b.centre()),
                    seen_proper_time: b.seen_proper_time,
                    orientation: billiard
                        .worldline(i)
                        .state_at(b.emissions[b.centre()].event.t)
                        .orientation,
                    vertices: with_vertices.then(|| {
                        (0..b.vertex_count())
                            .map(|k| SeenPoint::of_apparent(b, k))
                            .collect()
                    }),
                })
                .collect(),
        })
    }
}
