//! The one deliberate way to change an SRDO's safety configuration: in NMT Pre-Operational only,
//! write the communication object (and, if asked, the mapping), then the recomputed signature
//! (13FFh sub n), then the validity flag 13FEh = A5h — the order of the SWD quick start (line
//! 4111) and of the manual's rules: signatures are updated in Pre-Operational (line 3570), any
//! change to an SRDO's configuration resets 13FEh to 00h (line 3581), and 13FEh = A5h declares
//! the configuration valid (lines 3574-3579).
//!
//! Not written: the transmission type (sub-index 4), which the SWD fixes at FEh and refuses to
//! change (line 1711). SRVT (sub-index 3) is written as the SWD's object tables declare it, two
//! bytes (U16, e.g. line 1739), although the signature takes one byte of it.

use core::fmt;

use super::config::{SrdoConfig, SrdoDirection};
use super::mapping::check_mapping;
use super::signature::signature;
use super::SrdoError;
use crate::canopen::address::NodeId;
use crate::canopen::link::SdoBus;
use crate::canopen::nmt::NmtState;
use crate::canopen::pdo::SdoWrite;
use crate::error::BusError;

/// The safety configuration checksum object: sub-index n holds SRDO n's signature.
pub const SIGNATURES: u16 = 0x13FF;
/// The SRDO configuration-valid object (sub-index 0).
pub const CONFIGURATION_VALID: u16 = 0x13FE;
/// The value of [`CONFIGURATION_VALID`] that declares the configuration valid.
pub const VALID: u8 = 0xA5;

/// Whether the safety write also writes the mapping object. The SWD's mapping objects are
/// read-only (e.g. lines 1744-1746), so its safety writes keep the mapping.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MappingWrite {
    /// Write only the communication object; the mapping signed is the one the drive holds.
    Keep,
    /// Also write the mapping object: zero the count, the entries, the count.
    Write,
}

/// Why a safety write was refused or stopped.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SafetyWriteError {
    /// The node is not in Pre-Operational; nothing was sent.
    NotPreOperational {
        /// The state the caller reported.
        state: NmtState,
    },
    /// The configuration is not valid or cannot be signed; nothing was sent.
    Config(SrdoError),
    /// The handle refuses writes (the drive's identity or configuration is not the
    /// description's); nothing was sent.
    WritesRefused(crate::error::WriteRefusal),
    /// The safety function has no such instance (SLS 9); nothing was sent.
    NoSuchFunction {
        /// The function.
        function: &'static str,
        /// The instance asked for.
        instance: u8,
    },
    /// A value of an object the function's signature does not cover: writing it would change
    /// the safety application without updating a signature; nothing was sent.
    NotSigned {
        /// The function whose signature was to be updated.
        function: &'static str,
        /// Object index of the value.
        index: u16,
        /// Sub-index of the value.
        subindex: u8,
    },
    /// The drive refused a write or the bus failed; the writes before it were made, the validity
    /// flag was not set.
    Bus {
        /// Object index of the failed write.
        index: u16,
        /// Sub-index of the failed write.
        subindex: u8,
        /// What happened.
        cause: BusError,
    },
}

impl fmt::Display for SafetyWriteError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotPreOperational { state } => write!(
                f,
                "safety configuration is written in NMT Pre-Operational only (node is {state:?}); nothing was sent"
            ),
            Self::Config(e) => write!(f, "{e}; nothing was sent"),
            Self::WritesRefused(reason) => {
                write!(f, "safety write refused: {reason}; nothing was sent")
            }
            Self::NoSuchFunction { function, instance } => {
                write!(f, "{function} has no instance {instance}; nothing was sent")
            }
            Self::NotSigned {
                function,
                index,
                subindex,
            } => write!(
                f,
                "{index:#06x}:{subindex} is not covered by the {function} signature; nothing was sent"
            ),
            Self::Bus {
                index,
                subindex,
                cause,
            } => write!(
                f,
                "safety write of {index:#06x}:{subindex} failed: {cause}; the configuration is not marked valid"
            ),
        }
    }
}

impl core::error::Error for SafetyWriteError {}

/// The SDO writes of a safety write, in order, with the signature they end with. Pure: computing
/// it sends nothing.
#[derive(Debug, Clone)]
pub struct SafetyPlan<'a> {
    config: SrdoConfig<'a>,
    mapping: MappingWrite,
    signature: u16,
    step: usize,
}

impl<'a> SafetyPlan<'a> {
    /// The plan for `config`, or why it cannot be written: a bad SRDO number, a mapping that does
    /// not pair or fit, times or COB-IDs a valid SRDO cannot run with, or a value the signature
    /// cannot hold.
    pub fn new(config: SrdoConfig<'a>, mapping: MappingWrite) -> Result<Self, SrdoError> {
        config.checked_number()?;
        check_mapping(config.mapping)?;
        if config.communication.direction != SrdoDirection::Invalid {
            config.communication.timing()?;
            config.communication.cob_ids()?;
        }
        let signature = signature(&config)?;
        Ok(Self {
            config,
            mapping,
            signature,
            step: 0,
        })
    }

    /// The signature the plan writes to 13FFh.
    pub const fn signature(&self) -> u16 {
        self.signature
    }

    fn communication_write(&self, step: usize) -> Option<SdoWrite> {
        let c = &self.config.communication;
        let index = 0x1300 + u16::from(self.config.number);
        Some(match step {
            0 => SdoWrite::u8(index, 1, c.direction as u8),
            1 => SdoWrite::u16(index, 2, c.sct_ms),
            2 => SdoWrite::u16(index, 3, c.srvt_ms),
            3 => SdoWrite::u32(index, 5, c.cob_id_normal),
            4 => SdoWrite::u32(index, 6, c.cob_id_inverted),
            _ => return None,
        })
    }

    fn mapping_write(&self, step: usize) -> Option<SdoWrite> {
        let index = 0x1380 + u16::from(self.config.number);
        let entries = self.config.mapping;
        // Validated: at most 128 entries.
        let count = entries.len() as u8;
        match step {
            0 => Some(SdoWrite::u8(index, 0, 0)),
            s if s <= entries.len() => Some(SdoWrite::u32(index, s as u8, entries[s - 1].entry())),
            s if s == entries.len() + 1 => Some(SdoWrite::u8(index, 0, count)),
            _ => None,
        }
    }

    fn mapping_steps(&self) -> usize {
        match self.mapping {
            MappingWrite::Keep => 0,
            MappingWrite::Write => self.config.mapping.len() + 2,
        }
    }
}

const COMMUNICATION_STEPS: usize = 5;

impl Iterator for SafetyPlan<'_> {
    type Item = SdoWrite;

    fn next(&mut self) -> Option<SdoWrite> {
        let step = self.step;
        let mapping_end = COMMUNICATION_STEPS + self.mapping_steps();
        let write = if step < COMMUNICATION_STEPS {
            self.communication_write(step)
        } else if step < mapping_end {
            self.mapping_write(step - COMMUNICATION_STEPS)
        } else if step == mapping_end {
            Some(SdoWrite::u16(
                SIGNATURES,
                self.config.number,
                self.signature,
            ))
        } else if step == mapping_end + 1 {
            Some(SdoWrite::u8(CONFIGURATION_VALID, 0, VALID))
        } else {
            None
        };
        self.step += usize::from(write.is_some());
        write
    }
}

/// Writes SRDO `config` to `node` over `bus` and declares it valid: refused with
/// [`SafetyWriteError::NotPreOperational`] unless `state` is Pre-Operational, and with
/// [`SafetyWriteError::Config`] if the configuration cannot be written — in both cases before
/// any frame is sent. Returns the signature written to 13FFh.
pub fn write_safety_configuration<B: SdoBus + ?Sized>(
    bus: &mut B,
    node: NodeId,
    state: NmtState,
    config: SrdoConfig<'_>,
    mapping: MappingWrite,
) -> Result<u16, SafetyWriteError> {
    let plan = checked_plan(state, config, mapping)?;
    let signature = plan.signature();
    for write in plan {
        bus.download(node, write.index, write.subindex, write.data())
            .map_err(write_failed(&write))?;
    }
    Ok(signature)
}

/// [`write_safety_configuration`] over an async SDO client (feature `async`): the same checks
/// and plan, each write awaited.
#[cfg(feature = "async")]
pub async fn write_safety_configuration_async<B: crate::canopen::link::AsyncSdoBus + ?Sized>(
    bus: &mut B,
    node: NodeId,
    state: NmtState,
    config: SrdoConfig<'_>,
    mapping: MappingWrite,
) -> Result<u16, SafetyWriteError> {
    let plan = checked_plan(state, config, mapping)?;
    let signature = plan.signature();
    for write in plan {
        bus.download(node, write.index, write.subindex, write.data())
            .await
            .map_err(write_failed(&write))?;
    }
    Ok(signature)
}

/// The writes of `config`, refused before any frame unless `state` is Pre-Operational and the
/// configuration can be written.
fn checked_plan(
    state: NmtState,
    config: SrdoConfig<'_>,
    mapping: MappingWrite,
) -> Result<SafetyPlan<'_>, SafetyWriteError> {
    if state != NmtState::PreOperational {
        return Err(SafetyWriteError::NotPreOperational { state });
    }
    SafetyPlan::new(config, mapping).map_err(SafetyWriteError::Config)
}

/// The error of `write` failing with a bus error.
fn write_failed(write: &SdoWrite) -> impl Fn(BusError) -> SafetyWriteError {
    let (index, subindex) = (write.index, write.subindex);
    move |cause| SafetyWriteError::Bus {
        index,
        subindex,
        cause,
    }
}
