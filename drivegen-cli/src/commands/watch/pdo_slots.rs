//! TPDOs matched to what they answer: in SYNC mode each SYNC opens a slot that the nodes'
//! next TPDOs fill, so SYNCs go out at their own pace (the TPDO rate) while answers are still on
//! their way; by event timer a node's TPDO fills the oldest slot it has not filled yet, opening
//! one if there is none. A slot is a sample once every node filled it, or once it is older than
//! the timeout (the nodes that sent nothing are then named).

use std::collections::VecDeque;
use std::time::{Duration, Instant};

/// One sample in the making.
struct Slot {
    /// When it opened: the SYNC went out, or the first TPDO came.
    at: Instant,
    /// Seconds since the watch began, at `at`.
    time: f64,
    /// Each node's TPDO payload, once it came.
    payloads: Vec<Option<Vec<u8>>>,
}

/// A sample ready: its time and each node's payload (`None`: none came in time).
pub type Ready = (f64, Vec<Option<Vec<u8>>>);

/// The open slots, oldest first.
pub struct Slots {
    nodes: usize,
    /// TPDOs open slots of their own (event timer), instead of only filling SYNCs' slots.
    by_event: bool,
    open: VecDeque<Slot>,
}

impl Slots {
    /// Slots for `nodes` nodes; `by_event`: the TPDOs come by event timer, not at SYNC.
    pub fn new(nodes: usize, by_event: bool) -> Self {
        Self {
            nodes,
            by_event,
            open: VecDeque::new(),
        }
    }

    /// A SYNC went out at `at`.
    pub fn sync(&mut self, at: Instant, time: f64) {
        self.open.push_back(self.slot(at, time));
    }

    fn slot(&self, at: Instant, time: f64) -> Slot {
        Slot {
            at,
            time,
            payloads: vec![None; self.nodes],
        }
    }

    /// Node `node`'s TPDO came at `at`. At SYNC, one with no SYNC waiting for it is dropped
    /// (a late answer to a SYNC whose slot already timed out).
    pub fn fill(&mut self, node: usize, payload: Vec<u8>, at: Instant, time: f64) {
        let slot = match self.open.iter().position(|s| s.payloads[node].is_none()) {
            Some(i) => &mut self.open[i],
            None if self.by_event => {
                let slot = self.slot(at, time);
                self.open.push_back(slot);
                let last = self.open.len() - 1;
                &mut self.open[last]
            }
            None => return,
        };
        slot.payloads[node] = Some(payload);
    }

    /// The oldest slot, once every node filled it or it is older than `timeout` at `now`.
    pub fn ready(&mut self, now: Instant, timeout: Duration) -> Option<Ready> {
        let front = self.open.front()?;
        let complete = front.payloads.iter().all(Option::is_some);
        if !complete && now.duration_since(front.at) < timeout {
            return None;
        }
        let slot = self.open.pop_front()?;
        Some((slot.time, slot.payloads))
    }

    /// When the oldest slot times out, if any is open.
    pub fn deadline(&self, timeout: Duration) -> Option<Instant> {
        self.open.front().map(|s| s.at + timeout)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TIMEOUT: Duration = Duration::from_millis(100);

    #[test]
    fn answers_fill_the_syncs_in_order_and_late_nodes_time_out() {
        let t0 = Instant::now();
        let mut slots = Slots::new(2, false);
        slots.fill(0, vec![9], t0, 0.0);
        assert!(
            slots.ready(t0, TIMEOUT).is_none(),
            "no SYNC for it: dropped"
        );
        slots.sync(t0, 0.0);
        slots.sync(t0 + Duration::from_millis(1), 0.001);
        slots.fill(0, vec![1], t0, 0.0);
        slots.fill(0, vec![2], t0, 0.0);
        slots.fill(1, vec![3], t0, 0.0);
        assert_eq!(
            slots.ready(t0, TIMEOUT),
            Some((0.0, vec![Some(vec![1]), Some(vec![3])]))
        );
        assert_eq!(slots.ready(t0, TIMEOUT), None, "node 1 still due");
        let later = t0 + Duration::from_millis(150);
        assert_eq!(
            slots.ready(later, TIMEOUT),
            Some((0.001, vec![Some(vec![2]), None]))
        );
        assert_eq!(slots.deadline(TIMEOUT), None);
    }

    #[test]
    fn by_event_a_tpdo_opens_its_own_slot() {
        let t0 = Instant::now();
        let mut slots = Slots::new(1, true);
        slots.fill(0, vec![1], t0, 0.5);
        slots.fill(0, vec![2], t0, 0.6);
        assert_eq!(slots.ready(t0, TIMEOUT), Some((0.5, vec![Some(vec![1])])));
        assert_eq!(slots.ready(t0, TIMEOUT), Some((0.6, vec![Some(vec![2])])));
    }
}
