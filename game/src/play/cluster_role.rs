//! The window's part in the render cluster: a render node's frames come
//! from the master (`lightcone wall`), the master publishes each of its
//! own (`play --cave --serve`), and both may log each frame's CAVE eyes
//! (`--frame-log`).

use std::io::Write;
use std::path::Path;
use std::time::{Duration, Instant};

use glam::DVec3;
use lightcone_engine::ecs::Entity;
use lightcone_tracker::cave::CaveConfig;

use super::cave_role::Immersion;
use crate::cave::Side;
use crate::cluster::master::ClusterMaster;
use crate::cluster::message::Frame;
use crate::cluster::node::{ClusterNode, Stamps};
use crate::model::GameState;

/// A render node's part of the window: frames come from the master.
pub struct NodeRole {
    /// The node.
    pub node: ClusterNode,
    /// The first frame, taken before the window opened.
    pending: Option<Frame>,
    /// Frames to show (0: no limit).
    frames: u64,
    /// How long without a frame before the node stops.
    silence: Duration,
    /// When the last frame came.
    last_frame: Instant,
    /// Frames shown so far.
    pub shown: u64,
}

/// What a render node does this frame.
pub enum NodeStep {
    /// Show the master's frame.
    Show(Box<Frame>),
    /// Nothing came yet: wait for the next turn of the event loop.
    Wait,
    /// The master is gone or silent: stop.
    Stop,
}

impl NodeRole {
    /// A node whose `first` frame is in; it shows `frames` frames (0: no
    /// limit) and stops after `silence` without one.
    pub fn new(node: ClusterNode, first: Frame, frames: u64, silence: Duration) -> Self {
        Self {
            node,
            pending: Some(first),
            frames,
            silence,
            last_frame: Instant::now(),
            shown: 0,
        }
    }

    /// The master's next frame, applied to `game` (the node's copy of the
    /// master's game). Waits in short slices, so the window stays
    /// responsive (it can be closed) while the master is silent.
    pub fn next(&mut self, game: &mut GameState) -> Result<NodeStep, String> {
        let frame = match self.pending.take() {
            Some(f) => f,
            None => match self.node.next_frame(game, Duration::from_millis(50))? {
                Some(f) => f,
                None => {
                    let silent = self.last_frame.elapsed() >= self.silence;
                    if self.node.master_gone {
                        crate::errln!("lightcone wall: the master is gone; stopping");
                    } else if silent {
                        crate::errln!(
                            "lightcone wall: no frame from the master in {:?}; stopping",
                            self.silence
                        );
                    }
                    return Ok(if silent || self.node.master_gone {
                        NodeStep::Stop
                    } else {
                        NodeStep::Wait
                    });
                }
            },
        };
        self.last_frame = Instant::now();
        game.message = self.node.status_line();
        Ok(NodeStep::Show(Box::new(frame)))
    }

    /// The swap lock: this node is ready with frame `seq`, and waits for
    /// the others. Returns when the frame is shown (Unix ns).
    pub fn swap(&mut self, seq: u64) -> u64 {
        self.node.ready(seq);
        self.node.wait_swap(seq, crate::cluster::BARRIER * 4);
        crate::cluster::now_ns()
    }

    /// Counts a frame shown; whether the node has shown all it was to
    /// (or `shot` was the last).
    pub fn shown_one(&mut self, shot: bool) -> bool {
        self.shown += 1;
        shot || (self.frames > 0 && self.shown >= self.frames)
    }
}

/// The master's part of a frame: the render nodes compute this frame and
/// show it together (the swap lock), before the master's window draws it,
/// so that the console's own drawing adds nothing to the walls' latency.
pub fn publish(master: &mut ClusterMaster, state: &GameState, immersion: &Immersion) {
    master.publish(
        state,
        immersion.own_head(),
        immersion.flight,
        immersion.newest_sample_ns(),
    );
    master.swap(state);
}

/// `--frame-log`: one line per frame with its CAVE eyes and stamps.
pub struct FrameLog(std::io::BufWriter<std::fs::File>);

impl FrameLog {
    /// Creates (or empties) the log at `path`.
    pub fn create(path: &Path) -> Result<Self, String> {
        std::fs::File::create(path)
            .map(|f| Self(std::io::BufWriter::new(f)))
            .map_err(|e| format!("{}: {e}", path.display()))
    }

    /// Writes frame `seq`'s line: the head at `head` (tracker space), the
    /// `stamps`, and the eyes `stereo` drawn for `cave` in `state`.
    pub fn write(
        &mut self,
        seq: u64,
        head: DVec3,
        stamps: Stamps,
        state: &GameState,
        cave: &CaveConfig,
        stereo: &[(Side, Entity, DVec3)],
    ) -> Result<(), String> {
        let line = crate::cluster::node::frame_record(seq, head, stamps, state, cave, stereo);
        writeln!(self.0, "{line}").map_err(|e| e.to_string())?;
        self.0.flush().map_err(|e| e.to_string())
    }
}
