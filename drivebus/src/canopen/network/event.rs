//! What the network manager tells a node's subscriber: the node's own frames and the changes
//! the manager noticed.

use crate::canopen::emcy::Emcy;
use crate::canopen::frame::CanFrame;
use crate::canopen::nmt::NmtState;

/// One thing that happened to a node, delivered to its subscriber.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NetworkEvent {
    /// A transmit PDO of the node's default connection set (COB-ID 0x180/0x280/0x380/0x480 +
    /// node id), for a [`PdoLayout`](crate::canopen::pdo::PdoLayout) to decode.
    Pdo {
        /// TPDO 1..=4.
        number: u8,
        /// The frame as received.
        frame: CanFrame,
    },
    /// An emergency the node sent.
    Emcy(Emcy),
    /// The node sent its boot-up message: it (re)started and is pre-operational.
    BootUp,
    /// The node's heartbeat reports a state other than the last one seen.
    State(NmtState),
    /// The node sent no heartbeat within its consumer time. Reported once per silence.
    Lost,
    /// A node reported lost is heard again.
    Back,
}
