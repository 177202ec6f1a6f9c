//! CANopen emergency messages through the SWD's error code table (manual section 9.8, lines
//! 1506-1581): [`EmcyErrorCode`] carries each code's meaning and, where the manual names the
//! level, its class.

use drivebus::canopen::emcy::{Emcy, EmcyTable};

use crate::types::EmcyErrorCode;

/// The SWD error table as a `drivebus` EMCY table: `emcy.meaning(&EmcyCodes)`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct EmcyCodes;

impl EmcyTable for EmcyCodes {
    fn meaning(&self, code: u16) -> Option<&'static str> {
        EmcyErrorCode::from_raw(code).meaning()
    }
}

impl EmcyErrorCode {
    /// The error code an emergency message carries; codes the table does not list stay
    /// readable as unknown values.
    pub const fn from_emcy(emcy: &Emcy) -> Self {
        Self::from_raw(emcy.code)
    }
}
