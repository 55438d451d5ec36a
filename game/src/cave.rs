//! The CAVE: a tracked head is the observer, and every wall of the CAVE gets
//! its own off-axis projection from that head (Kooima's generalized
//! perspective, in [`lightcone_tracker::cave`]).
//!
//! [`TrackedHead`] drains tracker samples into a [`Follower`], through a
//! child process that alone maps iceoryx2's shared memory
//! ([`crate::tracker_bridge`]: random bytes there may crash the child, never
//! the game) (which rejects NaN, out-of-order and stale samples, holds the
//! last good pose and One-Euro-filters the velocity) and drives the game's
//! eye: position from the pose, proper velocity from the filtered velocity,
//! viewing direction from the orientation. The velocity matters more than it
//! seems: aberration turns a velocity error δβ into a direction error of
//! about δβ radians, so unfiltered tracker noise at c = 1.4 m/s shakes the
//! whole picture (BENCHMARKS.md, "Tracker").
//!
//! The walls move with the observer: vertices are built in the observer's
//! rest frame relative to the eye (as for the desktop camera), and each wall
//! is placed in that frame by the tracker→board mapping. This is the paper's
//! approximation too: the physical CAVE is the observer's laboratory.
//!
//! The browser build (wasm32) has the walls' geometry, not the tracked
//! head (no bridge process there).

use std::path::Path;
#[cfg(not(target_arch = "wasm32"))]
use std::time::Instant;

use glam::{DMat3, DMat4, DQuat, DVec3, Mat4};
use lightcone_engine::ecs::Entity;
use lightcone_engine::spacetime::ProperVelocity;
use lightcone_tracker::cave::{CaveConfig, OutputEyes, TrackerToBoard, Wall};
#[cfg(not(target_arch = "wasm32"))]
use lightcone_tracker::follow::{Follower, FollowerConfig, FollowerOutput, TrackerStatus, Verdict};
#[cfg(not(target_arch = "wasm32"))]
use lightcone_tracker::{TrackerSample, unix_now_ns};

use crate::model::GameState;
#[cfg(not(target_arch = "wasm32"))]
use crate::tracker_bridge::{Bridge, BridgeState};
use lightcone_render::frame::{self, FrameVertex};
use lightcone_render::gpu::Gpu;
use lightcone_render::headless::{Image, Offscreen};

/// Where a head is when nobody is tracked: standing at the CAVE's centre,
/// eyes 1.7 m above its floor, facing the front wall (tracker space, y up).
pub const DEFAULT_HEAD: DVec3 = DVec3::new(0.0, 1.7, 0.0);

/// Near and far clip distances, tracker metres.
const NEAR: f64 = 0.05;
const FAR: f64 = 200.0;

/// Largest observer speed the tracker may give, as a fraction of c: a
/// tracker glitch must not produce a speed ≥ c.
const MAX_BETA: f64 = 0.99;

/// Where the tracker's origin goes without a CAVE file: on the floor
/// 0.8 m below the cloth, 1.3 m from the middle of the near long side, so a
/// head at 1.7 m stands where the default observer does.
pub fn desktop_map(table: glam::DVec2) -> TrackerToBoard {
    TrackerToBoard {
        origin: DVec3::new(table.x / 2.0, -1.3, -0.8),
        ..TrackerToBoard::default()
    }
}

#[cfg(not(target_arch = "wasm32"))]
/// How many latencies are kept (the newest).
const LATENCY_WINDOW: usize = 100_000;

#[cfg(not(target_arch = "wasm32"))]
/// A tracked head, driving the observer.
pub struct TrackedHead {
    service: String,
    bridge: Bridge,
    follower: Follower,
    /// Tracker → board placement.
    pub map: TrackerToBoard,
    output: Option<FollowerOutput>,
    /// Publish → observer-update delays of accepted samples, ns.
    latencies: Vec<u64>,
    /// The last velocity had to be capped below c.
    capped: bool,
    /// Publication times of the samples accepted since the last update.
    pending: Vec<u64>,
    /// Publication time of the newest sample accepted.
    newest: Option<u64>,
    received: u64,
    batch: Vec<TrackerSample>,
}

#[cfg(not(target_arch = "wasm32"))]
impl TrackedHead {
    /// Follows `service` through a `tracker-bridge` child of this very
    /// program. Never fails: a child that cannot start, dies or cannot
    /// open the service is retried, and the status says why.
    pub fn new(service: &str, map: TrackerToBoard) -> Self {
        Self::with_bridge(service, map, crate::tracker_bridge::this_program)
    }

    /// As [`TrackedHead::new`], with the bridge started by `make()` (plus
    /// `tracker-bridge --service NAME`): tests give the built `lightcone`.
    pub fn with_bridge(
        service: &str,
        map: TrackerToBoard,
        make: impl Fn() -> std::process::Command + Send + 'static,
    ) -> Self {
        Self {
            service: service.to_owned(),
            bridge: Bridge::new(service, make),
            follower: Follower::new(FollowerConfig::default()),
            map,
            output: None,
            latencies: Vec::new(),
            capped: false,
            pending: Vec::new(),
            newest: None,
            received: 0,
            batch: Vec::new(),
        }
    }

    /// Takes every sample that arrived, and brings the follower's view up
    /// to `now`. Returns the follower's output.
    pub fn poll(&mut self, now: Instant) -> FollowerOutput {
        self.batch.clear();
        self.bridge.poll(now, &mut self.batch);
        self.received += self.batch.len() as u64;
        for s in &self.batch {
            if self.follower.push(s, now) == Verdict::Accepted {
                self.pending.push(s.timestamp_ns);
                self.newest = Some(
                    self.newest
                        .map_or(s.timestamp_ns, |t| t.max(s.timestamp_ns)),
                );
            }
        }
        let out = self.follower.output(now);
        self.output = Some(out);
        out
    }

    /// The bridge process reading the tracker (its state, deaths, pid).
    pub fn bridge(&self) -> &Bridge {
        &self.bridge
    }

    /// The pose to use: the last good one, or `None` before any.
    pub fn output(&self) -> Option<FollowerOutput> {
        self.output
    }

    /// Moves the game's eye to the tracked head (plus `offset`, the
    /// player's own flight, board metres), with the filtered velocity plus
    /// the flight's `flight_v` (m/s). Holds the last good pose when the
    /// tracker is stale, lost or sends garbage; does nothing before the
    /// first good sample.
    pub fn drive(&mut self, game: &mut GameState, offset: DVec3, flight_v: DVec3) {
        let Some(out) = self.output else { return };
        let Some(pose) = out.pose else { return };
        let position = self.map.point(pose.position) + offset;
        if !position.is_finite() {
            return;
        }
        let head_v = self.map.rotation() * out.velocity * self.map.scale;
        self.capped = set_eye(game, position, head_v + flight_v);
        aim(game, &self.map, pose.orientation);
        // One latency per accepted sample: from its publication to this
        // update of the observer.
        let now = unix_now_ns();
        if self.latencies.len() + self.pending.len() > LATENCY_WINDOW {
            self.latencies.drain(..LATENCY_WINDOW / 2);
        }
        self.latencies
            .extend(self.pending.drain(..).map(|t| now.saturating_sub(t)));
    }

    /// Publication time (Unix ns) of the newest sample accepted, if any.
    pub fn newest_sample_ns(&self) -> Option<u64> {
        self.newest
    }

    /// The head in tracker space (the default head before any sample).
    pub fn head(&self) -> (DVec3, DQuat) {
        self.output
            .and_then(|o| o.pose)
            .map_or((DEFAULT_HEAD, DQuat::IDENTITY), |p| {
                (p.position, p.orientation)
            })
    }

    /// One line for the screen: service, health, samples.
    pub fn status_line(&self) -> String {
        let follower = self
            .output
            .map_or_else(|| "waiting".to_owned(), |o| o.status_line());
        let health = match self.bridge.state() {
            BridgeState::Restarting { reason } => {
                format!("{follower}; {reason}, restarting it")
            }
            BridgeState::Running { status } if status == "starting" && self.output.is_none() => {
                "waiting".to_owned()
            }
            BridgeState::Running { status } if !status.is_empty() && status != "starting" => {
                match self.output {
                    Some(_) => format!("{follower}; not connected: {status}"),
                    None => format!("not connected: {status}"),
                }
            }
            BridgeState::Running { .. } => follower,
        };
        let cap = if self.capped {
            " (speed capped at 0.99 c)"
        } else {
            ""
        };
        format!(
            "tracker {:?}: {health}{cap}; {} samples",
            self.service, self.received
        )
    }

    /// Publish → observer-update delays so far (ns), newest last.
    pub fn latencies(&self) -> &[u64] {
        &self.latencies
    }

    /// What the follower accepted, rejected and dropped so far.
    pub fn stats(&self) -> &lightcone_tracker::follow::FollowerStats {
        self.follower.stats()
    }

    /// The follower's status now.
    pub fn status(&self) -> Option<TrackerStatus> {
        self.output.map(|o| o.status)
    }
}

/// Puts the eye at `position` with velocity `v` (board frame), capped at
/// `MAX_BETA` (0.99) c, on its worldline at the live board time (a jump
/// to the pose: see [`GameState::move_eye`]); returns whether it had to be
/// capped.
pub fn set_eye(game: &mut GameState, position: DVec3, v: DVec3) -> bool {
    let c = game.scene.c;
    let mut v = if v.is_finite() { v } else { DVec3::ZERO };
    let capped = v.length() >= MAX_BETA * c;
    if capped {
        v = v.normalize() * MAX_BETA * c;
    }
    let u = ProperVelocity::try_from_velocity(v, c).unwrap_or(ProperVelocity::ZERO);
    game.move_eye(position, u);
    capped
}

/// Points the eye where a head with tracker orientation `q` looks (its
/// local −z).
fn aim(game: &mut GameState, map: &TrackerToBoard, q: DQuat) {
    let forward = map.rotation() * (q * DVec3::NEG_Z);
    if forward.is_finite() && forward.length() > 0.5 {
        game.eye = crate::model::FlyingEye::along(forward);
    }
}

/// Places the eye at tracker-space head `head` (orientation `q`), carried
/// by the flight (`offset`, `flight_v`).
fn place(
    game: &mut GameState,
    map: &TrackerToBoard,
    head: DVec3,
    q: DQuat,
    offset: DVec3,
    flight_v: DVec3,
) {
    set_eye(game, map.point(head) + offset, flight_v);
    aim(game, map, q);
}

/// A CAVE without a tracker: the head stands at [`DEFAULT_HEAD`], carried
/// by the flight.
pub fn place_untracked(game: &mut GameState, cave: &CaveConfig, offset: DVec3, flight_v: DVec3) {
    place(
        game,
        &cave.tracker,
        DEFAULT_HEAD,
        DQuat::IDENTITY,
        offset,
        flight_v,
    );
}

/// The matrix that takes eye-relative points (observer's frame, board axes,
/// board metres) to `wall`'s clip space, for an eye at `eye` (tracker
/// space). `None` when the eye is on or behind the wall's plane.
pub fn wall_view_proj(map: &TrackerToBoard, wall: &Wall, eye: DVec3) -> Option<Mat4> {
    let p = wall.projection(eye, NEAR, FAR).ok()?;
    if p.eye_distance <= 0.0 {
        return None;
    }
    // Eye-relative board vector → tracker vector: the inverse rotation and
    // scale, no translation; then back to absolute tracker coordinates.
    let linear = DMat4::from_mat3(DMat3::from_mat4(map.inverse_matrix()));
    let m = p.view_projection * DMat4::from_translation(eye) * linear;
    m.is_finite().then(|| m.as_mat4())
}

/// Which eye.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// Between the eyes (the desktop preview of the walls).
    Mono,
    /// Left eye.
    Left,
    /// Right eye.
    Right,
}

impl Side {
    /// `left` or `right`.
    pub fn name(self) -> &'static str {
        match self {
            Side::Mono => "mono",
            Side::Left => "left",
            Side::Right => "right",
        }
    }
}

/// The eyes an output needs drawn, each with its part of the output
/// (x, y, w, h as fractions of the output).
pub fn eye_viewports(eyes: OutputEyes) -> Vec<(Side, [f32; 4])> {
    match eyes {
        OutputEyes::Mono => vec![(Side::Mono, [0.0, 0.0, 1.0, 1.0])],
        OutputEyes::Left => vec![(Side::Left, [0.0, 0.0, 1.0, 1.0])],
        OutputEyes::Right => vec![(Side::Right, [0.0, 0.0, 1.0, 1.0])],
        OutputEyes::SideBySide => vec![
            (Side::Left, [0.0, 0.0, 0.5, 1.0]),
            (Side::Right, [0.5, 0.0, 0.5, 1.0]),
        ],
        OutputEyes::TopBottom => vec![
            (Side::Left, [0.0, 0.0, 1.0, 0.5]),
            (Side::Right, [0.0, 0.5, 1.0, 0.5]),
        ],
    }
}

/// The eyes every output of `cave` needs, each once, after `first` (the
/// main window's).
pub fn sides_needed(cave: &CaveConfig, first: Side) -> Vec<Side> {
    let mut sides = vec![first];
    for o in &cave.outputs {
        for (side, _) in eye_viewports(o.eyes) {
            if !sides.contains(&side) {
                sides.push(side);
            }
        }
    }
    sides
}

/// Where one stereo eye of the head is: tracker space, and board frame
/// (carried by the flight `offset`).
pub fn stereo_eye(
    cave: &CaveConfig,
    head: (DVec3, DQuat),
    side: Side,
    offset: DVec3,
) -> (DVec3, DVec3) {
    let (left, right) = cave.eyes(head.0, head.1);
    let e = match side {
        Side::Mono => head.0,
        Side::Left => left,
        Side::Right => right,
    };
    (e, cave.tracker.point(e) + offset)
}

/// Runs the game's frame for the stereo eyes `sides` of the head: each an
/// observer of the game's simulation, with a view of its own (the game's
/// effects). Returns each side's view entity and tracker-space eye.
pub fn stereo_views(
    game: &mut GameState,
    cave: &CaveConfig,
    head: (DVec3, DQuat),
    sides: &[Side],
    offset: DVec3,
) -> Vec<(Entity, DVec3)> {
    let eyes: Vec<(DVec3, DVec3)> = sides
        .iter()
        .map(|&side| stereo_eye(cave, head, side, offset))
        .collect();
    let boards: Vec<DVec3> = eyes.iter().map(|e| e.1).collect();
    game.run_stereo(&boards)
        .into_iter()
        .zip(eyes)
        .map(|(v, (tracker, _))| (v, tracker))
        .collect()
}

/// The vertices and matrix of one wall as the stereo view `view` (eye at
/// `tracker_eye`, tracker space) saw it at the last frame; `None` if the
/// eye cannot see the wall.
pub fn wall_frame(
    game: &GameState,
    cave: &CaveConfig,
    wall: &Wall,
    view: Entity,
    tracker_eye: DVec3,
    vertices: &mut Vec<FrameVertex>,
) -> Option<Mat4> {
    let m = wall_view_proj(&cave.tracker, wall, tracker_eye)?;
    frame::build_view(game.apparent(view)?, &game.meshes, vertices);
    Some(m)
}

/// Renders every wall for both eyes, headless, at `scale` × the walls'
/// projector resolution. Returns (wall, eye, image).
pub fn render_walls(
    gpu: &Gpu,
    game: &mut GameState,
    cave: &CaveConfig,
    head: (DVec3, DQuat),
    scale: f64,
) -> Result<Vec<(String, Side, Image)>, String> {
    let mut out = Vec::new();
    let mut vertices = Vec::new();
    let sides = [Side::Left, Side::Right];
    let views = stereo_views(game, cave, head, &sides, DVec3::ZERO);
    for wall in &cave.walls {
        let w = ((f64::from(wall.pixels[0]) * scale).round() as u32).clamp(1, 8192);
        let h = ((f64::from(wall.pixels[1]) * scale).round() as u32).clamp(1, 8192);
        let mut target = Offscreen::new(gpu, w, h);
        for (&side, &(view, tracker_eye)) in sides.iter().zip(&views) {
            vertices.clear();
            let m = wall_frame(game, cave, wall, view, tracker_eye, &mut vertices).ok_or_else(
                || {
                    format!(
                        "the {} eye is not in front of wall {:?}",
                        side.name(),
                        wall.name
                    )
                },
            )?;
            out.push((
                wall.name.clone(),
                side,
                target.draw_with(gpu, &vertices, m)?,
            ));
        }
    }
    Ok(out)
}

/// Loads a CAVE config, with the file named in any error.
pub fn load(path: &Path) -> Result<CaveConfig, String> {
    CaveConfig::from_path(path).map_err(|e| format!("{}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn example() -> CaveConfig {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/cave.toml");
        load(&path).unwrap()
    }

    /// A wall's corners, given to the renderer as eye-relative board
    /// vectors, land on the corners of clip space from any eye inside the
    /// CAVE: the walls stay glued to the screens as the head moves.
    #[test]
    fn wall_corners_map_to_the_screen_corners_from_any_eye() {
        let cave = example();
        let map = cave.tracker;
        for eye in [
            DEFAULT_HEAD,
            DVec3::new(0.7, 1.2, -0.4),
            DVec3::new(-1.1, 2.1, 1.0),
        ] {
            for wall in &cave.walls {
                let m = wall_view_proj(&map, wall, eye).unwrap();
                let corners = [
                    (wall.lower_left, (-1.0, -1.0)),
                    (wall.lower_right, (1.0, -1.0)),
                    (wall.upper_left, (-1.0, 1.0)),
                    (wall.upper_right(), (1.0, 1.0)),
                ];
                for (corner, (x, y)) in corners {
                    let rel = (map.point(corner) - map.point(eye)).as_vec3();
                    let clip = m * rel.extend(1.0);
                    let (nx, ny) = (clip.x / clip.w, clip.y / clip.w);
                    assert!(
                        (f64::from(nx) - x).abs() < 1e-4 && (f64::from(ny) - y).abs() < 1e-4,
                        "{} from {eye}: ({nx}, {ny}) for ({x}, {y})",
                        wall.name
                    );
                    assert!(clip.z / clip.w > 0.0 && clip.z / clip.w < 1.0);
                }
            }
        }
    }

    #[test]
    fn an_eye_outside_a_wall_sees_nothing_on_it() {
        let cave = example();
        let front = cave.wall("front").unwrap();
        assert!(wall_view_proj(&cave.tracker, front, DVec3::new(0.0, 1.7, -2.0)).is_none());
    }
}
