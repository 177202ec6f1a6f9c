//! NMT: master commands, node states, boot-up detection and state tracking.

use core::time::Duration;

use super::address::NodeId;
use super::frame::{cob, CanFrame};

/// An NMT node-control command (CiA 301 §7.2.8.3.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NmtCommand {
    /// Enter OPERATIONAL.
    Start,
    /// Enter STOPPED.
    Stop,
    /// Enter PRE-OPERATIONAL.
    EnterPreOperational,
    /// Reset the application (and communication).
    ResetNode,
    /// Reset communication parameters.
    ResetCommunication,
}

impl NmtCommand {
    /// The command specifier byte.
    pub const fn specifier(self) -> u8 {
        match self {
            Self::Start => 0x01,
            Self::Stop => 0x02,
            Self::EnterPreOperational => 0x80,
            Self::ResetNode => 0x81,
            Self::ResetCommunication => 0x82,
        }
    }

    /// The command for a specifier byte.
    pub const fn from_specifier(cs: u8) -> Option<Self> {
        Some(match cs {
            0x01 => Self::Start,
            0x02 => Self::Stop,
            0x80 => Self::EnterPreOperational,
            0x81 => Self::ResetNode,
            0x82 => Self::ResetCommunication,
            _ => return None,
        })
    }

    /// The frame that sends this command to `node`, or to every node for `None`.
    pub fn frame(self, node: Option<NodeId>) -> CanFrame {
        let target = node.map_or(0, NodeId::get);
        CanFrame::full(cob::NMT, [self.specifier(), target, 0, 0, 0, 0, 0, 0]).truncated(2)
    }

    /// Decodes an NMT command frame: the command and its target (`None` = all nodes).
    pub fn decode(frame: &CanFrame) -> Option<(Self, Option<NodeId>)> {
        if frame.id() != cob::NMT || frame.is_remote() || frame.dlc() != 2 {
            return None;
        }
        let data = frame.data();
        let command = Self::from_specifier(data[0])?;
        Some((command, NodeId::new(data[1])))
    }

    /// The state a node enters on this command (resets end in boot-up, then pre-operational).
    pub const fn target_state(self) -> NmtState {
        match self {
            Self::Start => NmtState::Operational,
            Self::Stop => NmtState::Stopped,
            Self::EnterPreOperational => NmtState::PreOperational,
            Self::ResetNode | Self::ResetCommunication => NmtState::Initializing,
        }
    }
}

/// A node's NMT state as its heartbeat reports it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NmtState {
    /// Boot-up (the one-off 0x00 message).
    Initializing,
    /// STOPPED (0x04).
    Stopped,
    /// OPERATIONAL (0x05).
    Operational,
    /// PRE-OPERATIONAL (0x7F).
    PreOperational,
}

impl NmtState {
    /// The state byte of a heartbeat.
    pub const fn code(self) -> u8 {
        match self {
            Self::Initializing => 0x00,
            Self::Stopped => 0x04,
            Self::Operational => 0x05,
            Self::PreOperational => 0x7F,
        }
    }

    /// The state for a heartbeat byte; bit 7 (the node-guarding toggle) is ignored.
    pub const fn from_code(code: u8) -> Option<Self> {
        Some(match code & 0x7F {
            0x00 => Self::Initializing,
            0x04 => Self::Stopped,
            0x05 => Self::Operational,
            0x7F => Self::PreOperational,
            _ => return None,
        })
    }
}

/// Decodes a heartbeat / boot-up / node-guarding answer: the node and the state it reports.
pub fn decode_heartbeat(frame: &CanFrame) -> Option<(NodeId, NmtState)> {
    let id = frame.id();
    if frame.is_remote()
        || frame.dlc() != 1
        || !(cob::HEARTBEAT + 1..=cob::HEARTBEAT + 127).contains(&id)
    {
        return None;
    }
    let node = NodeId((id - cob::HEARTBEAT) as u8);
    Some((node, NmtState::from_code(frame.data()[0])?))
}

/// The frame a node sends to report `state` (a boot-up for [`NmtState::Initializing`]).
pub fn heartbeat_frame(node: NodeId, state: NmtState) -> CanFrame {
    CanFrame::full(
        cob::HEARTBEAT + u16::from(node.0),
        [state.code(), 0, 0, 0, 0, 0, 0, 0],
    )
    .truncated(1)
}

/// What changed when a node reported its state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NodeEvent {
    /// The node sent its boot-up message: it (re)started and is now pre-operational.
    BootUp(NodeId),
    /// The node reports a state different from the last one seen.
    StateChanged {
        /// The node.
        node: NodeId,
        /// The previously known state, if any.
        from: Option<NmtState>,
        /// The reported state.
        to: NmtState,
    },
}

/// The last known NMT state of every node, from boot-ups and heartbeats.
#[derive(Debug, Clone)]
pub struct NodeStates {
    states: [Option<NmtState>; 128],
    seen: [Option<Duration>; 128],
}

impl Default for NodeStates {
    fn default() -> Self {
        Self::new()
    }
}

impl NodeStates {
    /// No node known.
    pub const fn new() -> Self {
        Self {
            states: [None; 128],
            seen: [None; 128],
        }
    }

    /// Feeds a frame; returns what changed. Frames other than heartbeats are ignored.
    pub fn handle(&mut self, frame: &CanFrame, now: Duration) -> Option<NodeEvent> {
        let (node, state) = decode_heartbeat(frame)?;
        let slot = node.0 as usize;
        let from = self.states[slot];
        self.seen[slot] = Some(now);
        if state == NmtState::Initializing {
            // After boot-up a node is pre-operational without announcing it again.
            self.states[slot] = Some(NmtState::PreOperational);
            return Some(NodeEvent::BootUp(node));
        }
        self.states[slot] = Some(state);
        (from != Some(state)).then_some(NodeEvent::StateChanged {
            node,
            from,
            to: state,
        })
    }

    /// The last state `node` reported.
    pub fn state(&self, node: NodeId) -> Option<NmtState> {
        self.states.get(node.0 as usize).copied().flatten()
    }

    /// When `node` was last heard from.
    pub fn last_seen(&self, node: NodeId) -> Option<Duration> {
        self.seen.get(node.0 as usize).copied().flatten()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn command_frames() {
        let frame = NmtCommand::Start.frame(Some(NodeId(0x10)));
        assert_eq!((frame.id(), frame.data()), (0, &[0x01, 0x10][..]));
        let frame = NmtCommand::ResetCommunication.frame(None);
        assert_eq!(frame.data(), &[0x82, 0x00]);
        for command in [
            NmtCommand::Start,
            NmtCommand::Stop,
            NmtCommand::EnterPreOperational,
            NmtCommand::ResetNode,
            NmtCommand::ResetCommunication,
        ] {
            assert_eq!(
                NmtCommand::decode(&command.frame(Some(NodeId(3)))),
                Some((command, Some(NodeId(3))))
            );
        }
        assert_eq!(
            NmtCommand::decode(&CanFrame::new(0, &[0x03, 1]).unwrap()),
            None
        );
    }

    #[test]
    fn every_state_transition_is_reported_once() {
        let mut states = NodeStates::new();
        let node = NodeId(4);
        let at = Duration::from_millis(5);
        let boot = heartbeat_frame(node, NmtState::Initializing);
        assert_eq!(boot.data(), &[0x00]);
        assert_eq!(states.handle(&boot, at), Some(NodeEvent::BootUp(node)));
        assert_eq!(states.state(node), Some(NmtState::PreOperational));
        let pre = heartbeat_frame(node, NmtState::PreOperational);
        assert_eq!(states.handle(&pre, at), None, "no change after boot-up");
        for (from, to) in [
            (NmtState::PreOperational, NmtState::Operational),
            (NmtState::Operational, NmtState::Stopped),
            (NmtState::Stopped, NmtState::PreOperational),
        ] {
            let event = states.handle(&heartbeat_frame(node, to), at);
            assert_eq!(
                event,
                Some(NodeEvent::StateChanged {
                    node,
                    from: Some(from),
                    to
                })
            );
            assert_eq!(states.handle(&heartbeat_frame(node, to), at), None);
        }
        assert_eq!(
            states.handle(&boot, at),
            Some(NodeEvent::BootUp(node)),
            "a reboot is seen"
        );
        assert_eq!(states.last_seen(node), Some(at));
    }

    #[test]
    fn node_guarding_toggle_and_foreign_frames() {
        let mut states = NodeStates::new();
        let guarded = CanFrame::new(0x705, &[0x85]).unwrap();
        assert_eq!(
            decode_heartbeat(&guarded),
            Some((NodeId(5), NmtState::Operational))
        );
        for frame in [
            CanFrame::new(0x705, &[0x05, 0]).unwrap(),
            CanFrame::new(0x700, &[0x05]).unwrap(),
            CanFrame::new(0x705, &[0x33]).unwrap(),
            CanFrame::remote(0x705, 1).unwrap(),
            CanFrame::new(0x185, &[0x05]).unwrap(),
        ] {
            assert_eq!(states.handle(&frame, Duration::ZERO), None);
        }
    }
}
