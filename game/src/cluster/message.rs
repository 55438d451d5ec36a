//! What the master and the render nodes of a CAVE cluster say to each
//! other, and how the master's game is copied into a node's.
//!
//! Every message is [postcard]-encoded (binary, each `f64` exact). A
//! [`Frame`] carries what a node needs to draw one frame exactly as the
//! master would: the game's view state (board times, the free eye, the
//! effects, the tracked head and the flight) and every change to the pucks'
//! worldlines since the previous frame, as copied segments ([`Change`]). A
//! node's billiard is driven from outside
//! ([`Billiard::drive_from_outside`]): it predicts nothing, so its
//! worldlines are the master's bit for bit, and its own frame schedule (the
//! same code as the master's) computes the same apparent vertices. A
//! [`Snapshot`] starts a node (when it joins, after a gap, and when the
//! master's game is restarted or replaced).
//!
//! [`Billiard::drive_from_outside`]: lightcone_engine::physics::Billiard::drive_from_outside

use glam::{DQuat, DVec3};
use lightcone_engine::scene::{Effects, Scene};
use lightcone_engine::spacetime::ProperVelocity;
use lightcone_engine::worldline::{Segment, Worldline};
use serde::{Deserialize, Serialize};

use crate::model::{FlyingEye, Framing, GameState};

/// The game's state that the pictures of the CAVE walls depend on, besides
/// the worldlines.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ViewState {
    /// Board time the physics has reached, s.
    pub live_time: f64,
    /// Board time shown, s.
    pub view_time: f64,
    /// Time stands still.
    pub paused: bool,
    /// The free eye watches the past from where it is now.
    pub replay_and_move: bool,
    /// The free eye's position, board frame, m.
    pub eye_position: DVec3,
    /// The free eye's proper velocity `γβ` (dimensionless), board frame.
    pub eye_u: DVec3,
    /// The free eye's yaw, radians.
    pub eye_yaw: f64,
    /// The free eye's pitch, radians.
    pub eye_pitch: f64,
    /// Effects shown.
    pub effects: Effects,
    /// Camera aim: `true` where the free eye looks, `false` fitted.
    pub look: bool,
    /// Zoom factor.
    pub zoom: f64,
    /// The puck the camera keeps in the middle, if any.
    pub follow: Option<usize>,
    /// The tracked head's position, tracker space, m.
    pub head_position: DVec3,
    /// The tracked head's orientation (tracker space).
    pub head_orientation: DQuat,
    /// The player's own flight added to the head (board metres).
    pub flight: DVec3,
}

impl ViewState {
    /// The state of `game` with the head `head` and flight `flight`.
    pub fn of(game: &GameState, head: (DVec3, DQuat), flight: DVec3) -> Self {
        Self {
            live_time: game.live_time,
            view_time: game.view_time,
            paused: game.paused,
            replay_and_move: game.replay_and_move,
            eye_position: game.eye_position(),
            eye_u: game.eye_velocity().0,
            eye_yaw: game.eye.yaw,
            eye_pitch: game.eye.pitch,
            effects: game.effects,
            look: game.framing == Framing::Look,
            zoom: game.zoom,
            follow: game.follow,
            head_position: head.0,
            head_orientation: head.1,
            flight,
        }
    }

    /// Sets it on `game` (a node's copy).
    pub fn apply(&self, game: &mut GameState) {
        game.live_time = self.live_time;
        game.view_time = self.view_time;
        game.paused = self.paused;
        game.eye = FlyingEye {
            yaw: self.eye_yaw,
            pitch: self.eye_pitch,
        };
        // On the node's copy of the eye's worldline, at the master's live
        // time; the master says whether it replays and moves.
        game.move_eye(self.eye_position, ProperVelocity(self.eye_u));
        game.replay_and_move = self.replay_and_move;
        game.effects = self.effects;
        game.framing = if self.look {
            Framing::Look
        } else {
            Framing::Fit
        };
        game.zoom = self.zoom;
        game.follow = self.follow;
    }

    /// Whether every number is finite (a state received from elsewhere is
    /// checked before use).
    pub fn is_finite(&self) -> bool {
        [
            self.live_time,
            self.view_time,
            self.eye_yaw,
            self.eye_pitch,
            self.zoom,
        ]
        .iter()
        .all(|x| x.is_finite())
            && self.eye_position.is_finite()
            && self.eye_u.is_finite()
            && self.head_position.is_finite()
            && self.head_orientation.is_finite()
            && self.flight.is_finite()
    }

    /// The head, as [`crate::cave::stereo_views`] takes it.
    pub fn head(&self) -> (DVec3, DQuat) {
        (self.head_position, self.head_orientation)
    }
}

/// A change to one puck's worldline since the last frame.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Change {
    /// New segments after the last one sent.
    Append {
        /// The puck's index.
        puck: usize,
        /// Its new segments, in time order.
        segments: Vec<Segment>,
    },
    /// The whole worldline (rewritten otherwise than by new segments).
    Replace {
        /// The puck's index.
        puck: usize,
        /// Its worldline.
        worldline: Worldline,
    },
}

/// One frame from the master.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Frame {
    /// Frame number, from 1, one more each frame the master draws.
    pub seq: u64,
    /// The master's game ([`GameState::generation`]): a frame of another
    /// generation than the node's snapshot needs a new snapshot.
    pub generation: u64,
    /// What the pictures depend on.
    pub view: ViewState,
    /// The worldlines' changes since frame `seq − 1`.
    pub changes: Vec<Change>,
    /// Publication time (Unix ns) of the newest tracker sample the head
    /// came from, if any: the start of the tracker-to-picture latency.
    pub sample_ns: Option<u64>,
    /// When the master sent it (Unix ns).
    pub sent_ns: u64,
}

/// Everything a node needs to start: the scene, the CAVE, the worldlines,
/// and the frame they are at.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Snapshot {
    /// The frame it is the state after.
    pub seq: u64,
    /// The master's game generation.
    pub generation: u64,
    /// The scene as JSON (its serde form; exact floats).
    pub scene_json: String,
    /// The CAVE file's text.
    pub cave_toml: String,
    /// Every puck's worldline, in index order.
    pub worldlines: Vec<Worldline>,
    /// The view state of frame `seq`.
    pub view: ViewState,
}

/// A node's answer: it has computed (`ready`) or shown (`shown`) frame
/// `seq`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Ready {
    /// The node's name (`WALLS-ID`).
    pub node: String,
    /// The frame.
    pub seq: u64,
}

/// Encodes a message.
pub fn encode<T: Serialize>(message: &T) -> Vec<u8> {
    // Encoding into a Vec fails only on a type serde cannot write, which
    // these are not.
    postcard::to_stdvec(message).unwrap_or_default()
}

/// Decodes a message; the error names what was expected.
pub fn decode<'a, T: Deserialize<'a>>(bytes: &'a [u8], what: &str) -> Result<T, String> {
    postcard::from_bytes(bytes)
        .map_err(|e| format!("a malformed {what} ({} bytes): {e}", bytes.len()))
}

/// What the master last sent of each puck's worldline, to send only what
/// changed.
#[derive(Default)]
pub struct Sent {
    generation: u64,
    last: Vec<Option<Segment>>,
}

impl Sent {
    /// The changes of `game`'s worldlines since the last call (everything
    /// after a new generation).
    pub fn changes(&mut self, game: &GameState) -> Vec<Change> {
        let physics = game.physics();
        if self.generation != game.generation || self.last.len() != physics.len() {
            self.generation = game.generation;
            self.last = vec![None; physics.len()];
        }
        let mut out = Vec::new();
        for (puck, last) in self.last.iter_mut().enumerate() {
            let w = physics.worldline(puck);
            let segments = w.segments();
            let known = last.and_then(|s| {
                let k = w.segment_index_at(s.start.t);
                (segments[k] == s).then_some(k)
            });
            match known {
                Some(k) if k + 1 == segments.len() => {}
                Some(k) => out.push(Change::Append {
                    puck,
                    segments: segments[k + 1..].to_vec(),
                }),
                None => out.push(Change::Replace {
                    puck,
                    worldline: w.clone(),
                }),
            }
            *last = segments.last().copied();
        }
        out
    }
}

/// The snapshot of `game` after frame `seq`.
pub fn snapshot(game: &GameState, seq: u64, cave_toml: &str, view: ViewState) -> Snapshot {
    let physics = game.physics();
    Snapshot {
        seq,
        generation: game.generation,
        scene_json: serde_json::to_string(&game.scene).unwrap_or_default(),
        cave_toml: cave_toml.to_owned(),
        worldlines: (0..physics.len())
            .map(|i| physics.worldline(i).clone())
            .collect(),
        view,
    }
}

/// A node's copy of the master's game, built from `snapshot`: the scene's
/// game with its billiard driven from outside and the master's worldlines.
pub fn game_of(snapshot: &Snapshot) -> Result<GameState, String> {
    let scene: Scene = serde_json::from_str(&snapshot.scene_json)
        .map_err(|e| format!("the master's scene does not read: {e}"))?;
    check_scene(&scene)?;
    if !snapshot.view.is_finite() {
        return Err("the master's snapshot: a view state that is not finite".into());
    }
    for (i, w) in snapshot.worldlines.iter().enumerate() {
        w.check()
            .map_err(|e| format!("the master's snapshot: puck {i}: {e}"))?;
    }
    if scene.pucks.len() != snapshot.worldlines.len() {
        return Err(format!(
            "the master's scene has {} pucks but {} worldlines",
            scene.pucks.len(),
            snapshot.worldlines.len()
        ));
    }
    let mut game = GameState::new(scene);
    game.physics_mut().drive_from_outside();
    for (i, w) in snapshot.worldlines.iter().enumerate() {
        game.physics_mut().replace_worldline(i, w.clone());
    }
    game.generation = snapshot.generation;
    snapshot.view.apply(&mut game);
    Ok(game)
}

/// Checks the numbers of a scene received from the master that reach the
/// engine (a scene file is checked field by field when read; this one comes
/// as data): the error names the field.
fn check_scene(scene: &Scene) -> Result<(), String> {
    let bad = |what: String| Err(format!("the master's scene: {what} is out of range"));
    if !(scene.c.is_finite() && scene.c > 0.0) {
        return bad("c".into());
    }
    let size = scene.table.size;
    if !(size.is_finite() && size.x > 0.0 && size.y > 0.0) {
        return bad("the table's size".into());
    }
    for p in &scene.pucks {
        let ok = p.position.is_finite()
            && p.u.is_finite()
            && [p.radius, p.height, p.mass]
                .iter()
                .all(|x| x.is_finite() && *x > 0.0);
        if !ok {
            return bad(format!("puck {:?}", p.name));
        }
    }
    Ok(())
}

/// Applies `frame`'s changes and view state to a node's `game`. Fails on a
/// change that does not fit (a puck that is not there, a segment before
/// the last): the node then needs a new snapshot.
pub fn apply(frame: &Frame, game: &mut GameState) -> Result<(), String> {
    if !frame.view.is_finite() {
        return Err(format!(
            "frame {}: a view state that is not finite",
            frame.seq
        ));
    }
    let n = game.physics().len();
    for change in &frame.changes {
        match change {
            Change::Append { puck, segments } if *puck < n => game
                .physics_mut()
                .extend_worldline(*puck, segments)
                .map_err(|e| format!("frame {}: puck {puck}: {e}", frame.seq))?,
            Change::Replace { puck, worldline } if *puck < n => {
                worldline
                    .check()
                    .map_err(|e| format!("frame {}: puck {puck}: {e}", frame.seq))?;
                game.physics_mut()
                    .replace_worldline(*puck, worldline.clone());
            }
            Change::Append { puck, .. } | Change::Replace { puck, .. } => {
                return Err(format!(
                    "frame {}: puck {puck} is not in the scene ({n} pucks)",
                    frame.seq
                ));
            }
        }
    }
    frame.view.apply(game);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn game() -> GameState {
        let mut scene = Scene::empty(glam::DVec2::new(2.84, 1.42), None).unwrap();
        for (k, x) in [0.5, 1.5].into_iter().enumerate() {
            scene
                .add_puck(lightcone_engine::scene::PuckSpec {
                    name: format!("p{k}"),
                    position: glam::DVec2::new(x, 0.7),
                    u: ProperVelocity::ZERO,
                    radius: 0.0305,
                    height: 0.02,
                    mass: 0.21,
                    color: lightcone_engine::scene::Color::default_for(k),
                })
                .unwrap();
        }
        GameState::new(scene)
    }

    fn frame(seq: u64, master: &GameState, sent: &mut Sent) -> Frame {
        Frame {
            seq,
            generation: master.generation,
            view: ViewState::of(master, (DVec3::ONE, DQuat::IDENTITY), DVec3::ZERO),
            changes: sent.changes(master),
            sample_ns: None,
            sent_ns: 0,
        }
    }

    #[test]
    fn only_what_changed_is_sent_and_the_copy_is_exact() {
        let mut master = game();
        let mut sent = Sent::default();
        // The first frame sends every worldline whole.
        let first = frame(1, &master, &mut sent);
        assert!(
            first
                .changes
                .iter()
                .all(|c| matches!(c, Change::Replace { .. }))
        );
        let snap = snapshot(&master, 1, "", first.view.clone());
        let mut copy = game_of(&snap).unwrap();
        // Nothing changed: nothing sent.
        assert!(frame(2, &master, &mut sent).changes.is_empty());
        // A stroke: one puck's new segment, appended.
        master.step(0.2);
        assert!(frame(3, &master, &mut sent).changes.is_empty());
        master
            .physics_mut()
            .apply_impulse(0, 0.2, DVec3::X)
            .unwrap();
        master.step(0.3);
        let f = frame(4, &master, &mut sent);
        assert!(
            matches!(&f.changes[..], [Change::Append { puck: 0, segments }] if segments.len() == 1),
            "{:?}",
            f.changes
        );
        // Through the wire and into the copy (frame 3 had no change): the
        // same bits.
        let f: Frame = decode(&encode(&f), "frame").unwrap();
        apply(&f, &mut copy).unwrap();
        for i in 0..2 {
            assert_eq!(copy.physics().worldline(i), master.physics().worldline(i));
        }
        assert_eq!(copy.live_time.to_bits(), master.live_time.to_bits());
        // A new game is sent whole again.
        master.restart();
        assert!(
            frame(5, &master, &mut sent)
                .changes
                .iter()
                .all(|c| matches!(c, Change::Replace { .. }))
        );
    }

    #[test]
    fn a_change_that_does_not_fit_is_refused_with_the_frame_and_puck() {
        let master = game();
        let mut sent = Sent::default();
        let mut f = frame(7, &master, &mut sent);
        let snap = snapshot(&master, 6, "", f.view.clone());
        let mut copy = game_of(&snap).unwrap();
        f.changes = vec![Change::Append {
            puck: 5,
            segments: Vec::new(),
        }];
        let e = apply(&f, &mut copy).unwrap_err();
        assert!(e.contains("frame 7") && e.contains("puck 5"), "{e}");
        // A segment before the last one.
        let old = master.physics().worldline(0).segments()[0];
        f.changes = vec![Change::Append {
            puck: 0,
            segments: vec![old],
        }];
        let e = apply(&f, &mut copy).unwrap_err();
        assert!(e.contains("frame 7") && e.contains("puck 0"), "{e}");
        // Garbage on the wire.
        let e = decode::<Frame>(&[0xff; 9], "frame").unwrap_err();
        assert!(e.contains("malformed frame (9 bytes)"), "{e}");
        // A scene whose pucks do not match the worldlines.
        let mut bad = snap.clone();
        bad.worldlines.pop();
        let Err(e) = game_of(&bad) else {
            panic!("a snapshot missing a worldline was taken")
        };
        assert!(e.contains("2 pucks but 1 worldlines"), "{e}");
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(16))]

        /// A node's copy, fed the frames (strokes on moving pucks that
        /// collide, a restart that brings a snapshot), holds the master's
        /// worldlines bit for bit at every frame.
        #[test]
        fn a_copy_follows_the_master_through_strokes_and_restarts(
            strokes in proptest::collection::vec((0usize..2, -3.0f64..3.0, -3.0f64..3.0), 12),
            stroke_every in 1usize..5,
            restart_at in proptest::option::of(3usize..30),
        ) {
            let mut master = game();
            master.physics_mut().apply_impulse(0, 0.0, DVec3::new(2.0, 0.05, 0.0)).unwrap();
            let mut sent = Sent::default();
            let mut copy: Option<GameState> = None;
            for k in 1..=40usize {
                master.step(0.05);
                if k % stroke_every == 0 {
                    let (i, x, y) = strokes[k % strokes.len()];
                    let t = master.live_time;
                    master.physics_mut().apply_impulse(i, t, DVec3::new(x, y, 0.0)).unwrap();
                }
                if restart_at == Some(k) {
                    master.restart();
                }
                let f = frame(k as u64, &master, &mut sent);
                let f: Frame = decode(&encode(&f), "frame").unwrap();
                match &mut copy {
                    Some(c) if c.generation == f.generation => apply(&f, c).unwrap(),
                    // First frame, or a new game: the node takes a snapshot.
                    _ => {
                        let snap = snapshot(&master, f.seq, "", f.view.clone());
                        let snap: Snapshot = decode(&encode(&snap), "snapshot").unwrap();
                        copy = Some(game_of(&snap).unwrap());
                    }
                }
                let c = copy.as_ref().unwrap();
                for i in 0..2 {
                    let (a, b) = (master.physics().worldline(i), c.physics().worldline(i));
                    proptest::prop_assert_eq!(a, b, "frame {}, puck {}", k, i);
                }
                proptest::prop_assert_eq!(c.view_time.to_bits(), master.view_time.to_bits());
            }
        }
    }
}
