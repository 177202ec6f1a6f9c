//! The sans-I/O heart of the network manager: routes every received frame to the node it
//! belongs to, tracks each node's state, and queues the frames to send. Both shells (the
//! blocking [`Network`](super::Network) and the async `AsyncNetwork`) own one behind a mutex
//! and differ only in how they wait.

use core::time::Duration;
use std::collections::VecDeque;
use std::vec::Vec;

use super::event::NetworkEvent;
use crate::canopen::address::NodeId;
use crate::canopen::bounded_queue::BoundedQueue;
use crate::canopen::emcy::Emcy;
use crate::canopen::frame::CanFrame;
use crate::canopen::heartbeat::{HeartbeatConsumer, HeartbeatEvent};
use crate::canopen::message::Message;
use crate::canopen::nmt::{NmtCommand, NmtState, NodeEvent};
use crate::canopen::pdo::PdoKind;
use crate::canopen::sync::SyncProducer;

/// Most SDO responses kept for one node's transfer: a block upload sends up to 127 segments
/// before the client answers, with room to spare.
pub const SDO_INBOX: usize = 256;

/// Most frames waiting to be sent; more means the bus stopped taking frames, and a sender is
/// told so ([`BusError::CanQueueFull`](crate::BusError::CanQueueFull)) instead of the queue
/// growing without end.
pub const OUTBOX: usize = 4096;

/// What the manager knows about a node.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct NodeStatus {
    /// The last NMT state it reported (boot-up counts as pre-operational).
    pub state: Option<NmtState>,
    /// Its heartbeat is monitored and overdue.
    pub lost: bool,
    /// The last emergency it sent.
    pub last_emcy: Option<Emcy>,
}

/// One subscription to a node's events, as [`NetworkCore::subscribe`] gave it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SubscriptionId {
    node: NodeId,
    number: u64,
}

impl SubscriptionId {
    /// The node subscribed to.
    pub fn node(&self) -> NodeId {
        self.node
    }
}

/// One node's share of the manager.
#[derive(Debug, Default)]
struct Slot {
    /// An SDO transfer to this node is in flight (CANopen allows one per server).
    sdo_claimed: bool,
    /// Responses on the node's SDO response COB-ID while a transfer is in flight.
    sdo_inbox: VecDeque<CanFrame>,
    /// The subscriber's queue, if the node has one, and the subscription it belongs to.
    events: Option<BoundedQueue<NetworkEvent>>,
    subscription: u64,
    status: NodeStatus,
}

/// Routes frames to nodes and tracks them; never touches a bus or a clock.
#[derive(Debug)]
pub struct NetworkCore {
    slots: Vec<Slot>,
    outbox: VecDeque<CanFrame>,
    heartbeat: HeartbeatConsumer,
    sync: Option<SyncProducer>,
    /// SDO responses that arrived while no transfer to their node was in flight, or that
    /// overflowed a transfer's inbox.
    stale_sdo: u64,
    /// SDO transfers in flight, all nodes together.
    transfers: usize,
}

impl Default for NetworkCore {
    fn default() -> Self {
        Self::new()
    }
}

impl NetworkCore {
    /// A manager that knows no node, produces no SYNC and monitors no heartbeat.
    pub fn new() -> Self {
        Self {
            slots: (0..=NodeId::MAX).map(|_| Slot::default()).collect(),
            outbox: VecDeque::new(),
            heartbeat: HeartbeatConsumer::new(),
            sync: None,
            stale_sdo: 0,
            transfers: 0,
        }
    }

    fn slot(&mut self, node: NodeId) -> &mut Slot {
        // NodeId's field is public: an id past 127 shares slot 0, which no node uses.
        let index = usize::from(node.get()).min(self.slots.len() - 1);
        &mut self.slots[index]
    }

    /// Queues `frame` for sending; `false` (nothing queued) when [`OUTBOX`] frames wait already.
    pub fn transmit(&mut self, frame: CanFrame) -> bool {
        if self.outbox.len() >= OUTBOX {
            return false;
        }
        self.outbox.push_back(frame);
        true
    }

    /// The next frame to send.
    pub fn poll_transmit(&mut self) -> Option<CanFrame> {
        self.outbox.pop_front()
    }

    /// Whether frames wait to be sent.
    pub fn has_transmit(&self) -> bool {
        !self.outbox.is_empty()
    }

    /// Queues the NMT `command` for `node`, or for every node with `None`.
    pub fn nmt(&mut self, command: NmtCommand, node: Option<NodeId>) -> bool {
        self.transmit(command.frame(node))
    }

    /// Produces a SYNC every `period` from `now` on (the first at `now`); `None` stops it.
    pub fn set_sync(&mut self, period: Option<Duration>, now: Duration) {
        self.sync = period.map(|p| SyncProducer::new(p, None, now));
    }

    /// Expects a heartbeat from `node` at least every `timeout`; a silence longer than that
    /// reports [`NetworkEvent::Lost`], the next heartbeat [`NetworkEvent::Back`]. Monitoring
    /// starts with the first heartbeat, as CiA 301 prescribes.
    pub fn monitor(&mut self, node: NodeId, timeout: Duration) {
        self.heartbeat.monitor(node, timeout);
        self.slot(node).status.lost = false;
    }

    /// Stops monitoring `node`'s heartbeat.
    pub fn forget(&mut self, node: NodeId) {
        self.heartbeat.forget(node);
        self.slot(node).status.lost = false;
    }

    /// Gives `node` a subscriber queue of `capacity` events, replacing any earlier one; returns
    /// the subscription, for [`unsubscribe`](Self::unsubscribe).
    pub fn subscribe(&mut self, node: NodeId, capacity: usize) -> SubscriptionId {
        let slot = self.slot(node);
        slot.events = Some(BoundedQueue::new(capacity));
        slot.subscription += 1;
        SubscriptionId {
            node,
            number: slot.subscription,
        }
    }

    /// Removes the subscriber queue of `subscription`'s node if it is still that
    /// subscription's (a later one that replaced it stays); its events are no longer kept.
    pub fn unsubscribe(&mut self, subscription: SubscriptionId) {
        let slot = self.slot(subscription.node);
        if slot.subscription == subscription.number {
            slot.events = None;
        }
    }

    /// The oldest event for `node`'s subscriber.
    pub fn next_event(&mut self, node: NodeId) -> Option<NetworkEvent> {
        self.slot(node).events.as_mut()?.pop()
    }

    /// Events dropped because `node`'s subscriber queue was full.
    pub fn dropped_events(&mut self, node: NodeId) -> u64 {
        self.slot(node)
            .events
            .as_ref()
            .map_or(0, BoundedQueue::dropped)
    }

    /// What the manager knows about `node`.
    pub fn status(&mut self, node: NodeId) -> NodeStatus {
        self.slot(node).status
    }

    /// SDO responses dropped: late (no transfer to their node in flight) or past [`SDO_INBOX`].
    pub fn stale_sdo_responses(&self) -> u64 {
        self.stale_sdo
    }

    /// Claims `node`'s SDO channel for one transfer: `false` while another transfer to that
    /// node is in flight.
    pub fn claim_sdo(&mut self, node: NodeId) -> bool {
        let slot = self.slot(node);
        if slot.sdo_claimed {
            return false;
        }
        slot.sdo_claimed = true;
        slot.sdo_inbox.clear();
        self.transfers += 1;
        true
    }

    /// Whether any SDO transfer is in flight: a shell that cannot be woken to send polls more
    /// often meanwhile.
    pub fn transfers_in_flight(&self) -> bool {
        self.transfers > 0
    }

    /// Ends the transfer to `node`; responses that still arrive are dropped as stale.
    pub fn release_sdo(&mut self, node: NodeId) {
        let slot = self.slot(node);
        let was_claimed = core::mem::take(&mut slot.sdo_claimed);
        slot.sdo_inbox.clear();
        if was_claimed {
            self.transfers -= 1;
        }
    }

    /// The next SDO response for the transfer to `node`.
    pub fn next_sdo_response(&mut self, node: NodeId) -> Option<CanFrame> {
        self.slot(node).sdo_inbox.pop_front()
    }

    /// Routes a received frame; returns the node it concerned, if any, so a shell wakes only
    /// that node's waiters.
    pub fn handle(&mut self, frame: &CanFrame, now: Duration) -> Option<NodeId> {
        match Message::classify(frame) {
            Message::SdoResponse { node, .. } => {
                self.sdo_response(node, *frame);
                Some(node)
            }
            Message::Pdo {
                kind: PdoKind::Transmit,
                number,
                node,
                frame,
            } => {
                self.deliver(node, NetworkEvent::Pdo { number, frame });
                Some(node)
            }
            Message::Emcy(emcy) => {
                self.slot(emcy.node).status.last_emcy = Some(emcy);
                self.deliver(emcy.node, NetworkEvent::Emcy(emcy));
                Some(emcy.node)
            }
            Message::Heartbeat { node, state } => {
                self.heartbeat_frame(frame, node, state, now);
                Some(node)
            }
            _ => None,
        }
    }

    fn sdo_response(&mut self, node: NodeId, frame: CanFrame) {
        let slot = self.slot(node);
        if slot.sdo_claimed && slot.sdo_inbox.len() < SDO_INBOX {
            slot.sdo_inbox.push_back(frame);
        } else {
            self.stale_sdo += 1;
        }
    }

    fn deliver(&mut self, node: NodeId, event: NetworkEvent) {
        if let Some(queue) = self.slot(node).events.as_mut() {
            queue.push(event);
        }
    }

    /// A heartbeat or boot-up of `node` reporting `state`. The consumer reports a node heard
    /// again as resumed only; a boot-up or state change that came with it is news of its own
    /// (a node that rebooted needs configuring again), so it is delivered after.
    fn heartbeat_frame(&mut self, frame: &CanFrame, node: NodeId, state: NmtState, now: Duration) {
        let before = self.heartbeat.states().state(node);
        let Some(event) = self.heartbeat.handle(frame, now) else {
            return;
        };
        let resumed = matches!(event, HeartbeatEvent::Resumed(_));
        self.heartbeat_event(event);
        if resumed {
            let news = match state {
                NmtState::Initializing => Some(NodeEvent::BootUp(node)),
                to if before != Some(to) => Some(NodeEvent::StateChanged {
                    node,
                    from: before,
                    to,
                }),
                _ => None,
            };
            if let Some(news) = news {
                self.heartbeat_event(HeartbeatEvent::Node(news));
            }
        }
    }

    fn heartbeat_event(&mut self, event: HeartbeatEvent) {
        let (node, event) = match event {
            HeartbeatEvent::Node(NodeEvent::BootUp(node)) => (node, NetworkEvent::BootUp),
            HeartbeatEvent::Node(NodeEvent::StateChanged { node, to, .. }) => {
                (node, NetworkEvent::State(to))
            }
            HeartbeatEvent::Timeout(node) => (node, NetworkEvent::Lost),
            HeartbeatEvent::Resumed(node) => (node, NetworkEvent::Back),
        };
        let state = self.heartbeat.states().state(node);
        let status = &mut self.slot(node).status;
        status.state = state;
        match event {
            NetworkEvent::Lost => status.lost = true,
            NetworkEvent::Back | NetworkEvent::BootUp => status.lost = false,
            _ => {}
        }
        self.deliver(node, event);
    }

    /// Runs the timers due at `now`: queues a due SYNC, reports overdue heartbeats. Returns
    /// whether anything happened (a frame queued or an event delivered).
    pub fn handle_time(&mut self, now: Duration) -> bool {
        let mut happened = false;
        if let Some(frame) = self.sync.as_mut().and_then(|s| s.poll(now)) {
            happened |= self.transmit(frame);
        }
        while let Some(event) = self.heartbeat.poll(now) {
            self.heartbeat_event(event);
            happened = true;
        }
        happened
    }

    /// When [`handle_time`](Self::handle_time) next has something to do.
    pub fn next_deadline(&self) -> Option<Duration> {
        let sync = self.sync.as_ref().map(SyncProducer::next_due);
        match (sync, self.heartbeat.next_deadline()) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canopen::nmt::heartbeat_frame;

    const MS: Duration = Duration::from_millis(1);

    fn sdo_response(node: u8) -> CanFrame {
        CanFrame::new(0x580 + u16::from(node), &[0x43, 0, 0x10, 0, 1, 2, 3, 4]).unwrap()
    }

    #[test]
    fn sdo_responses_reach_only_a_claimed_node() {
        let mut core = NetworkCore::new();
        assert!(core.claim_sdo(NodeId(3)));
        assert!(!core.claim_sdo(NodeId(3)), "one transfer per node");
        assert!(core.transfers_in_flight());
        assert_eq!(core.handle(&sdo_response(3), MS), Some(NodeId(3)));
        core.handle(&sdo_response(4), MS);
        assert_eq!(core.next_sdo_response(NodeId(3)), Some(sdo_response(3)));
        assert_eq!(core.next_sdo_response(NodeId(4)), None);
        assert_eq!(core.stale_sdo_responses(), 1);
        core.release_sdo(NodeId(3));
        core.release_sdo(NodeId(3));
        assert!(!core.transfers_in_flight());
        core.handle(&sdo_response(3), MS);
        assert_eq!(core.stale_sdo_responses(), 2, "late answers are dropped");
    }

    #[test]
    fn pdos_and_emcys_go_to_their_node_only() {
        let mut core = NetworkCore::new();
        core.subscribe(NodeId(5), 8);
        core.subscribe(NodeId(6), 8);
        let tpdo2 = CanFrame::new(0x285, &[1, 2]).unwrap();
        let emcy = CanFrame::new(0x086, &[0x10, 0x23, 0x02, 1, 2, 3, 4, 5]).unwrap();
        core.handle(&tpdo2, MS);
        core.handle(&emcy, MS);
        assert_eq!(
            core.next_event(NodeId(5)),
            Some(NetworkEvent::Pdo {
                number: 2,
                frame: tpdo2
            })
        );
        assert_eq!(core.next_event(NodeId(5)), None);
        let Some(NetworkEvent::Emcy(decoded)) = core.next_event(NodeId(6)) else {
            panic!("the EMCY goes to node 6");
        };
        assert_eq!(decoded.code, 0x2310);
        assert_eq!(core.status(NodeId(6)).last_emcy, Some(decoded));
    }

    #[test]
    fn a_silent_node_is_lost_then_back() {
        let mut core = NetworkCore::new();
        let node = NodeId(9);
        core.subscribe(node, 8);
        core.monitor(node, 100 * MS);
        core.handle(
            &heartbeat_frame(node, NmtState::Initializing),
            Duration::ZERO,
        );
        core.handle(&heartbeat_frame(node, NmtState::PreOperational), 50 * MS);
        assert_eq!(core.next_deadline(), Some(150 * MS));
        assert!(!core.handle_time(149 * MS));
        assert!(core.handle_time(150 * MS));
        assert!(core.status(node).lost);
        core.handle(&heartbeat_frame(node, NmtState::PreOperational), 400 * MS);
        core.handle_time(1000 * MS);
        core.handle(&heartbeat_frame(node, NmtState::Initializing), 1100 * MS);
        let events: Vec<_> = core::iter::from_fn(|| core.next_event(node)).collect();
        assert_eq!(
            events,
            [
                NetworkEvent::BootUp,
                NetworkEvent::Lost,
                NetworkEvent::Back,
                NetworkEvent::Lost,
                NetworkEvent::Back,
                NetworkEvent::BootUp
            ],
            "a node that rebooted while lost is back, and booted"
        );
        assert!(!core.status(node).lost);
    }

    #[test]
    fn sync_is_queued_every_period() {
        let mut core = NetworkCore::new();
        core.set_sync(Some(10 * MS), Duration::ZERO);
        assert!(core.handle_time(Duration::ZERO));
        assert_eq!(core.poll_transmit().map(|f| f.id()), Some(0x080));
        assert!(!core.handle_time(9 * MS));
        assert_eq!(core.next_deadline(), Some(10 * MS));
        core.set_sync(None, 10 * MS);
        assert!(!core.handle_time(20 * MS));
    }

    #[test]
    fn a_replaced_subscription_does_not_unsubscribe_its_successor() {
        let mut core = NetworkCore::new();
        let first = core.subscribe(NodeId(2), 4);
        let second = core.subscribe(NodeId(2), 4);
        core.unsubscribe(first);
        core.handle(&CanFrame::new(0x182, &[1]).unwrap(), MS);
        assert!(
            core.next_event(NodeId(2)).is_some(),
            "the second still receives"
        );
        core.unsubscribe(second);
        core.handle(&CanFrame::new(0x182, &[1]).unwrap(), MS);
        assert_eq!(core.next_event(NodeId(2)), None);
    }

    #[test]
    fn nmt_for_all_nodes_has_target_zero() {
        let mut core = NetworkCore::new();
        core.nmt(NmtCommand::Start, None);
        assert_eq!(core.poll_transmit().unwrap().data(), [0x01, 0x00]);
    }
}
