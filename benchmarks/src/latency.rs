//! A fixed-size latency histogram (10 µs buckets up to one second, one bucket above): its
//! memory does not grow with the run, so it does not disturb a measurement of resident memory.

use std::time::Duration;

const BUCKET_US: u64 = 10;
const BUCKETS: usize = 100_000;

/// Counts of latencies by 10 µs bucket.
#[derive(Debug, Clone)]
pub struct Histogram {
    counts: Vec<u32>,
    total: u64,
}

impl Default for Histogram {
    /// Every bucket written once here (`vec![0; n]` alone gets pages that the kernel maps only
    /// as buckets are first hit), so resident memory does not creep up as rarer latencies come
    /// in during a run.
    fn default() -> Self {
        let mut counts = vec![0; BUCKETS + 1];
        // A zero the optimiser cannot see through, so the pages are really written.
        counts.fill(std::hint::black_box(0));
        Self { counts, total: 0 }
    }
}

impl Histogram {
    /// Counts one latency.
    pub fn record(&mut self, latency: Duration) {
        let bucket = (latency.as_micros() as u64 / BUCKET_US).min(BUCKETS as u64) as usize;
        self.counts[bucket] = self.counts[bucket].saturating_add(1);
        self.total += 1;
    }

    /// How many latencies were counted.
    pub fn total(&self) -> u64 {
        self.total
    }

    /// The upper edge of the bucket holding quantile `q` (0..=1); `None` when empty or when it
    /// lies beyond one second.
    pub fn quantile(&self, q: f64) -> Option<Duration> {
        let rank = ((self.total as f64 * q).ceil() as u64).max(1);
        let mut seen = 0;
        for (bucket, &count) in self.counts.iter().enumerate().take(BUCKETS) {
            seen += u64::from(count);
            if seen >= rank {
                return Some(Duration::from_micros((bucket as u64 + 1) * BUCKET_US));
            }
        }
        None
    }

    /// Adds `other`'s counts and empties it.
    pub fn drain_into(&mut self, other: &mut Histogram) {
        for (mine, theirs) in self.counts.iter_mut().zip(other.counts.iter_mut()) {
            *mine = mine.saturating_add(std::mem::take(theirs));
        }
        self.total += std::mem::take(&mut other.total);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn p99_of_100_latencies_is_the_99th() {
        let mut h = Histogram::default();
        for us in 1..=100 {
            h.record(Duration::from_micros(us * 100));
        }
        assert_eq!(h.quantile(0.99), Some(Duration::from_micros(9_910)));
        assert_eq!(h.quantile(0.5), Some(Duration::from_micros(5_010)));
        let mut all = Histogram::default();
        all.drain_into(&mut h);
        assert_eq!((all.total(), h.total(), h.quantile(0.5)), (100, 0, None));
    }
}
