//! The CAVE render cluster over Zenoh: a master (`lightcone play --cave
//! FILE --serve [ENDPOINT]`) owns the simulation, the input, the lesson and
//! the tracker; render nodes (`lightcone wall --join ENDPOINT --wall NAME`)
//! each draw their walls from their own copy of the engine.
//!
//! Per frame the master publishes a [`message::Frame`] on [`FRAME_KEY`];
//! each node applies it, computes its walls' views and answers
//! [`message::Ready`] on [`READY_KEY`]; when every live node is ready (or a
//! [`BARRIER`] has passed) the master publishes the frame's number on
//! [`SWAP_KEY`] and the nodes show it (the swap lock). A node that joins
//! late, misses a frame or sees a new game asks [`SNAPSHOT_KEY`] for a
//! [`message::Snapshot`]. Each node holds a Zenoh liveliness token under
//! [`NODE_KEY`], so the master knows which nodes are live the moment one
//! joins or its connection drops, and never waits on a dead one; the
//! master holds one under [`MASTER_KEY`], and the nodes stop when it goes
//! (the master quit or died).
//!
//! Transport: Zenoh over TCP, multicast and gossip scouting off (the
//! master listens on the endpoint, the nodes connect to it), every peer
//! authenticated with the CAVE's key and every message signed with it
//! ([`key`]).

pub mod key;
pub mod master;
pub mod message;
pub mod node;

use std::time::Duration;

/// Frames, master → nodes.
pub const FRAME_KEY: &str = "lightcone/cluster/frame";
/// Frame numbers whose pictures every node may show, master → nodes.
pub const SWAP_KEY: &str = "lightcone/cluster/swap";
/// Ready answers, nodes → master.
pub const READY_KEY: &str = "lightcone/cluster/ready";
/// Snapshots, asked by a node, answered by the master.
pub const SNAPSHOT_KEY: &str = "lightcone/cluster/snapshot";
/// The nodes' liveliness tokens: `lightcone/cluster/node/WALLS-ID`.
pub const NODE_KEY: &str = "lightcone/cluster/node";
/// The master's liveliness token: the nodes stop when it goes.
pub const MASTER_KEY: &str = "lightcone/cluster/master";

/// The longest the master waits for a live node's ready answer before it
/// lets the others show the frame.
pub const BARRIER: Duration = Duration::from_millis(250);

/// The endpoint `--serve` listens on without a value.
pub const DEFAULT_ENDPOINT: &str = "tcp/0.0.0.0:7447";

/// A Zenoh configuration that listens on (`listen`) or connects to
/// `endpoint` (a Zenoh locator such as `tcp/127.0.0.1:7447`), with
/// multicast and gossip scouting off (the master connects to no one, and
/// learns of no one but those who connect to it), authenticated with
/// `key`. The error names the endpoint.
pub fn config(
    endpoint: &str,
    listen: bool,
    key: &key::ClusterKey,
) -> Result<zenoh::Config, String> {
    if !endpoint.starts_with("tcp/") {
        return Err(format!(
            "{endpoint:?}: give a Zenoh TCP endpoint such as tcp/127.0.0.1:7447"
        ));
    }
    let mut c = zenoh::Config::default();
    let endpoints = serde_json::to_string(&[endpoint]).unwrap_or_default();
    let set = |c: &mut zenoh::Config, key: &str, value: &str| {
        c.insert_json5(key, value)
            .map_err(|e| format!("Zenoh configuration {key} = {value}: {e}"))
    };
    set(
        &mut c,
        "mode",
        if listen { "\"peer\"" } else { "\"client\"" },
    )?;
    set(&mut c, "scouting/multicast/enabled", "false")?;
    set(&mut c, "scouting/gossip/enabled", "false")?;
    key.configure(&mut c, listen)?;
    if listen {
        set(&mut c, "listen/endpoints", &endpoints)?;
        set(&mut c, "connect/endpoints", "[]")?;
    } else {
        set(&mut c, "connect/endpoints", &endpoints)?;
        set(&mut c, "listen/endpoints", "[]")?;
    }
    Ok(c)
}

/// Unix time now, ns.
pub fn now_ns() -> u64 {
    lightcone_tracker::unix_now_ns()
}
