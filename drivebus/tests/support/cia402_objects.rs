//! Hand-written parameter markers for the CiA 402 objects of tests/peers/cia402_peer.eds, and the
//! `Cia402Objects` / `Cia402Modes` implementations the control driver needs (what drivegen emits
//! for a description).
#![allow(dead_code)] // Each test file uses part of this module.

use drivebus::canopen::{CanOpen, ObjectAddress};
use drivebus::codec::{Enumerated, Plain};
use drivebus::control::{Cia402Modes, Cia402Objects, Quirks};
use drivebus::parameter::{FromWire, OpenEnum};
use drivebus::{Parameter, Placement, Readable, Writable};

/// A mode of operation as the test's own open enum.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Mode(pub i8);

impl OpenEnum for Mode {
    type Raw = i8;
    fn from_raw(raw: i8, _: FromWire) -> Self {
        Mode(raw)
    }
    fn raw(self) -> i8 {
        self.0
    }
    fn name(self) -> Option<&'static str> {
        None
    }
}

/// A parameter marker at object `$index`:0 of raw type `$raw`, engineering type `$value`.
macro_rules! object {
    ($marker:ident, $name:literal, $index:literal, $raw:ty, $value:ty, $codec:ty) => {
        pub struct $marker;
        impl Parameter for $marker {
            const NAME: &'static str = $name;
            type Raw = $raw;
            type Value = $value;
            type Codec = $codec;
        }
        impl Readable<CanOpen> for $marker {
            const READ_AT: Placement<ObjectAddress> = Placement::Everywhere(ObjectAddress {
                index: $index,
                subindex: 0,
                bytes: core::mem::size_of::<$raw>() as u16,
            });
        }
        impl Writable<CanOpen> for $marker {
            const WRITE_AT: Placement<ObjectAddress> = Self::READ_AT;
        }
    };
}

object!(Controlword, "controlword", 0x6040, u16, u16, Plain);
object!(Statusword, "statusword", 0x6041, u16, u16, Plain);
object!(StoStatus, "sto_status", 0x2003, u16, u16, Plain);
object!(
    ModesOfOperation,
    "modes_of_operation",
    0x6060,
    i8,
    Mode,
    Enumerated
);
object!(
    ModesDisplay,
    "modes_of_operation_display",
    0x6061,
    i8,
    Mode,
    Enumerated
);

/// The peer's objects, with a fault reset hold of `HOLD_MS` and, if `STO`, the STO status word.
pub struct Objects<const HOLD_MS: u32, const STO: bool>;

impl<const HOLD_MS: u32, const STO: bool> Cia402Objects for Objects<HOLD_MS, STO> {
    type Controlword = Controlword;
    type Statusword = Statusword;
    type SafeTorqueOffWord = StoStatus;
    const SAFE_TORQUE_OFF_BIT: Option<u8> = if STO { Some(0) } else { None };
    const QUIRKS: Quirks = Quirks {
        fault_reset_hold_ms: HOLD_MS,
        ..Quirks::STANDARD
    };
}

impl<const HOLD_MS: u32, const STO: bool> Cia402Modes for Objects<HOLD_MS, STO> {
    type Mode = Mode;
    type ModesOfOperation = ModesOfOperation;
    type ModesOfOperationDisplay = ModesDisplay;
}

/// A drive without quirks or STO word.
pub type Standard = Objects<0, false>;

/// A drive that only takes a mode change with halt clear.
pub struct HaltQuirk;

impl Cia402Objects for HaltQuirk {
    type Controlword = Controlword;
    type Statusword = Statusword;
    type SafeTorqueOffWord = Statusword;
    const SAFE_TORQUE_OFF_BIT: Option<u8> = None;
    const QUIRKS: Quirks =
        Quirks::STANDARD.with(drivebus::control::Quirk::ModeChangeNeedsHaltClear);
}

impl Cia402Modes for HaltQuirk {
    type Mode = Mode;
    type ModesOfOperation = ModesOfOperation;
    type ModesOfOperationDisplay = ModesDisplay;
}
