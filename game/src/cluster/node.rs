//! A render node of a CAVE cluster (`lightcone wall --join ENDPOINT --wall
//! NAME`): it copies the master's game frame by frame and draws its walls.

use std::io::Write;
use std::time::{Duration, Instant};

use zenoh::Wait;
use zenoh::handlers::FifoChannelHandler;
use zenoh::liveliness::LivelinessToken;
use zenoh::pubsub::{Publisher, Subscriber};
use zenoh::qos::CongestionControl;
use zenoh::sample::Sample;

use lightcone_tracker::cave::CaveConfig;

use super::key::ClusterKey;
use super::message::{self, Frame, Ready, Snapshot};
use super::{FRAME_KEY, MASTER_KEY, NODE_KEY, READY_KEY, SNAPSHOT_KEY, SWAP_KEY};
use crate::cave::{self, Side};
use crate::model::GameState;

/// How long a node waits for the master's snapshot.
const SNAPSHOT_WAIT: Duration = Duration::from_secs(5);

/// A render node joined to a master.
pub struct ClusterNode {
    /// `WALLS-ID` (its walls, and the start of its Zenoh id): its liveliness
    /// token's and ready answers' name.
    pub name: String,
    walls: Vec<String>,
    session: zenoh::Session,
    _token: LivelinessToken,
    frames: Subscriber<FifoChannelHandler<Sample>>,
    swaps: Subscriber<FifoChannelHandler<Sample>>,
    ready: Publisher<'static>,
    master: Subscriber<FifoChannelHandler<Sample>>,
    /// The master's token was seen, then went: it quit or died.
    pub master_gone: bool,
    master_seen: bool,
    /// The generation of the master's game the node copies (after the
    /// first snapshot).
    synced: Option<u64>,
    /// The master's CAVE, reduced to this node's walls and their outputs
    /// (after the first snapshot).
    pub cave: Option<CaveConfig>,
    /// The master's endpoint.
    pub endpoint: String,
    /// The last frame applied.
    seq: u64,
    /// Checks what the master sends, signs the ready answers.
    key: ClusterKey,
}

/// `cave` with only the walls named `walls` (in that order) and the outputs
/// showing them. The error names a wall that is not there and those that
/// are.
pub fn only_walls(cave: &CaveConfig, walls: &[String]) -> Result<CaveConfig, String> {
    let mut out = cave.clone();
    let mut index = Vec::new();
    for name in walls {
        let Some(k) = cave.walls.iter().position(|w| &w.name == name) else {
            let there: Vec<&str> = cave.walls.iter().map(|w| w.name.as_str()).collect();
            return Err(format!(
                "the master's CAVE{} has no wall {name:?} (its walls: {})",
                cave.source
                    .as_ref()
                    .map(|p| format!(" ({})", p.display()))
                    .unwrap_or_default(),
                there.join(", ")
            ));
        };
        index.push(k);
    }
    out.walls = index.iter().map(|&k| cave.walls[k].clone()).collect();
    out.outputs = cave
        .outputs
        .iter()
        .filter_map(|o| {
            let k = index.iter().position(|&w| w == o.wall)?;
            let mut o = o.clone();
            o.wall = k;
            Some(o)
        })
        .collect();
    Ok(out)
}

impl ClusterNode {
    /// Joins the master at `endpoint` to draw `walls` (checked against the
    /// master's CAVE at the first snapshot), trying again every half second
    /// for at most `patience` while no master is there yet, proving it
    /// holds `key` (the master refuses it otherwise), and taking only what
    /// is signed with it.
    pub fn join(
        endpoint: &str,
        walls: &[String],
        patience: Duration,
        key: ClusterKey,
    ) -> Result<Self, String> {
        let start = Instant::now();
        let session = loop {
            match zenoh::open(super::config(endpoint, false, &key)?).wait() {
                Ok(s) => break s,
                Err(e) if start.elapsed() >= patience => {
                    // Zenoh says the same whether nothing listens there or
                    // the master refused this key.
                    return Err(format!(
                        "no cluster master at {endpoint} within {patience:?} that accepts the key {}: {e}",
                        key.path.display()
                    ));
                }
                Err(_) => std::thread::sleep(Duration::from_millis(500)),
            }
        };
        let err = |what: &str, e: zenoh::Error| format!("cluster at {endpoint}: {what}: {e}");
        // Unique across machines (a Zenoh id is random), and a single
        // chunk of a key expression.
        let zid = session.zid().to_string();
        let walls_part: String = walls
            .join("+")
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || "-_+".contains(c) {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        let name = format!("{walls_part}-{}", &zid[..zid.len().min(8)]);
        let frames = session
            .declare_subscriber(FRAME_KEY)
            .wait()
            .map_err(|e| err("frames", e))?;
        let swaps = session
            .declare_subscriber(SWAP_KEY)
            .wait()
            .map_err(|e| err("swaps", e))?;
        let ready = session
            .declare_publisher(READY_KEY)
            .congestion_control(CongestionControl::Block)
            .wait()
            .map_err(|e| err("ready answers", e))?;
        let master = session
            .liveliness()
            .declare_subscriber(MASTER_KEY)
            .history(true)
            .wait()
            .map_err(|e| err("the master's liveliness", e))?;
        let token = session
            .liveliness()
            .declare_token(format!("{NODE_KEY}/{name}"))
            .wait()
            .map_err(|e| err("liveliness", e))?;
        Ok(Self {
            name,
            walls: walls.to_vec(),
            session,
            _token: token,
            frames,
            swaps,
            ready,
            master,
            master_gone: false,
            master_seen: false,
            synced: None,
            cave: None,
            endpoint: endpoint.to_owned(),
            seq: 0,
            key,
        })
    }

    /// Asks the master for a snapshot and starts the copy `game` from it.
    /// `Ok(false)`: none to be had now (said on stderr; the next frame asks
    /// again); an error: the master's CAVE has not this node's walls.
    fn resync(&mut self, game: &mut GameState) -> Result<bool, String> {
        let snapshot = match self.ask_snapshot() {
            Ok(s) => s,
            Err(e) => {
                crate::errln!("lightcone wall: {e}; asking again at the next frame");
                return Ok(false);
            }
        };
        let full = CaveConfig::from_toml_str(&snapshot.cave_toml)
            .map_err(|e| format!("the master's CAVE file does not read: {e}"))?;
        let cave = only_walls(&full, &self.walls)?;
        match message::game_of(&snapshot) {
            Ok(g) => *game = g,
            Err(e) => {
                crate::errln!("lightcone wall: {e}; asking again at the next frame");
                return Ok(false);
            }
        }
        self.synced = Some(snapshot.generation);
        self.cave = Some(cave);
        self.seq = snapshot.seq;
        Ok(true)
    }

    /// One snapshot from the master.
    fn ask_snapshot(&self) -> Result<Snapshot, String> {
        let replies = self
            .session
            .get(SNAPSHOT_KEY)
            .timeout(SNAPSHOT_WAIT)
            .wait()
            .map_err(|e| format!("cannot ask the master for a snapshot: {e}"))?;
        let reply = replies
            .recv()
            .map_err(|_| format!("the master sent no snapshot within {SNAPSHOT_WAIT:?}"))?;
        let sample = reply
            .into_result()
            .map_err(|e| format!("the master refused a snapshot: {e:?}"))?;
        let bytes = sample.payload().to_bytes();
        message::decode(self.key.open("snapshot", &bytes)?, "snapshot")
    }

    /// Waits at most `timeout` for the master's next frame and applies it
    /// to `game`, the copy of the master's (replaced by a snapshot when the
    /// node has none yet, missed a frame or the master started a new game).
    /// `Ok(None)`: no frame in time.
    pub fn next_frame(
        &mut self,
        game: &mut GameState,
        timeout: Duration,
    ) -> Result<Option<Frame>, String> {
        let deadline = Instant::now() + timeout;
        loop {
            self.watch_master();
            if self.master_gone {
                return Ok(None);
            }
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return Ok(None);
            }
            // Look at the master's liveliness at least every 100 ms.
            let Ok(Some(sample)) = self
                .frames
                .recv_timeout(left.min(Duration::from_millis(100)))
            else {
                continue;
            };
            let bytes = sample.payload().to_bytes();
            let opened = self.key.open("frame", &bytes);
            let frame: Frame = match opened.and_then(|b| message::decode(b, "frame")) {
                Ok(f) => f,
                Err(e) => {
                    // Dropped; the gap it leaves brings a new snapshot.
                    crate::errln!("lightcone wall: {e}; dropped");
                    continue;
                }
            };
            let fresh = self.synced == Some(frame.generation);
            if fresh && frame.seq <= self.seq {
                // Already in the snapshot.
                continue;
            }
            if !fresh || frame.seq != self.seq + 1 {
                if !self.resync(game)? {
                    self.synced = None;
                    continue;
                }
                if frame.seq == self.seq && self.synced == Some(frame.generation) {
                    // The snapshot is the state after this very frame.
                    return Ok(Some(frame));
                }
                if frame.seq != self.seq + 1 || self.synced != Some(frame.generation) {
                    // Older than the snapshot (newer frames are queued),
                    // or of another game.
                    continue;
                }
            }
            if let Err(e) = message::apply(&frame, game) {
                crate::errln!("lightcone wall: {e}; taking a new snapshot");
                self.synced = None;
                continue;
            }
            self.seq = frame.seq;
            return Ok(Some(frame));
        }
    }

    /// Takes the master's liveliness changes.
    fn watch_master(&mut self) {
        while let Ok(Some(sample)) = self.master.try_recv() {
            match sample.kind() {
                zenoh::sample::SampleKind::Put => self.master_seen = true,
                zenoh::sample::SampleKind::Delete => self.master_gone = self.master_seen,
            }
        }
    }

    /// One line for the screen: the node, the master, the frame.
    pub fn status_line(&self) -> String {
        format!(
            "render node {} of {}, frame {}",
            self.name, self.endpoint, self.seq
        )
    }

    /// Tells the master this node is ready to show frame `seq`.
    pub fn ready(&self, seq: u64) {
        let r = Ready {
            node: self.name.clone(),
            seq,
        };
        let _ = self
            .ready
            .put(self.key.seal("ready", message::encode(&r)))
            .wait();
    }

    /// Waits at most `timeout` for the master to let frame `seq` be shown.
    /// `false`: not in time (the master is gone, or slow).
    pub fn wait_swap(&mut self, seq: u64, timeout: Duration) -> bool {
        let deadline = Instant::now() + timeout;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.swaps.recv_timeout(left) {
                Ok(Some(sample)) => {
                    let bytes = sample.payload().to_bytes();
                    if self
                        .key
                        .open("swap", &bytes)
                        .and_then(|b| message::decode::<u64>(b, "swap"))
                        .is_ok_and(|s| s >= seq)
                    {
                        return true;
                    }
                }
                _ => return false,
            }
        }
    }
}

/// How a node runs (`lightcone wall`).
pub struct Headless {
    /// Frames to show before it stops (0: until the master is gone).
    pub frames: u64,
    /// Write each frame shown here, one JSON line each (see
    /// [`frame_record`]).
    pub log: Option<std::path::PathBuf>,
    /// Stop after this long without a frame.
    pub silence: Duration,
    /// With a window: save a screenshot (the main window's and one per
    /// output) after `frames` frames, then stop.
    pub screenshot: Option<std::path::PathBuf>,
}

/// When a frame's head was sampled, the frame sent and shown (Unix ns).
#[derive(Clone, Copy, Debug, Default)]
pub struct Stamps {
    /// The newest tracker sample's publication, if any.
    pub sample_ns: Option<u64>,
    /// The master's sending (0 for the master's own log).
    pub sent_ns: u64,
    /// The showing (after the swap lock).
    pub shown_ns: u64,
}

/// One line of a frame log: the frame number, the game's board times, the
/// [`Stamps`], the tracked head (tracker space, m); for each eye's view
/// (`"mono"`, `"left"`, `"right"`) every apparent vertex (`views`) and each
/// puck's apparent centre (`centres`), as `[x, y, z]` metres relative to
/// the eye (the observer's frame), pucks in index order, then the table;
/// and for each wall of `cave` and each eye, the wall's view-projection
/// matrix (`walls`: 16 numbers, column-major; absent for an eye behind
/// the wall).
pub fn frame_record(
    seq: u64,
    head: glam::DVec3,
    stamps: Stamps,
    game: &GameState,
    cave: &CaveConfig,
    eyes: &[(Side, lightcone_engine::ecs::Entity, glam::DVec3)],
) -> serde_json::Value {
    let mut views = serde_json::Map::new();
    let mut centres = serde_json::Map::new();
    for &(side, v, _) in eyes {
        let vertices: Vec<[f64; 3]> = game
            .apparent(v)
            .map(|a| {
                a.bodies
                    .iter()
                    .flat_map(|b| b.seen.iter().map(|s| s.position.to_array()))
                    .collect()
            })
            .unwrap_or_default();
        views.insert(side.name().to_owned(), serde_json::json!(vertices));
        let c: Vec<[f64; 3]> = game
            .centres(v)
            .iter()
            .map(|c| c.seen.position.to_array())
            .collect();
        centres.insert(side.name().to_owned(), serde_json::json!(c));
    }
    let mut walls = serde_json::Map::new();
    for wall in &cave.walls {
        let mut per_eye = serde_json::Map::new();
        for &(side, _, tracker_eye) in eyes {
            if let Some(m) = cave::wall_view_proj(&cave.tracker, wall, tracker_eye) {
                per_eye.insert(side.name().to_owned(), serde_json::json!(m.to_cols_array()));
            }
        }
        walls.insert(wall.name.clone(), serde_json::Value::Object(per_eye));
    }
    serde_json::json!({
        "seq": seq,
        "view_time": game.view_time,
        "live_time": game.live_time,
        "sample_ns": stamps.sample_ns,
        "sent_ns": stamps.sent_ns,
        "shown_ns": stamps.shown_ns,
        "head": head.to_array(),
        "views": views,
        "centres": centres,
        "walls": walls,
    })
}

/// Runs a node without a window: each frame applied, its walls' eyes
/// computed, ready, shown at the swap and logged. Returns the frames shown.
pub fn run_headless(node: &mut ClusterNode, options: &Headless) -> Result<u64, String> {
    let mut log = match &options.log {
        Some(p) => Some(std::io::BufWriter::new(
            std::fs::File::create(p).map_err(|e| format!("{}: {e}", p.display()))?,
        )),
        None => None,
    };
    let mut shown = 0u64;
    let mut game = placeholder()?;
    while options.frames == 0 || shown < options.frames {
        let Some(frame) = node.next_frame(&mut game, options.silence)? else {
            if shown == 0 && !node.master_gone {
                return Err(format!("no frame from the master in {:?}", options.silence));
            }
            if node.master_gone {
                crate::errln!("lightcone wall: the master is gone; stopping");
            } else {
                crate::errln!(
                    "lightcone wall: no frame from the master in {:?}; stopping",
                    options.silence
                );
            }
            break;
        };
        let Some(cave) = node.cave.as_ref() else {
            continue;
        };
        let sides = cave::sides_needed(cave, Side::Mono);
        let views = cave::stereo_views(
            &mut game,
            cave,
            frame.view.head(),
            &sides,
            frame.view.flight,
        );
        let eyes: Vec<(Side, lightcone_engine::ecs::Entity, glam::DVec3)> = sides
            .iter()
            .zip(&views)
            .map(|(&s, &(v, tracker))| (s, v, tracker))
            .collect();
        node.ready(frame.seq);
        node.wait_swap(frame.seq, super::BARRIER * 4);
        let shown_ns = super::now_ns();
        shown += 1;
        if let (Some(log), Some(cave)) = (log.as_mut(), node.cave.as_ref()) {
            let stamps = Stamps {
                sample_ns: frame.sample_ns,
                sent_ns: frame.sent_ns,
                shown_ns,
            };
            let line = frame_record(
                frame.seq,
                frame.view.head_position,
                stamps,
                &game,
                cave,
                &eyes,
            );
            writeln!(log, "{line}").map_err(|e| format!("frame log: {e}"))?;
        }
    }
    if let Some(mut log) = log {
        log.flush().map_err(|e| format!("frame log: {e}"))?;
    }
    Ok(shown)
}

/// The game a node holds before its first snapshot replaces it: an empty
/// table.
pub fn placeholder() -> Result<GameState, String> {
    lightcone_engine::scene::Scene::empty(glam::DVec2::new(2.84, 1.42), None)
        .map(GameState::new)
        .map_err(|e| format!("an empty table: {e}"))
}
