//! What an LSS master sends on 7E5h (CiA 305): each command, encoded into its 8-byte frame, and
//! decoded again for simulated slaves. Byte 0 is the command specifier; unused bytes are 0
//! ("reserved", CiA 305), as python canopen 2.4.1's `LssMaster` sends them.

use super::{LssError, Response, MASTER_COB, UNCONFIGURED};
use crate::canopen::address::NodeId;
use crate::canopen::frame::CanFrame;

/// The LSS state a global switch puts every slave in (CiA 305).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LssMode {
    /// LSS waiting state: the node runs normally, configure commands are ignored.
    Waiting,
    /// LSS configuration state: the node takes configure, store and inquire commands.
    Configuration,
}

/// One word of the LSS address (identity object 1018h sub 1-4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum IdentityWord {
    /// Vendor-ID (1018h sub 1).
    VendorId,
    /// Product code (1018h sub 2).
    ProductCode,
    /// Revision number (1018h sub 3).
    Revision,
    /// Serial number (1018h sub 4).
    Serial,
}

impl IdentityWord {
    /// The four words in LSS address order.
    pub const ALL: [Self; 4] = [
        Self::VendorId,
        Self::ProductCode,
        Self::Revision,
        Self::Serial,
    ];

    /// Position in the LSS address (0 to 3; the Fastscan LSSSub).
    pub const fn position(self) -> u8 {
        self as u8
    }

    fn from_position(position: u8) -> Option<Self> {
        Self::ALL.get(usize::from(position)).copied()
    }
}

/// The node id a configure command sets: a valid one, or none at all (FFh, CiA 305).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NewNodeId {
    /// Node id 1-127.
    Id(NodeId),
    /// FFh: the node becomes non-configured after its next reset.
    Unconfigured,
}

impl NewNodeId {
    /// The node id `raw` if a configure command may carry it: 1-127 or FFh. 0 and 128-254 are
    /// refused here, before anything is sent.
    pub fn new(raw: u8) -> Result<Self, LssError> {
        match raw {
            UNCONFIGURED => Ok(Self::Unconfigured),
            raw => NodeId::new(raw)
                .map(Self::Id)
                .ok_or(LssError::InvalidNodeId(raw)),
        }
    }

    /// The byte on the wire.
    pub const fn raw(self) -> u8 {
        match self {
            Self::Id(id) => id.get(),
            Self::Unconfigured => UNCONFIGURED,
        }
    }
}

/// The parts of an "identify remote slave" range (CiA 305, command specifiers 46h-4Bh).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RangePart {
    /// Vendor-ID (46h).
    VendorId,
    /// Product code (47h).
    ProductCode,
    /// Lowest revision number (48h).
    RevisionLow,
    /// Highest revision number (49h).
    RevisionHigh,
    /// Lowest serial number (4Ah).
    SerialLow,
    /// Highest serial number (4Bh): the slaves within the range answer this one.
    SerialHigh,
}

impl RangePart {
    /// The six parts in the order a master sends them.
    pub const ALL: [Self; 6] = [
        Self::VendorId,
        Self::ProductCode,
        Self::RevisionLow,
        Self::RevisionHigh,
        Self::SerialLow,
        Self::SerialHigh,
    ];
}

/// A command an LSS master sends.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Command {
    /// Switch state global (04h): every slave to `mode`; no answer.
    SwitchGlobal(LssMode),
    /// Switch state selective (40h-43h): one word of the address; the slave whose address
    /// matches all four answers the serial number (43h) with 44h.
    SwitchSelective(IdentityWord, u32),
    /// Configure node id (11h); answered with an error code.
    ConfigureNodeId(NewNodeId),
    /// Configure bit timing (13h): table selector and index; answered with an error code.
    ConfigureBitTiming {
        /// Table selector (0: the CiA 305 table, see [`BitTiming`](super::BitTiming)).
        table: u8,
        /// Index in the table.
        index: u8,
    },
    /// Activate bit timing (15h): switch after `delay_ms`, stay silent `delay_ms` more; no answer.
    ActivateBitTiming {
        /// The switch delay in milliseconds.
        delay_ms: u16,
    },
    /// Store configuration (17h): keep node id and bit timing across a reset; answered with an
    /// error code.
    Store,
    /// Inquire one word of the address (5Ah-5Dh).
    Inquire(IdentityWord),
    /// Inquire node id (5Eh).
    InquireNodeId,
    /// Identify remote slave (46h-4Bh): one part of an address range.
    IdentifyRemote(RangePart, u32),
    /// Identify non-configured remote slave (4Ch): nodes without a node id answer 50h.
    IdentifyNonConfigured,
    /// Fastscan (51h).
    Fastscan {
        /// IDNumber: the bits of the word found so far.
        id: u32,
        /// BitChecked: the lowest bit compared (0-31), or 80h to reset every slave's scan.
        bit: u8,
        /// LSSSub: the word being scanned (0-3).
        sub: u8,
        /// LSSNext: the word the matching slave scans next.
        next: u8,
    },
}

/// Command specifiers (CiA 305).
mod cs {
    pub const SWITCH_GLOBAL: u8 = 0x04;
    pub const CONFIGURE_NODE_ID: u8 = 0x11;
    pub const CONFIGURE_BIT_TIMING: u8 = 0x13;
    pub const ACTIVATE_BIT_TIMING: u8 = 0x15;
    pub const STORE: u8 = 0x17;
    pub const SWITCH_SELECTIVE: u8 = 0x40;
    pub const IDENTIFY_REMOTE: u8 = 0x46;
    pub const IDENTIFY_NON_CONFIGURED: u8 = 0x4C;
    pub const FASTSCAN: u8 = 0x51;
    pub const INQUIRE: u8 = 0x5A;
    pub const INQUIRE_NODE_ID: u8 = 0x5E;
}

impl Command {
    /// The 8 data bytes.
    pub fn to_bytes(self) -> [u8; 8] {
        let mut data = [0u8; 8];
        let with_word = |data: &mut [u8; 8], cs: u8, word: u32| {
            data[0] = cs;
            data[1..5].copy_from_slice(&word.to_le_bytes());
        };
        match self {
            Self::SwitchGlobal(mode) => {
                data[0] = cs::SWITCH_GLOBAL;
                data[1] = mode as u8;
            }
            Self::SwitchSelective(word, value) => {
                with_word(&mut data, cs::SWITCH_SELECTIVE + word.position(), value);
            }
            Self::ConfigureNodeId(id) => {
                data[0] = cs::CONFIGURE_NODE_ID;
                data[1] = id.raw();
            }
            Self::ConfigureBitTiming { table, index } => {
                data[..3].copy_from_slice(&[cs::CONFIGURE_BIT_TIMING, table, index]);
            }
            Self::ActivateBitTiming { delay_ms } => {
                data[0] = cs::ACTIVATE_BIT_TIMING;
                data[1..3].copy_from_slice(&delay_ms.to_le_bytes());
            }
            Self::Store => data[0] = cs::STORE,
            Self::Inquire(word) => data[0] = cs::INQUIRE + word.position(),
            Self::InquireNodeId => data[0] = cs::INQUIRE_NODE_ID,
            Self::IdentifyRemote(part, value) => {
                with_word(&mut data, cs::IDENTIFY_REMOTE + part as u8, value);
            }
            Self::IdentifyNonConfigured => data[0] = cs::IDENTIFY_NON_CONFIGURED,
            Self::Fastscan { id, bit, sub, next } => {
                with_word(&mut data, cs::FASTSCAN, id);
                data[5..8].copy_from_slice(&[bit, sub, next]);
            }
        }
        data
    }

    /// The frame on 7E5h.
    pub fn encode(self) -> CanFrame {
        CanFrame::full(MASTER_COB, self.to_bytes())
    }

    /// The command in `frame`, if it is an LSS master frame this module knows (for slaves and
    /// simulators). Frames shorter than 8 bytes are read as if zero-padded.
    pub fn decode(frame: &CanFrame) -> Option<Self> {
        if frame.id() != MASTER_COB || frame.is_remote() {
            return None;
        }
        let data = frame.data();
        let mut bytes = [0u8; 8];
        bytes[..data.len()].copy_from_slice(data);
        let word = u32::from_le_bytes([bytes[1], bytes[2], bytes[3], bytes[4]]);
        Some(match bytes[0] {
            cs::SWITCH_GLOBAL => Self::SwitchGlobal(match bytes[1] {
                0 => LssMode::Waiting,
                1 => LssMode::Configuration,
                _ => return None,
            }),
            c @ 0x40..=0x43 => Self::SwitchSelective(IdentityWord::from_position(c - 0x40)?, word),
            cs::CONFIGURE_NODE_ID => Self::ConfigureNodeId(NewNodeId::new(bytes[1]).ok()?),
            cs::CONFIGURE_BIT_TIMING => Self::ConfigureBitTiming {
                table: bytes[1],
                index: bytes[2],
            },
            cs::ACTIVATE_BIT_TIMING => Self::ActivateBitTiming {
                delay_ms: u16::from_le_bytes([bytes[1], bytes[2]]),
            },
            cs::STORE => Self::Store,
            c @ 0x46..=0x4B => {
                Self::IdentifyRemote(*RangePart::ALL.get(usize::from(c - 0x46))?, word)
            }
            cs::IDENTIFY_NON_CONFIGURED => Self::IdentifyNonConfigured,
            cs::FASTSCAN => Self::Fastscan {
                id: word,
                bit: bytes[5],
                sub: bytes[6],
                next: bytes[7],
            },
            c @ 0x5A..=0x5D => Self::Inquire(IdentityWord::from_position(c - cs::INQUIRE)?),
            cs::INQUIRE_NODE_ID => Self::InquireNodeId,
            _ => return None,
        })
    }

    /// Whether `response` is this command's answer. Commands without an answer (global switch,
    /// activate bit timing, all but the last part of a selective switch or a range) match none.
    pub fn is_answered_by(&self, response: &Response) -> bool {
        match (self, response) {
            (Self::SwitchSelective(IdentityWord::Serial, _), Response::SwitchSelective) => true,
            (Self::ConfigureNodeId(_), Response::Confirmed(super::Confirmed::NodeId, _)) => true,
            (
                Self::ConfigureBitTiming { .. },
                Response::Confirmed(super::Confirmed::BitTiming, _),
            ) => true,
            (Self::Store, Response::Confirmed(super::Confirmed::Store, _)) => true,
            (Self::Inquire(word), Response::Inquired(answered, _)) => word == answered,
            (Self::InquireNodeId, Response::NodeId(_)) => true,
            (Self::IdentifyRemote(RangePart::SerialHigh, _), Response::IdentifySlave) => true,
            (Self::Fastscan { .. }, Response::IdentifySlave) => true,
            (Self::IdentifyNonConfigured, Response::IdentifyNonConfigured) => true,
            _ => false,
        }
    }

    /// Whether a slave answers this command at all.
    pub fn expects_answer(&self) -> bool {
        !matches!(
            self,
            Self::SwitchGlobal(_)
                | Self::ActivateBitTiming { .. }
                | Self::SwitchSelective(
                    IdentityWord::VendorId | IdentityWord::ProductCode | IdentityWord::Revision,
                    _
                )
                | Self::IdentifyRemote(
                    RangePart::VendorId
                        | RangePart::ProductCode
                        | RangePart::RevisionLow
                        | RangePart::RevisionHigh
                        | RangePart::SerialLow,
                    _
                )
        )
    }
}
