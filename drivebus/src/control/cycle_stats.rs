//! The timing of a cyclic run as the master saw it: the time between the feedback of two
//! successive SYNCs, its deviation from the period (jitter) and the SYNCs whose feedback never
//! came in time (missed cycles).

use core::time::Duration;
use std::vec::Vec;

/// Cycle timing of a run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CycleStats {
    period: Duration,
    /// Time between successive cycles' feedback, in order.
    intervals: Vec<Duration>,
}

impl CycleStats {
    /// Empty statistics of a run at `period`.
    pub fn new(period: Duration) -> Self {
        Self {
            period,
            intervals: Vec::new(),
        }
    }

    /// Records the time since the previous cycle's feedback.
    pub fn record(&mut self, interval: Duration) {
        self.intervals.push(interval);
    }

    /// The SYNC period.
    pub fn period(&self) -> Duration {
        self.period
    }

    /// Cycles recorded.
    pub fn cycles(&self) -> usize {
        self.intervals.len()
    }

    /// SYNCs missed: an interval of about n periods (rounded) missed n − 1.
    pub fn missed(&self) -> u64 {
        if self.period.is_zero() {
            return 0;
        }
        let period = self.period.as_secs_f64();
        self.intervals
            .iter()
            .map(|i| ((i.as_secs_f64() / period).round() as u64).saturating_sub(1))
            .sum()
    }

    /// The jitter (|interval − period|) at quantile `q` in 0..=1 (0.5: median, 1: maximum);
    /// zero without cycles.
    pub fn jitter(&self, q: f64) -> Duration {
        let mut jitter: Vec<Duration> = self
            .intervals
            .iter()
            .map(|i| i.abs_diff(self.period))
            .collect();
        if jitter.is_empty() {
            return Duration::ZERO;
        }
        jitter.sort_unstable();
        let rank = (q.clamp(0.0, 1.0) * (jitter.len() - 1) as f64).round() as usize;
        jitter[rank]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: Duration = Duration::from_millis(1);
    const US: Duration = Duration::from_micros(1);

    #[test]
    fn jitter_quantiles_and_missed_cycles() {
        let mut stats = CycleStats::new(MS);
        for us in [1_000, 1_010, 990, 1_100, 3_020] {
            stats.record(us * US);
        }
        assert_eq!(stats.cycles(), 5);
        assert_eq!(stats.missed(), 2, "an interval of three periods missed two");
        assert_eq!(stats.jitter(0.5), 10 * US);
        assert_eq!(stats.jitter(1.0), 2_020 * US);
        assert_eq!(CycleStats::new(MS).jitter(0.99), Duration::ZERO);
    }
}
