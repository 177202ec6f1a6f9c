//! What the generated API reads but never writes with a plain setter:
//!
//! * CANopen Safety configuration (EN 50325-5): the SRDO communication objects 1301h..1340h and
//!   mapping objects 1381h..13C0h (SWD manual lines 1667, 3621-3631), the configuration-valid
//!   flag 13FEh (line 3574) and the signatures 13FFh (line 3587). They are written only through
//!   `drivebus::canopen::srdo::write_safety_configuration`, which signs and validates them.
//! * Safety-function parameters a description marks `safety = true` (e.g. the SWD's 6607h and
//!   its CiA 402-4 objects, section 11): the drive checks them against their function's
//!   signature, so a plain write would invalidate the safety application.

use super::{ObjectAddress, Parameter};

/// Whether `address` is an SRDO configuration, validity or signature object.
pub fn is_safety_configuration(address: &ObjectAddress) -> bool {
    matches!(address.index, 0x1301..=0x1340 | 0x1381..=0x13C0 | 0x13FE | 0x13FF)
}

impl Parameter {
    /// Whether the generated API must give this parameter no setter: an SRDO configuration
    /// object or a parameter marked `safety = true`.
    pub fn is_safety(&self) -> bool {
        self.safety || self.canopen.iter().any(is_safety_configuration)
    }

    /// Whether this is a safety-function parameter written through the deliberate
    /// `drivebus::canopen::srdo::write_safety_function`: marked `safety = true`, not an SRDO
    /// configuration object, with a writable CANopen address.
    pub fn is_safety_function_parameter(&self) -> bool {
        self.safety
            && !self.canopen.iter().any(is_safety_configuration)
            && self.canopen.iter().any(|a| a.access.write)
    }

    /// How a safety parameter is written, for its documentation; `None` for other parameters.
    pub fn safety_write_note(&self) -> Option<&'static str> {
        if self.canopen.iter().any(is_safety_configuration) {
            Some("written only through `drivebus::canopen::srdo::write_safety_configuration` (no setter)")
        } else if self.safety {
            Some("safety-function parameter: no setter; written only through `drivebus::canopen::srdo::write_safety_function` (Pre-Operational, the function's signature recomputed after), which takes a `SafetyValue::of` this parameter")
        } else {
            None
        }
    }
}
