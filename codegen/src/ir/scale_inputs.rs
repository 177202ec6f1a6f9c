//! Where a run-time scale's inputs come from: a per-model constant, a parameter read over the
//! protocol in use, or (where that parameter is not readable there) a value the user gives when
//! opening the handle. Validation and the emitter both ask these.

use super::{Device, Parameter};

impl Parameter {
    /// Whether the parameter has a readable Modbus address.
    pub fn readable_over_modbus(&self) -> bool {
        self.modbus.iter().any(|a| a.access.read)
    }

    /// Whether the parameter has a readable CANopen address.
    pub fn readable_over_canopen(&self) -> bool {
        self.canopen.iter().any(|a| a.access.read)
    }

    /// Whether the parameter has a readable Kinco RS-232 address.
    pub fn readable_over_rs232(&self) -> bool {
        self.rs232.iter().any(|a| a.access.read)
    }
}

impl Device {
    /// Whether `name` is one of the device's per-model constants.
    pub fn is_constant(&self, name: &str) -> bool {
        self.constants.iter().any(|c| c.name == name)
    }
}
