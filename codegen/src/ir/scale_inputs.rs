//! Which protocols a run-time scale can be computed on: its inputs must be readable there.
//! Validation warns where they are not; the emitter leaves such a parameter out of that
//! protocol's API rather than return unscaled values.

use super::{Device, Parameter, Scale};

impl Parameter {
    /// Whether the parameter has a readable Modbus address.
    pub fn readable_over_modbus(&self) -> bool {
        self.modbus.iter().any(|a| a.access.read)
    }

    /// Whether the parameter has a readable CANopen address.
    pub fn readable_over_canopen(&self) -> bool {
        self.canopen.iter().any(|a| a.access.read)
    }
}

impl Device {
    /// Whether every run-time scale input of `p` is readable by `readable` (true without one).
    pub fn scale_inputs_readable(&self, p: &Parameter, readable: fn(&Parameter) -> bool) -> bool {
        match &p.scale {
            Some(Scale::Runtime { inputs, .. }) => inputs
                .iter()
                .all(|i| self.parameter(i).is_some_and(readable)),
            _ => true,
        }
    }
}
