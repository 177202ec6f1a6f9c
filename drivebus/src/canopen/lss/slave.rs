//! An LSS slave (CiA 305), sans-I/O, for simulators and test peers: answers from its LSS
//! address (identity object 1018h sub 1-4), takes a node id and bit timing in configuration
//! state, and keeps them across a power cycle only once stored.
//!
//! Node ids, as CiA 305 has them: the *active* id is the one the node communicates with; a
//! configure command sets the *pending* one, which becomes active at the next NMT reset (node
//! or communication) — or at once when the node had none and is switched back to waiting
//! state; *store* makes the pending id the one a power cycle starts with.

use super::command::{IdentityWord, RangePart};
use super::UNCONFIGURED;
use super::{BitTiming, Command, ConfigureError, Confirmed, LssAddress, LssMode, Response};
use crate::canopen::frame::CanFrame;

/// What the node must do after a command, beyond the answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SlaveEvent {
    /// A node without an id got one and left configuration state: it continues its
    /// initialisation with this id (boot-up), as after an NMT reset communication.
    NodeIdAssigned(u8),
    /// Activate bit timing: switch to the pending bit timing after `delay_ms`.
    BitTimingActivated {
        /// The bit timing now in use.
        timing: BitTiming,
        /// The switch delay in milliseconds.
        delay_ms: u16,
    },
}

/// An LSS slave: see the module documentation.
#[derive(Debug, Clone)]
pub struct LssSlave {
    address: LssAddress,
    mode: LssMode,
    active: u8,
    pending: u8,
    stored: u8,
    timing: BitTiming,
    pending_timing: BitTiming,
    stored_timing: BitTiming,
    supported: u16,
    can_store: bool,
    selective: u8,
    range: u8,
    fastscan: u8,
}

impl LssSlave {
    /// A slave with LSS address `address` at node id `node` (FFh: none), at `timing`, taking
    /// every bit timing of the CiA 305 table but automatic detection, able to store.
    pub fn new(address: LssAddress, node: u8, timing: BitTiming) -> Self {
        Self {
            address,
            mode: LssMode::Waiting,
            active: node,
            pending: node,
            stored: node,
            timing,
            pending_timing: timing,
            stored_timing: timing,
            supported: 0x01FF,
            can_store: true,
            selective: 0,
            range: 0,
            fastscan: 0,
        }
    }

    /// Takes only the bit timings in `supported` (the others are refused with code 1).
    pub fn with_bit_timings(mut self, supported: &[BitTiming]) -> Self {
        self.supported = supported.iter().fold(0, |m, t| m | 1 << t.index());
        self
    }

    /// Whether store configuration is supported (if not, it is refused with code 1).
    pub fn with_store(mut self, can_store: bool) -> Self {
        self.can_store = can_store;
        self
    }

    /// The active node id (FFh: none).
    pub fn node_id(&self) -> u8 {
        self.active
    }

    /// The node id the next reset activates.
    pub fn pending_node_id(&self) -> u8 {
        self.pending
    }

    /// The node id a power cycle starts with.
    pub fn stored_node_id(&self) -> u8 {
        self.stored
    }

    /// The bit timing in use.
    pub fn bit_timing(&self) -> BitTiming {
        self.timing
    }

    /// The stored bit timing.
    pub fn stored_bit_timing(&self) -> BitTiming {
        self.stored_timing
    }

    /// The LSS state.
    pub fn mode(&self) -> LssMode {
        self.mode
    }

    /// The LSS address.
    pub fn address(&self) -> LssAddress {
        self.address
    }

    /// NMT reset node or communication: the pending node id becomes active; returns it.
    pub fn reset_communication(&mut self) -> u8 {
        self.active = self.pending;
        self.active
    }

    /// Power off and on: the stored node id and bit timing, LSS waiting state.
    pub fn power_cycle(&mut self) -> u8 {
        self.pending = self.stored;
        self.active = self.stored;
        self.pending_timing = self.stored_timing;
        self.timing = self.stored_timing;
        self.mode = LssMode::Waiting;
        self.selective = 0;
        self.range = 0;
        self.fastscan = 0;
        self.active
    }

    /// Handles a frame (of any COB-ID): the answer to send, and what else to do.
    pub fn handle(&mut self, frame: &CanFrame) -> (Option<CanFrame>, Option<SlaveEvent>) {
        if frame.id() != super::MASTER_COB {
            return (None, None);
        }
        let Some(command) = Command::decode(frame) else {
            // A configure node id with an id no node may have (0, 128-254): code 1.
            let refused =
                frame.data().first() == Some(&0x11) && self.mode == LssMode::Configuration;
            let answer =
                Response::Confirmed(Confirmed::NodeId, Err(ConfigureError::NodeIdOutOfRange));
            return (refused.then(|| answer.encode()), None);
        };
        let (answer, event) = self.command(command);
        (answer.map(Response::encode), event)
    }

    fn command(&mut self, command: Command) -> (Option<Response>, Option<SlaveEvent>) {
        let configuring = self.mode == LssMode::Configuration;
        let answer = match command {
            Command::SwitchGlobal(mode) => return (None, self.switch(mode)),
            Command::SwitchSelective(word, value) => self.selective(word, value),
            Command::IdentifyRemote(part, value) => self.range(part, value),
            Command::IdentifyNonConfigured => {
                (self.pending == UNCONFIGURED).then_some(Response::IdentifyNonConfigured)
            }
            Command::Fastscan { id, bit, sub, next } => self.fastscan(id, bit, sub, next),
            _ if !configuring => None,
            Command::ConfigureNodeId(id) => {
                self.pending = id.raw();
                Some(Response::Confirmed(Confirmed::NodeId, Ok(())))
            }
            Command::ConfigureBitTiming { table, index } => {
                Some(self.configure_timing(table, index))
            }
            Command::ActivateBitTiming { delay_ms } => {
                self.timing = self.pending_timing;
                let event = SlaveEvent::BitTimingActivated {
                    timing: self.timing,
                    delay_ms,
                };
                return (None, Some(event));
            }
            Command::Store => Some(self.store()),
            Command::Inquire(word) => Some(Response::Inquired(
                word,
                self.address.words()[usize::from(word.position())],
            )),
            Command::InquireNodeId => Some(Response::NodeId(self.active)),
        };
        (answer, None)
    }

    fn switch(&mut self, mode: LssMode) -> Option<SlaveEvent> {
        let was = core::mem::replace(&mut self.mode, mode);
        self.selective = 0;
        let assigned = was == LssMode::Configuration
            && mode == LssMode::Waiting
            && self.active == UNCONFIGURED
            && self.pending != UNCONFIGURED;
        assigned.then(|| SlaveEvent::NodeIdAssigned(self.reset_communication()))
    }

    /// The four words of a selective switch must arrive in order and all match (CiA 305).
    fn selective(&mut self, word: IdentityWord, value: u32) -> Option<Response> {
        let position = word.position();
        let matches = self.address.words()[usize::from(position)] == value;
        if self.mode != LssMode::Waiting || position != self.selective || !matches {
            self.selective = 0;
            return None;
        }
        self.selective += 1;
        if word != IdentityWord::Serial {
            return None;
        }
        self.selective = 0;
        self.mode = LssMode::Configuration;
        Some(Response::SwitchSelective)
    }

    /// The six parts of a range, in order: vendor and product equal, revision and serial within.
    fn range(&mut self, part: RangePart, value: u32) -> Option<Response> {
        let a = self.address;
        let position = part as u8;
        let within = match part {
            RangePart::VendorId => a.vendor_id == value,
            RangePart::ProductCode => a.product_code == value,
            RangePart::RevisionLow => a.revision >= value,
            RangePart::RevisionHigh => a.revision <= value,
            RangePart::SerialLow => a.serial >= value,
            RangePart::SerialHigh => a.serial <= value,
        };
        if position != self.range || !within {
            self.range = 0;
            return None;
        }
        self.range += 1;
        if part != RangePart::SerialHigh {
            return None;
        }
        self.range = 0;
        Some(Response::IdentifySlave)
    }

    /// Fastscan: only non-configured slaves in waiting state take part (CiA 305).
    fn fastscan(&mut self, id: u32, bit: u8, sub: u8, next: u8) -> Option<Response> {
        if self.pending != UNCONFIGURED || self.mode != LssMode::Waiting {
            return None;
        }
        if bit == 0x80 {
            self.fastscan = 0;
            return Some(Response::IdentifySlave);
        }
        if bit > 31 || sub > 3 || next > 3 || sub != self.fastscan {
            return None;
        }
        let mask = u32::MAX << bit;
        let own = self.address.words()[usize::from(sub)];
        if (own ^ id) & mask != 0 {
            return None;
        }
        if bit == 0 {
            self.fastscan = next;
            if next < sub {
                self.mode = LssMode::Configuration;
            }
        }
        Some(Response::IdentifySlave)
    }

    fn configure_timing(&mut self, table: u8, index: u8) -> Response {
        let timing = BitTiming::from_index(index)
            .filter(|t| table == 0 && self.supported & (1 << t.index()) != 0);
        let verdict = match timing {
            Some(timing) => {
                self.pending_timing = timing;
                Ok(())
            }
            None => Err(ConfigureError::BitTimingNotSupported),
        };
        Response::Confirmed(Confirmed::BitTiming, verdict)
    }

    fn store(&mut self) -> Response {
        if !self.can_store {
            return Response::Confirmed(Confirmed::Store, Err(ConfigureError::StoreNotSupported));
        }
        self.stored = self.pending;
        self.stored_timing = self.pending_timing;
        Response::Confirmed(Confirmed::Store, Ok(()))
    }
}
