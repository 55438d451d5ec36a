//! Publish→receive latency statistics.
//!
//! Why: the CAVE's motion-to-photon budget is a few milliseconds, so the IPC
//! hop must be measured, not assumed. Both timestamps are Unix-epoch
//! nanoseconds from the same machine's wall clock (see
//! [`crate::sample::unix_now_ns`]), so their difference is the latency.

use thiserror::Error;

/// Latency summary in nanoseconds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LatencyStats {
    /// Number of pairs.
    pub count: usize,
    /// Smallest latency.
    pub min_ns: u64,
    /// Median (nearest-rank).
    pub p50_ns: u64,
    /// 99th percentile (nearest-rank).
    pub p99_ns: u64,
    /// Largest latency.
    pub max_ns: u64,
    /// Pairs whose receive time was before the publish time (clock step);
    /// they count as 0 ns.
    pub negative: usize,
}

impl std::fmt::Display for LatencyStats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let us = |ns: u64| ns as f64 / 1000.0;
        write!(
            f,
            "n={} p50={:.1} µs p99={:.1} µs max={:.1} µs",
            self.count,
            us(self.p50_ns),
            us(self.p99_ns),
            us(self.max_ns)
        )
    }
}

/// Why statistics could not be computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Error)]
pub enum LatencyError {
    /// No samples.
    #[error("no latency samples")]
    Empty,
    /// The two slices differ in length.
    #[error("{publish} publish timestamps but {receive} receive timestamps")]
    LengthMismatch {
        /// Length of the publish slice.
        publish: usize,
        /// Length of the receive slice.
        receive: usize,
    },
}

/// Nearest-rank percentile of sorted data (`q` in 0..=1).
fn percentile(sorted: &[u64], q: f64) -> u64 {
    let n = sorted.len();
    let rank = (q * n as f64).ceil() as usize;
    sorted[rank.clamp(1, n) - 1]
}

/// p50/p99/max of `receive_ns[i] - publish_ns[i]`.
pub fn latency_stats(publish_ns: &[u64], receive_ns: &[u64]) -> Result<LatencyStats, LatencyError> {
    if publish_ns.len() != receive_ns.len() {
        return Err(LatencyError::LengthMismatch {
            publish: publish_ns.len(),
            receive: receive_ns.len(),
        });
    }
    if publish_ns.is_empty() {
        return Err(LatencyError::Empty);
    }
    let mut negative = 0;
    let mut d: Vec<u64> = publish_ns
        .iter()
        .zip(receive_ns)
        .map(|(&p, &r)| {
            if r < p {
                negative += 1;
            }
            r.saturating_sub(p)
        })
        .collect();
    d.sort_unstable();
    Ok(LatencyStats {
        count: d.len(),
        min_ns: d[0],
        p50_ns: percentile(&d, 0.50),
        p99_ns: percentile(&d, 0.99),
        max_ns: d[d.len() - 1],
        negative,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_of_1_to_100() {
        let publish: Vec<u64> = vec![1_000; 100];
        let receive: Vec<u64> = (1..=100).rev().map(|i| 1_000 + i).collect();
        let s = latency_stats(&publish, &receive).expect("stats");
        assert_eq!(
            (s.count, s.min_ns, s.p50_ns, s.p99_ns, s.max_ns),
            (100, 1, 50, 99, 100)
        );
        assert_eq!(s.negative, 0);
        assert!(s.to_string().contains("p99=0.1 µs"));
    }

    #[test]
    fn single_and_negative() {
        let s = latency_stats(&[10], &[5]).expect("stats");
        assert_eq!((s.p50_ns, s.p99_ns, s.max_ns, s.negative), (0, 0, 0, 1));
    }

    #[test]
    fn errors() {
        assert_eq!(latency_stats(&[], &[]), Err(LatencyError::Empty));
        assert_eq!(
            latency_stats(&[1, 2], &[3]),
            Err(LatencyError::LengthMismatch {
                publish: 2,
                receive: 1
            })
        );
    }
}
