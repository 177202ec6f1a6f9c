//! SYNC producer (CiA 301 §7.2.5): a frame every communication cycle, optionally with a counter.

use core::time::Duration;

use super::frame::{cob, CanFrame};

/// Produces SYNC frames at a fixed period (object 0x1006), with the counter of object 0x1019
/// when its overflow value is 2..=240.
#[derive(Debug, Clone)]
pub struct SyncProducer {
    cob_id: u16,
    period: Duration,
    next: Duration,
    overflow: Option<u8>,
    counter: u8,
}

impl SyncProducer {
    /// A producer on COB-ID 0x080 whose first SYNC is due at `start`. `overflow` outside
    /// 2..=240 means no counter, as in 0x1019.
    pub fn new(period: Duration, overflow: Option<u8>, start: Duration) -> Self {
        Self {
            cob_id: cob::SYNC,
            period,
            next: start,
            overflow: overflow.filter(|o| (2..=240).contains(o)),
            counter: 1,
        }
    }

    /// Uses another COB-ID (object 0x1005).
    pub fn with_cob_id(mut self, cob_id: u16) -> Self {
        self.cob_id = cob_id & super::frame::MAX_ID;
        self
    }

    /// When the next SYNC is due.
    pub fn next_due(&self) -> Duration {
        self.next
    }

    /// The SYNC to send at `now`, if one is due. Missed cycles are not made up: the next one is
    /// scheduled a period after the previous due time, or after `now` if that is already past.
    pub fn poll(&mut self, now: Duration) -> Option<CanFrame> {
        if now < self.next || self.period.is_zero() {
            return None;
        }
        self.next += self.period;
        if self.next <= now {
            self.next = now + self.period;
        }
        let frame = CanFrame::full(self.cob_id, [self.counter, 0, 0, 0, 0, 0, 0, 0]);
        Some(match self.overflow {
            Some(overflow) => {
                self.counter = if self.counter >= overflow {
                    1
                } else {
                    self.counter + 1
                };
                frame.truncated(1)
            }
            None => frame.truncated(0),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: Duration = Duration::from_millis(1);

    #[test]
    fn periodic_sync_without_counter() {
        let mut sync = SyncProducer::new(10 * MS, None, Duration::ZERO);
        let frame = sync.poll(Duration::ZERO).unwrap();
        assert_eq!((frame.id(), frame.dlc()), (0x080, 0));
        assert_eq!(sync.poll(9 * MS), None);
        assert!(sync.poll(10 * MS).is_some());
        assert_eq!(sync.next_due(), 20 * MS);
        // A stall of several periods yields one SYNC, not a burst.
        assert!(sync.poll(55 * MS).is_some());
        assert_eq!(sync.poll(56 * MS), None);
        assert_eq!(sync.next_due(), 65 * MS);
    }

    #[test]
    fn counter_runs_from_one_to_overflow() {
        let mut sync = SyncProducer::new(MS, Some(3), Duration::ZERO).with_cob_id(0x81);
        let counters: std::vec::Vec<u8> = (0..7)
            .map(|t| sync.poll(t * MS).unwrap().data()[0])
            .collect();
        assert_eq!(counters, [1, 2, 3, 1, 2, 3, 1]);
        assert_eq!(sync.poll(7 * MS).unwrap().id(), 0x81);
        assert_eq!(
            SyncProducer::new(MS, Some(1), Duration::ZERO)
                .poll(Duration::ZERO)
                .unwrap()
                .dlc(),
            0,
            "1 disables the counter"
        );
    }
}
