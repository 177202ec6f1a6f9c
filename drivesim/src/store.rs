//! The parameter store: every parameter's raw value, its factory default and its stored copy.

use std::collections::HashMap;

use drivebus::interpret::{self, Breach, RawValue};
use drivegen::ir::{DataType, Device, Parameter};

use crate::raw;
use crate::refusal::Refusal;

/// Index of a parameter in [`Device::parameters`].
pub type ParamId = usize;

/// Raw values of every parameter of one device, as little-endian bytes of the parameter's type.
#[derive(Debug, Clone)]
pub struct Store {
    device: Device,
    by_name: HashMap<String, ParamId>,
    values: Vec<Vec<u8>>,
    factory: Vec<Vec<u8>>,
    stored: Vec<Vec<u8>>,
}

impl Store {
    /// A store holding the described defaults (0 where none is described); node-relative ones on
    /// the description's default node id.
    pub fn new(device: Device) -> Self {
        let node = device.canopen.as_ref().map_or(1, |c| c.default_node_id);
        let factory: Vec<Vec<u8>> = device
            .parameters
            .iter()
            .map(|p| default_bytes(p, node))
            .collect();
        let by_name = device
            .parameters
            .iter()
            .enumerate()
            .map(|(id, p)| (p.name.clone(), id))
            .collect();
        Self {
            device,
            by_name,
            values: factory.clone(),
            stored: factory.clone(),
            factory,
        }
    }

    /// The device model.
    pub fn device(&self) -> &Device {
        &self.device
    }

    /// A parameter's id by name.
    pub fn id(&self, name: &str) -> Option<ParamId> {
        self.by_name.get(name).copied()
    }

    /// A parameter's description.
    pub fn parameter(&self, id: ParamId) -> &Parameter {
        &self.device.parameters[id]
    }

    /// A parameter's raw bytes.
    pub fn bytes(&self, id: ParamId) -> &[u8] {
        &self.values[id]
    }

    /// A parameter's value as an integer (`None` for non-integer types).
    pub fn int(&self, id: ParamId) -> Option<i128> {
        raw::to_int(self.parameter(id).data_type, &self.values[id])
    }

    /// Sets an integer parameter without checks (the drive's own doing, not a request).
    pub fn set_int(&mut self, id: ParamId, value: i128) {
        self.values[id] = raw::from_int(self.parameter(id).data_type, value);
    }

    /// Sets a parameter's bytes without checks; they are padded or cut to its width.
    pub fn set_bytes(&mut self, id: ParamId, bytes: &[u8]) {
        let width = self.parameter(id).data_type.bytes() as usize;
        let mut value = bytes.to_vec();
        value.resize(width, 0);
        self.values[id] = value;
    }

    /// Checks a value a client wants to write against the parameter's type, range and allowed
    /// values.
    pub fn check(&self, id: ParamId, bytes: &[u8]) -> Result<(), Refusal> {
        let parameter = self.parameter(id);
        let width = parameter.data_type.bytes() as usize;
        let text = matches!(
            parameter.data_type,
            DataType::String(_) | DataType::Octets(_)
        );
        if bytes.len() != width && !(text && bytes.len() <= width) {
            return Err(Refusal::WrongLength);
        }
        let Some(value) = RawValue::of(parameter.data_type, bytes) else {
            return Ok(());
        };
        interpret::check(parameter, value).map_err(|breach| match breach {
            Breach::BelowRange => Refusal::TooLow,
            Breach::AboveRange => Refusal::TooHigh,
            Breach::OutsideType | Breach::Unordered | Breach::NotAllowed => Refusal::InvalidValue,
        })
    }

    /// Puts a parameter back to its factory value.
    pub fn reset_to_factory(&mut self, id: ParamId) {
        self.values[id] = self.factory[id].clone();
    }

    /// Copies the present values to the non-volatile copy.
    pub fn store(&mut self) {
        self.stored = self.values.clone();
    }

    /// Replaces the non-volatile copy by the factory defaults.
    pub fn restore_factory(&mut self) {
        self.stored = self.factory.clone();
    }

    /// Gives every node-relative default (`$NODEID+0x180`) its value on node `node`, as the drive
    /// computes it: the factory value, and the present and stored values still holding the default
    /// of another node. The value is kept even where the parameter's own limits refuse it (a vendor
    /// EDS whose limits allow some node IDs only): the drive holds it, a client sees it.
    pub fn at_node(&mut self, node: u8) {
        for (id, p) in self.device.parameters.iter().enumerate() {
            let Some(default) = p.default_on(node).filter(|_| p.default_plus_node_id) else {
                continue;
            };
            let bytes = raw::from_number(p.data_type, default);
            let old = std::mem::replace(&mut self.factory[id], bytes.clone());
            for copy in [&mut self.values[id], &mut self.stored[id]] {
                if *copy == old {
                    *copy = bytes.clone();
                }
            }
        }
    }

    /// Reloads the present values from the non-volatile copy, as a reboot does.
    pub fn reload(&mut self) {
        self.values = self.stored.clone();
    }
}

/// The factory value; a node-relative default is taken on node `node` (the description's default
/// node id, until [`Store::at_node`] says which node the drive is).
fn default_bytes(parameter: &Parameter, node: u8) -> Vec<u8> {
    if let Some(d) = parameter
        .default_on(node)
        .filter(|_| parameter.default_plus_node_id)
    {
        return raw::from_number(parameter.data_type, d);
    }
    parameter.default.map_or_else(
        || raw::zero(parameter.data_type),
        |d| raw::from_number(parameter.data_type, d),
    )
}
