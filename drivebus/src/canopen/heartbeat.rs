//! Heartbeat consumer (CiA 301 §7.2.8.3.2.2): one timeout event per node that falls silent.

use core::time::Duration;

use super::address::NodeId;
use super::frame::CanFrame;
use super::nmt::{NodeEvent, NodeStates};

/// What the consumer noticed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HeartbeatEvent {
    /// A boot-up or a state change (see [`NodeStates`]).
    Node(NodeEvent),
    /// A monitored node sent no heartbeat within its consumer time. Reported once per silence.
    Timeout(NodeId),
    /// A node that had timed out is heard again.
    Resumed(NodeId),
}

#[derive(Debug, Clone, Copy, Default)]
struct Watch {
    period: Option<Duration>,
    /// Deadline, armed by the first heartbeat after monitoring starts (as CiA 301 prescribes).
    deadline: Option<Duration>,
    expired: bool,
}

/// Tracks node states and heartbeat deadlines.
#[derive(Debug, Clone)]
pub struct HeartbeatConsumer {
    states: NodeStates,
    watches: [Watch; 128],
}

impl Default for HeartbeatConsumer {
    fn default() -> Self {
        Self::new()
    }
}

impl HeartbeatConsumer {
    /// A consumer monitoring no node yet.
    pub const fn new() -> Self {
        Self {
            states: NodeStates::new(),
            watches: [Watch {
                period: None,
                deadline: None,
                expired: false,
            }; 128],
        }
    }

    /// Expects a heartbeat from `node` at least every `timeout` (its 0x1016 consumer time).
    pub fn monitor(&mut self, node: NodeId, timeout: Duration) {
        if let Some(watch) = self.watches.get_mut(node.0 as usize) {
            *watch = Watch {
                period: Some(timeout),
                ..Watch::default()
            };
        }
    }

    /// Stops monitoring `node`.
    pub fn forget(&mut self, node: NodeId) {
        if let Some(watch) = self.watches.get_mut(node.0 as usize) {
            *watch = Watch::default();
        }
    }

    /// The node states seen so far.
    pub fn states(&self) -> &NodeStates {
        &self.states
    }

    /// Feeds a received frame (others than heartbeats are ignored).
    pub fn handle(&mut self, frame: &CanFrame, now: Duration) -> Option<HeartbeatEvent> {
        let event = self.states.handle(frame, now);
        let node = super::nmt::decode_heartbeat(frame)?.0;
        let watch = &mut self.watches[node.0 as usize];
        if let Some(period) = watch.period {
            watch.deadline = Some(now + period);
            if core::mem::take(&mut watch.expired) {
                return Some(HeartbeatEvent::Resumed(node));
            }
        }
        event.map(HeartbeatEvent::Node)
    }

    /// Reports the next node whose heartbeat is overdue at `now`; call until it returns `None`.
    pub fn poll(&mut self, now: Duration) -> Option<HeartbeatEvent> {
        let (slot, watch) = self
            .watches
            .iter_mut()
            .enumerate()
            .find(|(_, w)| !w.expired && w.deadline.is_some_and(|d| now >= d))?;
        watch.expired = true;
        Some(HeartbeatEvent::Timeout(NodeId(slot as u8)))
    }

    /// The earliest time [`poll`](Self::poll) may report a timeout.
    pub fn next_deadline(&self) -> Option<Duration> {
        self.watches
            .iter()
            .filter(|w| !w.expired)
            .filter_map(|w| w.deadline)
            .min()
    }
}

/// A consumer heartbeat time entry of object 0x1016: node id in bits 16..23, time in ms.
pub const fn consumer_entry(node: NodeId, timeout_ms: u16) -> u32 {
    ((node.0 as u32) << 16) | timeout_ms as u32
}

#[cfg(test)]
mod tests {
    use super::super::nmt::{heartbeat_frame, NmtState};
    use super::*;

    const MS: Duration = Duration::from_millis(1);

    #[test]
    fn a_silent_node_times_out_once_and_resumes() {
        let node = NodeId(7);
        let mut consumer = HeartbeatConsumer::new();
        consumer.monitor(node, 100 * MS);
        assert_eq!(
            consumer.poll(10_000 * MS),
            None,
            "not armed before the first heartbeat"
        );
        let beat = heartbeat_frame(node, NmtState::Operational);
        let first = consumer.handle(&beat, Duration::ZERO);
        assert!(matches!(
            first,
            Some(HeartbeatEvent::Node(NodeEvent::StateChanged { .. }))
        ));
        assert_eq!(consumer.next_deadline(), Some(100 * MS));
        assert_eq!(consumer.handle(&beat, 90 * MS), None);
        assert_eq!(consumer.poll(189 * MS), None);
        assert_eq!(consumer.poll(190 * MS), Some(HeartbeatEvent::Timeout(node)));
        assert_eq!(consumer.poll(500 * MS), None, "one event per silence");
        assert_eq!(consumer.next_deadline(), None);
        assert_eq!(
            consumer.handle(&beat, 600 * MS),
            Some(HeartbeatEvent::Resumed(node))
        );
        assert_eq!(consumer.poll(650 * MS), None);
        assert_eq!(consumer.poll(700 * MS), Some(HeartbeatEvent::Timeout(node)));
    }

    #[test]
    fn nodes_time_out_independently_and_boot_ups_pass_through() {
        let (a, b) = (NodeId(1), NodeId(2));
        let mut consumer = HeartbeatConsumer::new();
        consumer.monitor(a, 50 * MS);
        consumer.monitor(b, 200 * MS);
        consumer.handle(
            &heartbeat_frame(a, NmtState::PreOperational),
            Duration::ZERO,
        );
        let boot = consumer.handle(&heartbeat_frame(b, NmtState::Initializing), Duration::ZERO);
        assert_eq!(boot, Some(HeartbeatEvent::Node(NodeEvent::BootUp(b))));
        assert_eq!(consumer.poll(60 * MS), Some(HeartbeatEvent::Timeout(a)));
        assert_eq!(consumer.poll(60 * MS), None);
        assert_eq!(consumer.poll(200 * MS), Some(HeartbeatEvent::Timeout(b)));
        consumer.forget(a);
        assert_eq!(
            consumer.handle(&heartbeat_frame(a, NmtState::PreOperational), 300 * MS),
            None
        );
        assert_eq!(consumer.poll(10_000 * MS), None);
    }

    #[test]
    fn consumer_time_entry_layout() {
        assert_eq!(consumer_entry(NodeId(0x10), 500), 0x0010_01F4);
    }
}
