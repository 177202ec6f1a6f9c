//! A description's CANopen objects looked up by address, for decoding a bus frame by frame
//! (`decode`, `trace`): built once, so a frame costs a hash lookup instead of a walk through
//! every parameter (hundreds in a vendor description), and a PDO a lookup of its declared
//! mapping instead of resolving its entries by name each time.

use std::collections::HashMap;

use drivebus::canopen::pdo::MappedObject;
use drivegen::ir::{Device, Direction, Parameter};

use crate::frames::Sample;

/// The objects of one description.
#[derive(Debug)]
pub struct Objects<'d> {
    device: &'d Device,
    /// The first parameter at each CANopen address, as a walk in declaration order finds it.
    by_address: HashMap<(u16, u8), &'d Parameter>,
    /// Each declared PDO's mapping, by (transmit, number), where its entries resolve.
    declared: HashMap<(bool, u16), Vec<MappedObject>>,
    /// The first name of each EMCY code in the description's error-code enumerations.
    emcy: HashMap<u16, &'d str>,
}

impl<'d> Objects<'d> {
    /// The objects of `device`.
    pub fn new(device: &'d Device) -> Self {
        let mut by_address = HashMap::new();
        for parameter in &device.parameters {
            for a in &parameter.canopen {
                by_address.entry((a.index, a.subindex)).or_insert(parameter);
            }
        }
        let mut declared = HashMap::new();
        for (pdo, defaults) in device.pdos() {
            let transmit = pdo.direction == Direction::Tx;
            if let Some(entries) = pdo.mapped_objects(device) {
                declared
                    .entry((transmit, defaults.number))
                    .or_insert(entries);
            }
        }
        let mut emcy = HashMap::new();
        let errors = device.enums.iter().filter(|e| e.name.contains("error"));
        for value in errors.flat_map(|e| e.values.iter()) {
            if let Ok(code) = u16::try_from(value.value) {
                emcy.entry(code).or_insert(value.name.as_str());
            }
        }
        Self {
            device,
            by_address,
            declared,
            emcy,
        }
    }

    /// The parameter at `index:subindex`.
    pub fn find(&self, index: u16, subindex: u8) -> Option<&'d Parameter> {
        self.by_address.get(&(index, subindex)).copied()
    }

    /// The parameter at `index:subindex` by name, or the address.
    pub fn name(&self, index: u16, subindex: u8) -> String {
        self.find(index, subindex)
            .map_or(format!("{index:04X}:{subindex:02X}"), |p| p.name.clone())
    }

    /// A sample of the parameter at `index:subindex` from its raw bytes.
    pub fn sample(&self, index: u16, subindex: u8, bytes: &[u8]) -> Sample {
        match self.find(index, subindex) {
            Some(p) => Sample::of(p, drivebus::interpret::show(self.device, p, bytes)),
            None => Sample::unknown(index, subindex, bytes),
        }
    }

    /// The mapping the description declares for a PDO (`[[pdo]]`), if any.
    pub fn declared_mapping(&self, transmit: bool, number: u8) -> Option<&[MappedObject]> {
        self.declared
            .get(&(transmit, u16::from(number)))
            .map(Vec::as_slice)
    }

    /// The name of an EMCY code, if the description's error-code enumerations have it.
    pub fn emcy_name(&self, code: u16) -> Option<&'d str> {
        self.emcy.get(&code).copied()
    }
}
