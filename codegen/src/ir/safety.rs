//! Which objects are CANopen Safety configuration (EN 50325-5): the SRDO communication objects
//! 1301h..1340h and mapping objects 1381h..13C0h (SWD manual lines 1667, 3621-3631), the
//! configuration-valid flag 13FEh (line 3574) and the signatures 13FFh (line 3587). The
//! generated API reads them but gives them no setter: they are written only through
//! `drivebus::canopen::srdo::write_safety_configuration`, which signs and validates them.

use super::ObjectAddress;

/// Whether `address` is an SRDO configuration, validity or signature object.
pub fn is_safety_configuration(address: &ObjectAddress) -> bool {
    matches!(address.index, 0x1301..=0x1340 | 0x1381..=0x13C0 | 0x13FE | 0x13FF)
}
