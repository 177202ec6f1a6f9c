//! Modbus vocabulary: tables, word orders, addresses, register spans, what a device accepts
//! ([`ModbusLimits`]) and exception codes. The codecs and clients are in `drivebus::modbus`.

pub mod address;
pub mod exception;

pub use address::{
    le_to_registers, registers_to_le, ModbusAddress, ModbusLimits, RegisterSpan, Table, UnitId,
    WordOrder, MAX_VALUE_WORDS,
};
pub use exception::ExceptionCode;

use crate::Protocol;

/// The Modbus protocol marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Modbus;

impl Protocol for Modbus {
    type Address = ModbusAddress;
    const NAME: &'static str = "Modbus";
}
