//! CANopen emergency messages through the drive's own error table: the EMCY error code is the
//! same code as Modbus input 0x0063 (Modbus manual Table 2; user guide 4.9 sends 0x2350/0x2351 as
//! EMCY), so it decodes into [`ErrorCode`] with its class, LED code and meaning.

use drivebus::canopen::emcy::{Emcy, EmcyTable};

use crate::types::ErrorCode;

/// The Smartris error table as a `drivebus` EMCY table: `emcy.meaning(&EmcyCodes)`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct EmcyCodes;

impl EmcyTable for EmcyCodes {
    fn meaning(&self, code: u16) -> Option<&'static str> {
        ErrorCode::from_raw(code).meaning()
    }
}

impl ErrorCode {
    /// The error code an emergency message carries; codes the table does not list stay
    /// readable as unknown values.
    pub const fn from_emcy(emcy: &Emcy) -> Self {
        Self::from_raw(emcy.code)
    }
}
