//! A description's CANopen objects looked up by address, for decoding a bus frame by frame
//! (`decode`, `trace`): built once, so a frame costs a hash lookup instead of a walk through
//! every parameter (hundreds in a vendor description), and a PDO a lookup of its declared
//! mapping instead of resolving its entries by name each time.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use drivebus::canopen::pdo::MappedObject;
use drivebus::interpret::Presentation;
use drivegen::ir::{Device, Direction, Parameter};

/// The tables of object addresses.
pub type AddressMap<K, V> = HashMap<K, V, BuildHasherDefault<AddressHasher>>;

/// A hasher for the few bytes of an object address: the standard hasher, built to resist
/// chosen keys, cost a fifth of a frame's decoding; the keys here are the description's own.
#[derive(Debug, Default)]
pub struct AddressHasher(u64);

impl Hasher for AddressHasher {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 << 8) | u64::from(b);
        }
    }

    fn write_u8(&mut self, n: u8) {
        self.0 = (self.0 << 8) | u64::from(n);
    }

    fn write_u16(&mut self, n: u16) {
        self.0 = (self.0 << 16) | u64::from(n);
    }

    fn finish(&self) -> u64 {
        // A folded multiply: every bit of the packed address reaches the low bits (the bucket)
        // and the high ones (the table's tag).
        let product = u128::from(self.0) * 0x9E37_79B9_7F4A_7C15;
        (product as u64) ^ ((product >> 64) as u64)
    }
}

/// A parameter at a CANopen address, with how its values are shown (looked up once, not for
/// every frame).
#[derive(Debug)]
pub struct Known<'d> {
    /// The parameter.
    pub parameter: &'d Parameter,
    /// How its values are shown.
    pub presentation: Presentation<'d>,
}

/// The objects of one description.
#[derive(Debug)]
pub struct Objects<'d> {
    /// The first parameter at each CANopen address, as a walk in declaration order finds it.
    by_address: AddressMap<(u16, u8), Known<'d>>,
    /// Each declared PDO's mapping, by (transmit, number), where its entries resolve.
    declared: AddressMap<(bool, u16), Vec<MappedObject>>,
    /// The first name of each EMCY code in the description's error-code enumerations.
    emcy: HashMap<u16, &'d str>,
}

impl<'d> Objects<'d> {
    /// The objects of `device`.
    pub fn new(device: &'d Device) -> Self {
        let mut by_address = HashMap::default();
        for parameter in &device.parameters {
            for a in &parameter.canopen {
                by_address
                    .entry((a.index, a.subindex))
                    .or_insert_with(|| Known {
                        parameter,
                        presentation: Presentation::of(device, parameter),
                    });
            }
        }
        let mut declared = AddressMap::default();
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
            by_address,
            declared,
            emcy,
        }
    }

    /// The parameter at `index:subindex`, with its presentation.
    pub fn find(&self, index: u16, subindex: u8) -> Option<&Known<'d>> {
        self.by_address.get(&(index, subindex))
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
