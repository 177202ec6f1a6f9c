//! LSS (CiA 305 Layer Setting Services) master, sans-I/O: set node ids and bit rates of nodes
//! on the bus, find the nodes that have none (Fastscan), and (for simulators) decode what a
//! master sends.
//!
//! LSS uses two COB-IDs (CiA 305): the master sends on [`MASTER_COB`] (7E5h), every slave answers
//! on [`SLAVE_COB`] (7E4h). Every LSS frame is 8 bytes; byte 0 is the command specifier.
//!
//! * [`command`] — what a master sends ([`Command`]), encoded and decoded.
//! * [`response`] — what a slave answers ([`Response`]), decoded into typed values.
//! * [`exchange`] — one command and the answers it waits for, driven by the caller's clock.
//! * [`fastscan`] — the Fastscan state machine: the identity of one non-configured node, bit by bit.
//! * [`request`] — each master operation as the commands it sends and how its outcome reads,
//!   shared by the blocking and the async master.
//! * [`error`] — the typed failures ([`LssError`], [`ConfigureError`]).
//! * [`bit_timing`] — the CiA 305 bit timing table.
//! * `slave` — (feature `server`) an LSS slave for simulators and test peers.
//!
//! Like the SDO transfers, [`Exchange`] and [`Fastscan`] never read a clock or touch a bus: a
//! driver loop drains `poll_transmit`, feeds received frames to `handle` and calls
//! `handle_timeout` once `deadline` passes. The blocking driver is `canopen::client::lss`, the
//! async one (feature `async`) `canopen::async_client::lss`.

pub mod bit_timing;
pub mod command;
pub mod error;
pub mod exchange;
pub mod fastscan;
pub mod request;
pub mod response;
#[cfg(feature = "server")]
pub mod slave;

pub use bit_timing::BitTiming;
pub use command::{Command, IdentityWord, LssMode, NewNodeId};
pub use error::{ConfigureError, LssError};
pub use exchange::{Answers, Exchange, Outcome, Progress};
pub use fastscan::{Fastscan, FastscanProgress};
pub use request::Request;
pub use response::{Confirmed, Response};
#[cfg(feature = "server")]
pub use slave::{LssSlave, SlaveEvent};

/// COB-ID the LSS master sends on (CiA 305).
pub const MASTER_COB: u16 = 0x7E5;

/// COB-ID every LSS slave answers on (CiA 305).
pub const SLAVE_COB: u16 = 0x7E4;

/// The node id of a node that has none (CiA 305: "not configured", FFh).
pub const UNCONFIGURED: u8 = 0xFF;

/// The LSS address of a node: its identity object 1018h sub 1-4 (CiA 305 names these 128 bits
/// the LSS address).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct LssAddress {
    /// Vendor-ID (1018h sub 1).
    pub vendor_id: u32,
    /// Product code (1018h sub 2).
    pub product_code: u32,
    /// Revision number (1018h sub 3).
    pub revision: u32,
    /// Serial number (1018h sub 4).
    pub serial: u32,
}

impl LssAddress {
    /// The four words in Fastscan order (LSSSub 0 to 3).
    pub const fn words(&self) -> [u32; 4] {
        [
            self.vendor_id,
            self.product_code,
            self.revision,
            self.serial,
        ]
    }

    /// The address from its four words in Fastscan order.
    pub const fn from_words(words: [u32; 4]) -> Self {
        Self {
            vendor_id: words[0],
            product_code: words[1],
            revision: words[2],
            serial: words[3],
        }
    }
}

#[cfg(test)]
mod tests;
