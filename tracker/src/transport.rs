//! Zero-copy IPC transport for [`TrackerSample`]s over an iceoryx2
//! publish-subscribe service.
//!
//! Why iceoryx2: the tracker bridge and the game are separate processes on one
//! machine; shared memory gives microsecond latency without a broker daemon,
//! and iceoryx2 detects dead processes so a crashed tracker can be restarted
//! without restarting the game.
//!
//! # Service settings and why
//!
//! Both sides open the service with `open_or_create` and the *same* QoS
//! ([`SERVICE_QOS`]), so whichever process starts first creates it and the
//! other opens it (opening verifies the existing service offers at least these
//! values):
//!
//! * `history_size = 1`: a subscriber that connects after the publisher gets
//!   the latest pose at once instead of waiting a tracker period.
//! * `subscriber_max_buffer_size = 64`, safe overflow on: a game frame at 60 Hz
//!   drains ~17 samples of a 1 kHz tracker; if the game stalls, the oldest
//!   samples are overwritten rather than blocking the tracker.
//! * `max_publishers = 4`: a killed publisher's port stays registered until
//!   its node is cleaned up; headroom lets a restarted publisher connect even
//!   before that cleanup has happened.
//!
//! # Dead publishers
//!
//! iceoryx2 0.10 cleans up dead nodes when a node is created
//! (`cleanup_dead_nodes_on_creation`), when a service is opened
//! (`cleanup_dead_nodes_on_open`) and when a node is dropped; all default to
//! true. On top of that [`cleanup_dead_nodes`] runs the explicit
//! `Node::list` + `DeadNodeView::try_remove_stale_resources` pass before
//! every open, and [`Subscriber::cleanup_dead_nodes`] lets the game run it
//! when the follower reports the tracker lost.
//!
//! # Threading
//!
//! The ports use `ipc_threadsafe::Service`: identical shared-memory layout and
//! interoperable with `ipc::Service`, but its ports are `Send + Sync`, so a
//! [`Subscriber`] can live in an ECS resource that is accessed from worker
//! threads. Signal handling is disabled in the nodes this module creates: the
//! game (and the publisher binary) own SIGINT/SIGTERM.

use crate::sample::TrackerSample;
use iceoryx2::node::NodeState;
use iceoryx2::port::publisher::Publisher as IoxPublisher;
use iceoryx2::port::subscriber::Subscriber as IoxSubscriber;
use iceoryx2::prelude::{
    CallbackProgression, Config, Node, NodeBuilder, NodeName, PortFactory, ServiceName,
    SignalHandlingMode,
};
use iceoryx2::service::port_factory::publish_subscribe::PortFactory as PubSubFactory;
use thiserror::Error;

/// The iceoryx2 service flavour used by both ends (see module docs).
pub type IpcService = iceoryx2::service::ipc_threadsafe::Service;

/// Default service name for the head tracker.
pub const DEFAULT_SERVICE_NAME: &str = "lightcone/tracker/head";

/// Quality-of-service settings shared by publisher and subscriber.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ServiceQos {
    /// Samples a late-joining subscriber receives on connect.
    pub history_size: usize,
    /// Samples buffered per subscriber between two `drain` calls.
    pub subscriber_max_buffer_size: usize,
    /// Publisher ports the service admits (headroom for restarts).
    pub max_publishers: usize,
    /// Subscriber ports the service admits.
    pub max_subscribers: usize,
    /// Processes (nodes) that may have the service open.
    pub max_nodes: usize,
}

/// The QoS this crate uses on both sides (see the module docs).
pub const SERVICE_QOS: ServiceQos = ServiceQos {
    history_size: 1,
    subscriber_max_buffer_size: 64,
    max_publishers: 4,
    max_subscribers: 8,
    max_nodes: 16,
};

/// Errors from the tracker transport. Every variant names the service so an
/// on-screen or log message is actionable.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum TransportError {
    /// The name is not a valid iceoryx2 service name (empty, too long, ...).
    #[error("invalid tracker service name {service:?}: {reason}")]
    InvalidServiceName {
        /// The offending name.
        service: String,
        /// iceoryx2's reason.
        reason: String,
    },
    /// The iceoryx2 node (per-process registration) could not be created.
    #[error("tracker service {service:?}: cannot create iceoryx2 node: {reason}")]
    Node {
        /// Service name.
        service: String,
        /// iceoryx2's reason.
        reason: String,
    },
    /// Opening or creating the publish-subscribe service failed, e.g. it
    /// exists with an incompatible payload type or smaller QoS.
    #[error(
        "tracker service {service:?}: cannot open or create the publish-subscribe service: {reason}"
    )]
    Service {
        /// Service name.
        service: String,
        /// iceoryx2's reason.
        reason: String,
    },
    /// Creating the publisher or subscriber port failed (e.g. too many
    /// publishers: a dead one was not cleaned up).
    #[error("tracker service {service:?}: cannot create {role} port: {reason}")]
    Port {
        /// Service name.
        service: String,
        /// "publisher" or "subscriber".
        role: &'static str,
        /// iceoryx2's reason.
        reason: String,
    },
    /// Sending a sample failed.
    #[error("tracker service {service:?}: send failed: {reason}")]
    Send {
        /// Service name.
        service: String,
        /// iceoryx2's reason.
        reason: String,
    },
    /// Receiving failed (e.g. a connection to a publisher could not be set up).
    #[error("tracker service {service:?}: receive failed: {reason}")]
    Receive {
        /// Service name.
        service: String,
        /// iceoryx2's reason.
        reason: String,
    },
    /// Listing nodes for dead-node cleanup failed.
    #[error("tracker service {service:?}: dead-node cleanup failed: {reason}")]
    Cleanup {
        /// Service name.
        service: String,
        /// iceoryx2's reason.
        reason: String,
    },
}

/// Restricts iceoryx2's own stderr logging to errors. By default it also
/// prints warnings such as "No config file was loaded" once per process,
/// which is noise on a game console. Process-wide; call once at startup.
pub fn quiet_iceoryx_logs() {
    iceoryx2::prelude::set_log_level(iceoryx2::prelude::LogLevel::Error);
}

/// Result of a dead-node cleanup pass.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CleanupReport {
    /// Dead nodes whose stale resources were removed.
    pub removed: usize,
    /// Dead nodes that could not be removed (permissions, another process is
    /// already cleaning them, version mismatch).
    pub failed: usize,
}

/// Removes the stale shared-memory resources of every dead iceoryx2 node
/// (processes that were killed without dropping their node) under the global
/// iceoryx2 config. This is what lets a killed publisher be replaced.
///
/// `service` is only used to label errors.
pub fn cleanup_dead_nodes(service: &str) -> Result<CleanupReport, TransportError> {
    let mut report = CleanupReport::default();
    Node::<IpcService>::list(Config::global_config(), |state| {
        if let NodeState::Dead(view) = state {
            match view.try_remove_stale_resources() {
                Ok(()) => report.removed += 1,
                Err(_) => report.failed += 1,
            }
        }
        CallbackProgression::Continue
    })
    .map_err(|e| TransportError::Cleanup {
        service: service.to_owned(),
        reason: format!("{e:?}"),
    })?;
    Ok(report)
}

/// The typed iceoryx2 port factory of the tracker service.
type TrackerFactory = PubSubFactory<IpcService, TrackerSample, ()>;

/// Creates a node and opens (or creates) the tracker service with
/// [`SERVICE_QOS`]. Shared by both ends so their settings cannot drift.
fn open_or_create(
    service: &str,
    node_name: &str,
) -> Result<(Node<IpcService>, TrackerFactory), TransportError> {
    let name = ServiceName::new(service).map_err(|e| TransportError::InvalidServiceName {
        service: service.to_owned(),
        reason: format!("{e:?}"),
    })?;
    let node_name = NodeName::new(node_name).map_err(|e| TransportError::Node {
        service: service.to_owned(),
        reason: format!("invalid node name {node_name:?}: {e:?}"),
    })?;

    // Best effort: a failure to list nodes must not prevent connecting, the
    // builder's own cleanup-on-open still runs.
    let _ = cleanup_dead_nodes(service);

    let node = NodeBuilder::new()
        .name(&node_name)
        .signal_handling_mode(SignalHandlingMode::Disabled)
        .create::<IpcService>()
        .map_err(|e| TransportError::Node {
            service: service.to_owned(),
            reason: format!("{e:?}"),
        })?;

    let qos = SERVICE_QOS;
    let factory = node
        .service_builder(&name)
        .publish_subscribe::<TrackerSample>()
        .history_size(qos.history_size)
        .subscriber_max_buffer_size(qos.subscriber_max_buffer_size)
        .enable_safe_overflow(true)
        .max_publishers(qos.max_publishers)
        .max_subscribers(qos.max_subscribers)
        .max_nodes(qos.max_nodes)
        .open_or_create()
        .map_err(|e| TransportError::Service {
            service: service.to_owned(),
            reason: format!("{e:?}"),
        })?;
    Ok((node, factory))
}

/// Sending end: owned by the tracker bridge / simulator process.
pub struct Publisher {
    service: String,
    // Field order is drop order: the port must go before the factory and node.
    port: IoxPublisher<IpcService, TrackerSample, ()>,
    _factory: TrackerFactory,
    _node: Node<IpcService>,
}

impl std::fmt::Debug for Publisher {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Publisher")
            .field("service", &self.service)
            .finish_non_exhaustive()
    }
}

impl Publisher {
    /// Opens (or creates) `service_name` and registers a publisher on it,
    /// after removing the resources of dead nodes (e.g. a previous, killed
    /// publisher with the same service name).
    pub fn open(service_name: &str) -> Result<Self, TransportError> {
        let (node, factory) = open_or_create(service_name, "lightcone-tracker-publisher")?;
        let port = factory
            .publisher_builder()
            .create()
            .map_err(|e| TransportError::Port {
                service: service_name.to_owned(),
                role: "publisher",
                reason: format!("{e:?}"),
            })?;
        Ok(Self {
            service: service_name.to_owned(),
            port,
            _factory: factory,
            _node: node,
        })
    }

    /// The service name this publisher sends on.
    #[must_use]
    pub fn service_name(&self) -> &str {
        &self.service
    }

    /// Copies `sample` into shared memory and delivers it to every connected
    /// subscriber. Returns the number of subscribers it reached (0 is not an
    /// error: the game may not be running yet; the history slot keeps it).
    pub fn send(&self, sample: &TrackerSample) -> Result<usize, TransportError> {
        self.port
            .send_copy(*sample)
            .map_err(|e| TransportError::Send {
                service: self.service.clone(),
                reason: format!("{e:?}"),
            })
    }
}

/// Receiving end: owned by the game.
pub struct Subscriber {
    service: String,
    port: IoxSubscriber<IpcService, TrackerSample, ()>,
    factory: TrackerFactory,
    _node: Node<IpcService>,
}

impl std::fmt::Debug for Subscriber {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Subscriber")
            .field("service", &self.service)
            .finish_non_exhaustive()
    }
}

impl Subscriber {
    /// Opens (or creates) `service_name` and registers a subscriber. Works
    /// whether or not a publisher exists yet.
    pub fn open(service_name: &str) -> Result<Self, TransportError> {
        let (node, factory) = open_or_create(service_name, "lightcone-tracker-subscriber")?;
        let port = factory
            .subscriber_builder()
            .buffer_size(SERVICE_QOS.subscriber_max_buffer_size)
            .create()
            .map_err(|e| TransportError::Port {
                service: service_name.to_owned(),
                role: "subscriber",
                reason: format!("{e:?}"),
            })?;
        Ok(Self {
            service: service_name.to_owned(),
            port,
            factory,
            _node: node,
        })
    }

    /// The service name this subscriber listens on.
    #[must_use]
    pub fn service_name(&self) -> &str {
        &self.service
    }

    /// Non-blocking: returns every sample received since the last call, in
    /// arrival order (possibly empty). Samples are copied out of shared memory
    /// and released immediately so the publisher never runs out of slots.
    pub fn drain(&self) -> Result<Vec<TrackerSample>, TransportError> {
        let mut out = Vec::new();
        self.drain_into(&mut out)?;
        Ok(out)
    }

    /// Like [`Subscriber::drain`] but appends to `out` (no allocation once
    /// `out` has grown). Returns the number appended. On error, samples
    /// already received are kept in `out`.
    pub fn drain_into(&self, out: &mut Vec<TrackerSample>) -> Result<usize, TransportError> {
        let before = out.len();
        loop {
            match self.port.receive() {
                Ok(Some(sample)) => out.push(*sample),
                Ok(None) => return Ok(out.len() - before),
                Err(e) => {
                    return Err(TransportError::Receive {
                        service: self.service.clone(),
                        reason: format!("{e:?}"),
                    });
                }
            }
        }
    }

    /// Number of publisher ports currently registered on the service. A
    /// killed publisher still counts until its node has been cleaned up.
    #[must_use]
    pub fn publisher_count(&self) -> usize {
        self.factory.dynamic_config().number_of_publishers()
    }

    /// Runs a dead-node cleanup pass (see [`cleanup_dead_nodes`]); call it
    /// when the follower reports the tracker lost, so a dead publisher's port
    /// and shared memory are released.
    pub fn cleanup_dead_nodes(&self) -> Result<CleanupReport, TransportError> {
        cleanup_dead_nodes(&self.service)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DQuat, DVec3};
    use std::time::{Duration, Instant};

    fn unique(tag: &str) -> String {
        static N: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
        let n = N.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        format!("lightcone/test/transport/{tag}/{}/{n}", std::process::id())
    }

    fn sample(seq: u64) -> TrackerSample {
        TrackerSample::new(seq, seq, DVec3::splat(seq as f64), DQuat::IDENTITY, true)
    }

    #[test]
    fn ports_are_send_and_sync() {
        fn check<T: Send + Sync>() {}
        check::<Publisher>();
        check::<Subscriber>();
    }

    #[test]
    fn invalid_name_is_reported_with_name() {
        let err = Subscriber::open("").expect_err("empty name must fail");
        let msg = err.to_string();
        assert!(msg.contains("invalid tracker service name"), "{msg}");
        let long = "x".repeat(10_000);
        let err = Publisher::open(&long).expect_err("overlong name must fail");
        assert!(matches!(err, TransportError::InvalidServiceName { .. }));
    }

    #[test]
    fn in_process_round_trip_and_drain() {
        let name = unique("roundtrip");
        let sub = Subscriber::open(&name).expect("subscriber");
        let publ = Publisher::open(&name).expect("publisher");
        assert_eq!(publ.service_name(), name);
        assert_eq!(sub.publisher_count(), 1);
        for i in 0..10 {
            assert_eq!(publ.send(&sample(i)).expect("send"), 1);
        }
        let got = sub.drain().expect("drain");
        let seqs: Vec<u64> = got.iter().map(|s| s.sequence).collect();
        assert_eq!(seqs, (0..10).collect::<Vec<_>>());
        assert_eq!(got[3], sample(3));
        assert!(sub.drain().expect("drain").is_empty());
    }

    #[test]
    fn late_subscriber_gets_history_of_one() {
        let name = unique("history");
        let publ = Publisher::open(&name).expect("publisher");
        for i in 0..5 {
            publ.send(&sample(i)).expect("send");
        }
        let sub = Subscriber::open(&name).expect("subscriber");
        // Connection (and history delivery) happens on the publisher's next
        // send or the subscriber's next receive; poll briefly.
        let deadline = Instant::now() + Duration::from_secs(1);
        let mut got = Vec::new();
        while got.is_empty() && Instant::now() < deadline {
            sub.drain_into(&mut got).expect("drain");
            if got.is_empty() {
                publ.send(&sample(5)).expect("send");
            }
        }
        assert!(!got.is_empty());
        assert!(got[0].sequence >= 4, "history should be the latest sample");
    }

    #[test]
    fn overflow_keeps_newest() {
        let name = unique("overflow");
        let sub = Subscriber::open(&name).expect("subscriber");
        let publ = Publisher::open(&name).expect("publisher");
        let n = SERVICE_QOS.subscriber_max_buffer_size as u64 * 3;
        for i in 0..n {
            publ.send(&sample(i)).expect("send never blocks");
        }
        let got = sub.drain().expect("drain");
        assert_eq!(got.len(), SERVICE_QOS.subscriber_max_buffer_size);
        assert_eq!(got.last().map(|s| s.sequence), Some(n - 1));
    }

    #[test]
    fn publisher_replaced_in_process() {
        let name = unique("replace");
        let sub = Subscriber::open(&name).expect("subscriber");
        {
            let p1 = Publisher::open(&name).expect("p1");
            p1.send(&sample(100)).expect("send");
        }
        let p2 = Publisher::open(&name).expect("p2");
        p2.send(&sample(0)).expect("send");
        let got: Vec<u64> = sub
            .drain()
            .expect("drain")
            .iter()
            .map(|s| s.sequence)
            .collect();
        assert!(got.contains(&0), "{got:?}");
        assert_eq!(sub.publisher_count(), 1);
        let report = sub.cleanup_dead_nodes().expect("cleanup");
        assert_eq!(report.failed, 0);
    }
}
