//! A node's PDOs checked against its description before anything is sent: the PDO exists on
//! the drive (its communication object is described), the sub-indices to set are described,
//! every mapped parameter exists, is PDO-mappable in the PDO's direction and fits, and the
//! mapping fits the PDO (64 bits) and the drive's mapping object. Each refusal names the line.

use drivebus_model::canopen::{mapping_bits, MappedObject, PdoKind, PdoSetup};

use super::error::{NetworkFileError, NetworkFileErrorKind as Kind};
use super::{NodeEntry, PdoEntry};
use crate::ir::{pdo_bits, Device, Direction, Parameter, Pdo};

/// `node`'s PDOs checked against `device`, its description, and ready to configure (in the
/// order of [`NodeEntry::pdos`], a COB-ID given or from the predefined connection set); the
/// first that the drive cannot take is refused with its line and why.
pub fn check_pdos(node: &NodeEntry, device: &Device) -> Result<Vec<PdoSetup>, NetworkFileError> {
    let objects = Objects::of(device);
    node.pdos
        .iter()
        .map(|pdo| check(node.id, pdo, device, &objects))
        .collect()
}

fn check(
    node: u8,
    pdo: &PdoEntry,
    device: &Device,
    objects: &Objects,
) -> Result<PdoSetup, NetworkFileError> {
    let refuse = |line: u32, kind: Kind| NetworkFileError::at(Some(line), kind);
    let (communication, mapping) = indices(pdo.direction, pdo.number);
    if !objects.has(communication, 1) {
        return Err(refuse(
            pdo.line,
            Kind::PdoAbsent {
                pdo: label(pdo),
                index: communication,
            },
        ));
    }
    let settings = [
        (pdo.transmission_type.is_some(), 2, "transmission_type"),
        (pdo.inhibit_time.is_some(), 3, "inhibit_time"),
        (pdo.event_timer.is_some(), 5, "event_timer"),
    ];
    for (_, subindex, key) in settings.iter().filter(|(given, ..)| *given) {
        if !objects.has(communication, *subindex) {
            return Err(refuse(
                pdo.line,
                Kind::PdoSettingAbsent {
                    pdo: label(pdo),
                    key,
                    index: communication,
                    subindex: *subindex,
                },
            ));
        }
    }
    let kind = match pdo.direction {
        Direction::Tx => PdoKind::Transmit,
        Direction::Rx => PdoKind::Receive,
    };
    let cob_id = pdo
        .cob_id
        .or_else(|| PdoSetup::default_cob_id(kind, pdo.number, node))
        .ok_or_else(|| refuse(pdo.line, Kind::PdoNoCobId { pdo: label(pdo) }))?;
    let entries = pdo
        .mapping
        .iter()
        .map(|name| {
            mapped(device, &name.name, pdo.direction).map_err(|kind| refuse(name.line, kind))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let bits = mapping_bits(&entries);
    if bits > 64 {
        return Err(refuse(
            pdo.line,
            Kind::PdoTooManyBits {
                pdo: label(pdo),
                bits,
            },
        ));
    }
    let capacity = objects.entries(mapping);
    if entries.len() > capacity {
        return Err(refuse(
            pdo.line,
            Kind::PdoTooManyEntries {
                pdo: label(pdo),
                entries: entries.len(),
                capacity,
                index: mapping,
            },
        ));
    }
    Ok(PdoSetup {
        kind,
        number: pdo.number,
        cob_id,
        transmission_type: pdo.transmission_type,
        inhibit_time: pdo.inhibit_time,
        event_timer: pdo.event_timer,
        entries,
    })
}

/// The mapping entry of parameter `name` in a PDO going `direction`.
fn mapped(device: &Device, name: &str, direction: Direction) -> Result<MappedObject, Kind> {
    let parameter: &Parameter =
        device
            .parameter(name)
            .ok_or_else(|| Kind::PdoUnknownParameter {
                name: name.to_owned(),
            })?;
    let not_mappable = || Kind::PdoNotMappable {
        name: name.to_owned(),
    };
    let object = parameter.pdo_object().ok_or_else(not_mappable)?;
    let allowed = match (object.pdo, direction) {
        (Pdo::None, _) => return Err(not_mappable()),
        (Pdo::Both, _) | (Pdo::Tx, Direction::Tx) | (Pdo::Rx, Direction::Rx) => true,
        _ => false,
    };
    if !allowed {
        return Err(Kind::PdoWrongDirection {
            name: name.to_owned(),
            wanted: direction_label(direction),
        });
    }
    let bits = u8::try_from(pdo_bits(parameter.data_type))
        .ok()
        .filter(|&bits| (1..=64).contains(&bits))
        .ok_or_else(not_mappable)?;
    Ok(MappedObject::new(object.index, object.subindex, bits))
}

/// The communication and mapping object indices of a PDO.
fn indices(direction: Direction, number: u16) -> (u16, u16) {
    let offset = number.saturating_sub(1);
    match direction {
        Direction::Tx => (0x1800 + offset, 0x1A00 + offset),
        Direction::Rx => (0x1400 + offset, 0x1600 + offset),
    }
}

fn direction_label(direction: Direction) -> &'static str {
    match direction {
        Direction::Tx => "TPDO",
        Direction::Rx => "RPDO",
    }
}

fn label(pdo: &PdoEntry) -> String {
    format!("{} {}", direction_label(pdo.direction), pdo.number)
}

/// The object sub-indices a description defines, with the PDO objects its `[[pdo]]` tables
/// imply (`eds::pdo_objects`: what the EDS export and the simulator give the drive).
struct Objects(Vec<(u16, u8)>);

impl Objects {
    fn of(device: &Device) -> Self {
        let derived = crate::eds::pdo_objects(device);
        let addresses = device
            .parameters
            .iter()
            .chain(&derived.parameters)
            .flat_map(|p| &p.canopen)
            .map(|a| (a.index, a.subindex))
            .collect();
        Self(addresses)
    }

    fn has(&self, index: u16, subindex: u8) -> bool {
        self.0.contains(&(index, subindex))
    }

    /// How many entries mapping object `index` has (sub-indices 1 and up).
    fn entries(&self, index: u16) -> usize {
        self.0
            .iter()
            .filter(|(i, sub)| *i == index && *sub >= 1)
            .count()
    }
}
