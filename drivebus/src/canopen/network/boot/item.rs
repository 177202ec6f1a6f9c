//! One configuration item of a boot (the heartbeat, a PDO, a boot parameter): the values its
//! objects must hold, read and compared first, and the writes that set them when one differs.
//! A node that already holds every value is not written to, so a second boot changes nothing
//! and sends no download.

use std::vec::Vec;

use super::{pdo, BootWrite, NodeBoot};
use crate::canopen::pdo::PdoSetup;
use crate::error::BusError;

/// A value an object must hold, and the bits of it that count.
#[derive(Debug, Clone)]
pub(super) struct Expected {
    pub write: BootWrite,
    pub bits: u32,
}

impl Expected {
    fn all(write: BootWrite) -> Self {
        Self {
            write,
            bits: u32::MAX,
        }
    }

    /// Whether `found` (an upload of the object) is the value.
    pub fn holds(&self, found: u32) -> bool {
        let mut bytes = [0u8; 4];
        bytes[..self.write.data.len()].copy_from_slice(&self.write.data);
        (u32::from_le_bytes(bytes) ^ found) & self.bits == 0
    }
}

/// The checks and writes of one item.
#[derive(Debug, Clone, Default)]
pub(super) struct Item {
    /// Read and compared in order; empty when the values cannot be compared (more than 4
    /// bytes): then the item is written.
    pub checks: Vec<Expected>,
    /// Written in order when a check fails.
    pub writes: Vec<BootWrite>,
}

impl Item {
    /// Writing `write` where the object does not hold it yet.
    pub fn single(write: BootWrite) -> Self {
        let checks = if write.data.len() <= 4 {
            std::vec![Expected::all(write.clone())]
        } else {
            Vec::new()
        };
        Self {
            checks,
            writes: std::vec![write],
        }
    }

    /// The heartbeat producer time (1017h) of `plan`, in ms.
    pub fn heartbeat(plan: &NodeBoot) -> Self {
        let ms = plan
            .heartbeat
            .map_or(0, |p| u16::try_from(p.as_millis()).unwrap_or(u16::MAX));
        Self::single(BootWrite {
            index: 0x1017,
            subindex: 0,
            data: ms.to_le_bytes().to_vec(),
        })
    }

    /// A PDO: its whole configuration sequence where any of its objects differs.
    pub fn pdo(setup: &PdoSetup) -> Result<Self, BusError> {
        let checks = pdo::target(setup)?
            .into_iter()
            .map(|write| Expected {
                bits: pdo::compared_bits(setup, write.index, write.subindex),
                write,
            })
            .collect();
        Ok(Self {
            checks,
            writes: pdo::writes(setup)?,
        })
    }
}
