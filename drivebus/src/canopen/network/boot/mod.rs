//! Network boot (CiA 302 in spirit), one node at a time and many at once: probe the node,
//! check its identity (1018h), set its heartbeat (1017h), configure its PDOs, write its boot
//! parameters, start it. A missing node or one with a foreign identity is reported and left
//! alone; a node that aborts a step is reported with the step and the abort code; the other
//! nodes still boot. Every configuration item is read and compared first and written only
//! where it differs, so booting a booted network again sends no download.
//!
//! [`BootProcedure`] is the sans-I/O procedure: it says what to ask of the node next and is
//! told how that went. [`boot_node`] and [`boot_all`] drive it over a [`Network`](super::Network)
//! (a thread per node); with feature `async`, [`boot_node_async`] over an
//! [`AsyncNetwork`](super::AsyncNetwork).

/// The loop both drivers run over a network handle: the procedure's reads and writes through
/// the node's SDO handle, its NMT through the network, then the heartbeat watched. The async
/// driver passes `await`, and each request is awaited; the blocking one passes nothing.
macro_rules! drive_boot {
    ($network:expr, $plan:expr, $timeout:expr $(, $awaited:tt)?) => {{
        use $crate::canopen::network::boot::{Action, BootProcedure};
        let (network, plan) = ($network, $plan);
        let node = plan.node;
        let mut sdo = network.node(node).with_timeout($timeout);
        let mut procedure = BootProcedure::new(plan);
        loop {
            match procedure.action() {
                Action::Read { index, subindex } => {
                    let mut out = [0u8; 4];
                    let read = sdo.upload(node, index, subindex, &mut out)$(.$awaited)?;
                    procedure.read(read.map(|len| $crate::canopen::network::boot::value(out, len)));
                }
                Action::Write { index, subindex, data } => {
                    let wrote = sdo.download(node, index, subindex, data)$(.$awaited)?;
                    procedure.wrote(wrote);
                }
                Action::Nmt(command) => procedure.sent(network.nmt(command, Some(node))),
                Action::Finished => break,
            }
        }
        if let Some(timeout) = procedure.heartbeat_watch() {
            network.monitor_heartbeat(node, timeout);
        }
        procedure.report()
    }};
}

#[cfg(feature = "async")]
mod async_boot;
mod blocking;
mod item;
mod pdo;
mod procedure;

pub use crate::canopen::pdo::PdoSetup;
#[cfg(feature = "async")]
pub use async_boot::boot_node_async;
pub use blocking::{boot_all, boot_node};
pub use procedure::{Action, BootProcedure};

use core::fmt;
use core::time::Duration;
use std::vec::Vec;

use crate::canopen::address::NodeId;
use crate::error::BusError;

/// The identity a node must report (1018h sub 1-3); `None` entries are not checked.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ExpectedIdentity {
    /// Vendor-ID (1018h sub 1).
    pub vendor_id: Option<u32>,
    /// Product code (1018h sub 2).
    pub product_code: Option<u32>,
    /// Revision number (1018h sub 3).
    pub revision: Option<u32>,
}

impl ExpectedIdentity {
    /// The expected value of 1018h sub `subindex` (1-3).
    pub fn entry(&self, subindex: u8) -> Option<u32> {
        match subindex {
            1 => self.vendor_id,
            2 => self.product_code,
            3 => self.revision,
            _ => None,
        }
    }
}

/// One object value written at boot, raw (as it goes on the wire).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BootWrite {
    /// Object index.
    pub index: u16,
    /// Subindex.
    pub subindex: u8,
    /// The value's bytes, little-endian as SDO carries them.
    pub data: Vec<u8>,
}

/// What booting one node does.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NodeBoot {
    /// The node.
    pub node: NodeId,
    /// The identity it must report before anything is written.
    pub identity: ExpectedIdentity,
    /// Its heartbeat producer time (1017h), if one is to be set; the manager then watches the
    /// heartbeat with [`consumer_timeout`].
    pub heartbeat: Option<Duration>,
    /// The PDOs to configure, in this order, after the heartbeat and before the boot
    /// parameters.
    pub pdos: Vec<PdoSetup>,
    /// The boot parameters, written in this order.
    pub writes: Vec<BootWrite>,
    /// Send NMT Start to the node at the end.
    pub start: bool,
}

impl NodeBoot {
    /// A plan that only probes `node` and starts it.
    pub fn new(node: NodeId) -> Self {
        Self {
            node,
            identity: ExpectedIdentity::default(),
            heartbeat: None,
            pdos: Vec::new(),
            writes: Vec::new(),
            start: true,
        }
    }
}

/// How long the manager waits for a heartbeat produced every `period` before it reports the
/// node lost: twice the period plus 50 ms, so one lost frame or a busy bus is no loss.
pub fn consumer_timeout(period: Duration) -> Duration {
    period * 2 + Duration::from_millis(50)
}

/// A step of the boot, for reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BootStep {
    /// The probe: an upload of the device type (1000h).
    Probe,
    /// The identity check of 1018h sub 1-3.
    Identity(u8),
    /// Setting the heartbeat producer time (1017h).
    Heartbeat,
    /// The PDO of this position in [`NodeBoot::pdos`] (disable, map, enable).
    Pdo(usize),
    /// The boot parameter of this position in [`NodeBoot::writes`].
    Write(usize),
    /// NMT Start.
    Start,
}

impl fmt::Display for BootStep {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Probe => f.write_str("probe (1000h)"),
            Self::Identity(sub) => write!(f, "identity check (1018h sub {sub})"),
            Self::Heartbeat => f.write_str("heartbeat producer time (1017h)"),
            Self::Pdo(n) => write!(f, "PDO configuration {}", n + 1),
            Self::Write(n) => write!(f, "boot parameter {}", n + 1),
            Self::Start => f.write_str("NMT start"),
        }
    }
}

/// Why a node was not booted.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum BootError {
    /// The node did not answer the probe: not on the bus (or not powered). Left alone.
    Missing,
    /// The node reports another identity than expected: left alone, nothing written.
    Foreign {
        /// The 1018h subindex that differs (1 vendor, 2 product, 3 revision).
        subindex: u8,
        /// The expected value.
        expected: u32,
        /// What the node reported.
        found: u32,
    },
    /// A step failed: an abort (with its code) or another bus error.
    Step {
        /// The step.
        step: BootStep,
        /// What went wrong.
        error: BusError,
    },
}

impl fmt::Display for BootError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Missing => f.write_str("no answer to the probe: not on the bus; left alone"),
            Self::Foreign {
                subindex,
                expected,
                found,
            } => write!(
                f,
                "foreign identity: 1018h sub {subindex} is {found:#010x}, expected {expected:#010x}; left alone"
            ),
            Self::Step { step, error } => write!(f, "{step} failed: {error}"),
        }
    }
}

impl std::error::Error for BootError {}

/// The value of an upload of at most 4 bytes, little-endian.
pub(crate) fn value(out: [u8; 4], len: usize) -> u32 {
    let mut bytes = [0u8; 4];
    let len = len.min(4);
    bytes[..len].copy_from_slice(&out[..len]);
    u32::from_le_bytes(bytes)
}

/// How booting one node ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BootReport {
    /// The node.
    pub node: NodeId,
    /// Its device type (1000h) when it answered the probe.
    pub device_type: Option<u32>,
    /// Booted, or why not.
    pub result: Result<(), BootError>,
    /// The configuration items (heartbeat, PDOs, boot parameters) written because the node
    /// held another value.
    pub written: usize,
    /// The configuration items the node already held: read, compared, not written.
    pub unchanged: usize,
}
