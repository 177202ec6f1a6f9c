//! The Kinco RS-232 protocol marker; its parameters are addressed as CANopen objects.

use crate::canopen::ObjectAddress;
use crate::Protocol;

/// The Kinco RS-232 protocol marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rs232;

impl Protocol for Rs232 {
    type Address = ObjectAddress;
    const NAME: &'static str = "Kinco RS-232";
}
