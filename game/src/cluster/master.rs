//! The master of a CAVE render cluster (`play --cave FILE --serve`): it
//! publishes each frame, answers snapshots, keeps the swap lock and knows
//! which render nodes are live.

use std::collections::BTreeSet;
use std::time::Instant;

use glam::{DQuat, DVec3};
use zenoh::Wait;
use zenoh::handlers::FifoChannelHandler;
use zenoh::pubsub::{Publisher, Subscriber};
use zenoh::qos::CongestionControl;
use zenoh::query::{Query, Queryable};
use zenoh::sample::{Sample, SampleKind};

use super::key::ClusterKey;
use super::message::{self, Frame, Ready, Sent, ViewState};
use super::{BARRIER, FRAME_KEY, MASTER_KEY, NODE_KEY, READY_KEY, SNAPSHOT_KEY, SWAP_KEY};
use crate::model::GameState;

/// The master's side of the cluster.
pub struct ClusterMaster {
    endpoint: String,
    cave_toml: String,
    /// Signs what the master sends, checks what the nodes answer.
    key: ClusterKey,
    _session: zenoh::Session,
    _token: zenoh::liveliness::LivelinessToken,
    frames: Publisher<'static>,
    swaps: Publisher<'static>,
    ready: Subscriber<FifoChannelHandler<Sample>>,
    snapshots: Queryable<FifoChannelHandler<Query>>,
    nodes: Subscriber<FifoChannelHandler<Sample>>,
    live: BTreeSet<String>,
    /// The live nodes that have answered a frame: those the swap lock
    /// waits for (a node that just joined is taking its snapshot).
    locked: BTreeSet<String>,
    ready_now: BTreeSet<String>,
    /// Nodes said to be late, not yet ready in time again (said once).
    said_late: BTreeSet<String>,
    sent: Sent,
    seq: u64,
    view: Option<ViewState>,
    /// Lines for the player: nodes joining and leaving.
    news: Vec<String>,
}

impl ClusterMaster {
    /// Listens on `endpoint` (`tcp/HOST:PORT`) for render nodes that hold
    /// `key`, whose CAVE is `cave_toml` (the CAVE file's text). The error
    /// names the endpoint.
    pub fn serve(endpoint: &str, cave_toml: String, key: ClusterKey) -> Result<Self, String> {
        let config = super::config(endpoint, true, &key)?;
        let session = zenoh::open(config)
            .wait()
            .map_err(|e| format!("cannot serve the cluster on {endpoint}: {e}"))?;
        let err = |what: &str, e: zenoh::Error| format!("cluster on {endpoint}: {what}: {e}");
        let frames = session
            .declare_publisher(FRAME_KEY)
            .congestion_control(CongestionControl::Drop)
            .wait()
            .map_err(|e| err("frames", e))?;
        let swaps = session
            .declare_publisher(SWAP_KEY)
            .congestion_control(CongestionControl::Drop)
            .wait()
            .map_err(|e| err("swaps", e))?;
        let ready = session
            .declare_subscriber(READY_KEY)
            .wait()
            .map_err(|e| err("ready answers", e))?;
        let snapshots = session
            .declare_queryable(SNAPSHOT_KEY)
            .wait()
            .map_err(|e| err("snapshots", e))?;
        let nodes = session
            .liveliness()
            .declare_subscriber(format!("{NODE_KEY}/*"))
            .history(true)
            .wait()
            .map_err(|e| err("node liveliness", e))?;
        let token = session
            .liveliness()
            .declare_token(MASTER_KEY)
            .wait()
            .map_err(|e| err("liveliness", e))?;
        Ok(Self {
            endpoint: endpoint.to_owned(),
            cave_toml,
            key,
            _session: session,
            _token: token,
            frames,
            swaps,
            ready,
            snapshots,
            nodes,
            live: BTreeSet::new(),
            locked: BTreeSet::new(),
            ready_now: BTreeSet::new(),
            said_late: BTreeSet::new(),
            sent: Sent::default(),
            seq: 0,
            view: None,
            news: Vec::new(),
        })
    }

    /// Publishes the next frame of `game` (call once per frame, when the
    /// game's state for the frame is final): its view state with the head
    /// `head` (tracker space) and `flight`, the worldlines' changes, and
    /// `sample_ns`, the newest tracker sample's publication time. Then
    /// answers the snapshots asked for meanwhile.
    pub fn publish(
        &mut self,
        game: &GameState,
        head: (DVec3, DQuat),
        flight: DVec3,
        sample_ns: Option<u64>,
    ) {
        self.watch_nodes();
        self.seq += 1;
        self.ready_now.clear();
        let view = ViewState::of(game, head, flight);
        let frame = Frame {
            seq: self.seq,
            generation: game.generation,
            view: view.clone(),
            changes: self.sent.changes(game),
            sample_ns,
            sent_ns: super::now_ns(),
        };
        if let Err(e) = self
            .frames
            .put(self.key.seal("frame", message::encode(&frame)))
            .wait()
        {
            self.news
                .push(format!("cluster: frame {} not sent: {e}", self.seq));
        }
        self.view = Some(view);
        self.answer_snapshots(game);
    }

    /// Answers the snapshots asked for since the last call with the state
    /// after the frame just published (built once for all of them).
    fn answer_snapshots(&mut self, game: &GameState) {
        let mut bytes = None;
        while let Ok(Some(query)) = self.snapshots.try_recv() {
            let Some(view) = self.view.clone() else {
                return;
            };
            let bytes = bytes.get_or_insert_with(|| {
                let snapshot = message::snapshot(game, self.seq, &self.cave_toml, view);
                self.key.seal("snapshot", message::encode(&snapshot))
            });
            if let Err(e) = query.reply(SNAPSHOT_KEY, bytes.clone()).wait() {
                self.news.push(format!("cluster: a snapshot not sent: {e}"));
            }
        }
    }

    /// The swap lock: waits until every live node in the lock (every one
    /// that keeps up: it answered this frame or the one before) is ready to show the frame
    /// just published (at most [`BARRIER`]), then lets them show it. A node
    /// that was not ready in time leaves the lock until it answers a frame
    /// in time again: a stuck node costs one barrier, not one per frame.
    /// Snapshots asked for meanwhile are answered (`game`: the game as
    /// published), so a node taking one can still show this frame.
    pub fn swap(&mut self, game: &GameState) {
        if self.seq == 0 {
            return;
        }
        let start = Instant::now();
        loop {
            self.watch_nodes();
            self.answer_snapshots(game);
            while let Ok(Some(sample)) = self.ready.try_recv() {
                self.take_ready(&sample);
            }
            if self.locked.is_subset(&self.ready_now) {
                break;
            }
            let left = BARRIER.saturating_sub(start.elapsed());
            if left.is_zero() {
                let late: Vec<String> = self.locked.difference(&self.ready_now).cloned().collect();
                for name in late {
                    self.locked.remove(&name);
                    if !self.said_late.insert(name.clone()) {
                        continue;
                    }
                    self.news.push(format!(
                        "cluster: render node {name} was not ready for frame {} in {BARRIER:?}; not waited for until it catches up",
                        self.seq
                    ));
                }
                break;
            }
            // Wake on the next answer (or a node leaving, checked above
            // at least every millisecond).
            if let Ok(Some(sample)) = self
                .ready
                .recv_timeout(left.min(std::time::Duration::from_millis(1)))
            {
                self.take_ready(&sample);
            }
        }
        if let Err(e) = self
            .swaps
            .put(self.key.seal("swap", message::encode(&self.seq)))
            .wait()
        {
            self.news
                .push(format!("cluster: swap {} not sent: {e}", self.seq));
        }
    }

    /// Takes one ready answer. A live node that answered this frame or the
    /// one before keeps up: it is (again) in the swap lock.
    fn take_ready(&mut self, sample: &Sample) {
        let bytes = sample.payload().to_bytes();
        let Ok(r) = self
            .key
            .open("ready", &bytes)
            .and_then(|b| message::decode::<Ready>(b, "ready answer"))
        else {
            return;
        };
        if !self.live.contains(&r.node) || r.seq + 1 < self.seq || r.seq > self.seq {
            return;
        }
        self.locked.insert(r.node.clone());
        if r.seq == self.seq {
            self.said_late.remove(&r.node);
            self.ready_now.insert(r.node);
        }
    }

    /// Takes the nodes' liveliness changes.
    fn watch_nodes(&mut self) {
        while let Ok(Some(sample)) = self.nodes.try_recv() {
            let name = sample
                .key_expr()
                .as_str()
                .rsplit('/')
                .next()
                .unwrap_or_default()
                .to_owned();
            match sample.kind() {
                SampleKind::Put => {
                    if self.live.insert(name.clone()) {
                        self.news
                            .push(format!("cluster: render node {name} joined"));
                    }
                }
                SampleKind::Delete => {
                    self.locked.remove(&name);
                    self.said_late.remove(&name);
                    if self.live.remove(&name) {
                        self.news.push(format!("cluster: render node {name} left"));
                    }
                }
            }
        }
    }

    /// The live render nodes' names (`WALLS-ID`), sorted.
    pub fn nodes(&self) -> Vec<String> {
        self.live.iter().cloned().collect()
    }

    /// The last frame published.
    pub fn seq(&self) -> u64 {
        self.seq
    }

    /// The lines to tell the player since the last call (nodes joined and
    /// left, frames not sent).
    pub fn take_news(&mut self) -> Vec<String> {
        std::mem::take(&mut self.news)
    }

    /// One line for the screen: the endpoint and the live nodes.
    pub fn status_line(&self) -> String {
        if self.live.is_empty() {
            format!("cluster on {}: no render node yet", self.endpoint)
        } else {
            format!(
                "cluster on {}: {} live ({})",
                self.endpoint,
                self.live.len(),
                self.nodes().join(", ")
            )
        }
    }
}
