//! The traits a generated crate implements to hand its parameters to the control driver.
//!
//! drivegen emits the implementations only when a description has the objects: the handle type
//! implements [`Cia402Objects`] when it has a controlword (0x6040) and statusword (0x6041),
//! [`Cia402Modes`] when it also has the modes of operation (0x6060) and their display (0x6061), and
//! [`VendorMachine`] when it describes a vendor state machine.

use super::machine::Machine;
use super::quirks::Quirks;
use crate::parameter::{OpenEnum, Parameter};

/// The CiA 402 state machine objects of a drive.
pub trait Cia402Objects {
    /// The controlword (0x6040).
    type Controlword: Parameter<Raw = u16>;
    /// The statusword (0x6041).
    type Statusword: Parameter<Raw = u16>;
    /// The 16-bit word holding the safe torque off bit; the statusword if the description has none.
    type SafeTorqueOffWord: Parameter<Raw = u16>;
    /// The bit of [`Self::SafeTorqueOffWord`] that is set while safe torque off is active.
    const SAFE_TORQUE_OFF_BIT: Option<u8>;
    /// The drive's deviations from CiA 402.
    const QUIRKS: Quirks;
}

/// The modes of operation objects of a CiA 402 drive.
pub trait Cia402Modes: Cia402Objects {
    /// The description's open enum of modes.
    type Mode: OpenEnum<Raw = i8>;
    /// Modes of operation (0x6060).
    type ModesOfOperation: Parameter<Raw = i8, Value = Self::Mode>;
    /// Modes of operation display (0x6061).
    type ModesOfOperationDisplay: Parameter<Raw = i8, Value = Self::Mode>;
}

/// The quick stop option code of a CiA 402 drive: drivegen implements it when the description
/// has 605Ah (a 16-bit signed object, CiA 402-2), so the handle can quick stop to the end the
/// drive's own code gives.
pub trait QuickStopOptionObjects: Cia402Objects {
    /// Quick stop option code (605Ah).
    type QuickStopOptionCode: Parameter<Raw = i16>;
}

/// A vendor state machine described as data (e.g. the Lafert Smartris Modbus run sequence).
pub trait VendorMachine {
    /// The register the states are recognised from.
    type Status: Parameter<Raw = u16>;
    /// The register transitions are commanded through.
    type Command: Parameter<Raw = u16>;
    /// States and transitions.
    const MACHINE: Machine<'static>;
}

/// The profile position objects of a CiA 402 drive whose modes list profile position (1):
/// drivegen implements it when the description has the target position (607Ah) and a position
/// actual value (6064h, else the internal value 6063h).
pub trait ProfilePositionObjects: Cia402Modes {
    /// Target position (607Ah).
    type TargetPosition: Parameter<Raw = i32>;
    /// Position actual value (6064h or 6063h).
    type PositionActual: Parameter<Raw = i32>;
}

/// The homing objects of a CiA 402 drive whose modes list homing (6): drivegen implements it
/// when the description has the homing method (6098h) as an enum of the methods the drive lists.
pub trait HomingObjects: Cia402Modes {
    /// The description's open enum of homing methods.
    type Method: OpenEnum<Raw = i8>;
    /// Homing method (6098h).
    type HomingMethod: Parameter<Raw = i8, Value = Self::Method>;
}

/// The profile velocity objects of a CiA 402 drive whose modes list profile velocity (3):
/// drivegen implements it when the description has the target velocity (60FFh) and the velocity
/// actual value (606Ch).
pub trait ProfileVelocityObjects: Cia402Modes {
    /// Target velocity (60FFh).
    type TargetVelocity: Parameter<Raw = i32>;
    /// Velocity actual value (606Ch).
    type VelocityActual: Parameter<Raw = i32>;
}

/// The profile torque objects of a CiA 402 drive whose modes list profile torque (4): drivegen
/// implements it when the description has the target torque (6071h).
pub trait ProfileTorqueObjects: Cia402Modes {
    /// Target torque (6071h).
    type TargetTorque: Parameter<Raw = i16>;
}
