//! The PDO communication and mapping objects (CiA 301 §7.5.2.35–7.5.2.38) of the PDOs a
//! description declares, as records and parameters: an exported EDS then tells a CANopen master
//! the drive's default PDO layout.
//!
//! A description that defines a PDO's communication or mapping object itself keeps its own
//! definition; that object is not derived again.

use drivebus_model::canopen::MappedObject;

use crate::ir::{self, pdo_bits, DataType, Device, Number, PdoDirection, PdoMapping};

const READ_WRITE: ir::Access = ir::Access::READ_WRITE;

/// Objects derived from declared PDOs.
#[derive(Debug, Clone, Default)]
pub struct PdoObjects {
    /// One communication and one mapping record per PDO.
    pub records: Vec<ir::Record>,
    /// Their sub-indices.
    pub parameters: Vec<ir::Parameter>,
}

/// The communication and mapping objects of `device`'s declared PDOs, where the description does
/// not define them itself. A PDO that validation would refuse (an unchecked device: a number
/// outside 1..=512, an entry that does not resolve or does not fit a PDO) is skipped.
pub fn pdo_objects(device: &Device) -> PdoObjects {
    let taken = |index: u16| {
        let mut addresses = device.parameters.iter().flat_map(|p| &p.canopen);
        addresses.any(|a| a.index == index) || device.records.iter().any(|r| r.index == index)
    };
    let mut out = PdoObjects::default();
    for pdo in &device.pdos {
        let (Some((communication, mapping)), Some(mapped)) =
            (indices(pdo), mapping_values(device, pdo))
        else {
            continue;
        };
        if !taken(communication) {
            communication_object(pdo, communication, &mut out);
        }
        if !taken(mapping) {
            mapping_object(pdo, mapping, &mapped, &mut out);
        }
    }
    out
}

/// The communication and mapping object indices of a PDO numbered 1..=512.
fn indices(pdo: &PdoMapping) -> Option<(u16, u16)> {
    let offset = pdo.number.checked_sub(1).filter(|&o| o < 512)?;
    Some(match pdo.direction {
        PdoDirection::Rx => (0x1400 + offset, 0x1600 + offset),
        PdoDirection::Tx => (0x1800 + offset, 0x1A00 + offset),
    })
}

/// Each entry as a mapping value: index, sub-index and length in bits (CiA 301 §7.5.2.36).
fn mapping_values(device: &Device, pdo: &PdoMapping) -> Option<Vec<u32>> {
    pdo.entries
        .iter()
        .map(|name| {
            let parameter = device.parameter(name)?;
            let address = parameter.pdo_object()?;
            let bits = u8::try_from(pdo_bits(parameter.data_type))
                .ok()
                .filter(|&b| b <= 64)?;
            Some(MappedObject::new(address.index, address.subindex, bits).entry())
        })
        .collect()
}

fn label(pdo: &PdoMapping) -> String {
    let kind = match pdo.direction {
        PdoDirection::Rx => "RPDO",
        PdoDirection::Tx => "TPDO",
    };
    format!("{kind}{}", pdo.number)
}

fn communication_object(pdo: &PdoMapping, index: u16, out: &mut PdoObjects) {
    let record = record(pdo, index, "communication", "communication parameter", out);
    let highest = [
        (5, pdo.event_timer.is_some()),
        (3, pdo.inhibit_time.is_some()),
        (2, pdo.transmission_type.is_some()),
    ]
    .into_iter()
    .find_map(|(sub, given)| given.then_some(sub))
    .unwrap_or(1);
    let member = Member {
        pdo,
        record: &record,
        index,
    };
    let u8_type = DataType::Unsigned(1);
    let highest = member.sub(0, "highest_sub_index", u8_type, ir::Access::READ, highest);
    let default_cob_id = pdo.default_cob_id();
    let cob_id = i64::from(default_cob_id.value);
    let mut cob_id = member.sub(1, "cob_id", DataType::Unsigned(4), READ_WRITE, cob_id);
    cob_id.default_plus_node_id = default_cob_id.plus_node_id;
    out.parameters.extend([highest, cob_id]);
    if let Some(kind) = pdo.transmission_type {
        let kind = member.sub(2, "transmission_type", u8_type, READ_WRITE, i64::from(kind));
        out.parameters.push(kind);
    }
    let u16_type = DataType::Unsigned(2);
    for (sub, name, value) in [
        (3, "inhibit_time", pdo.inhibit_time),
        (5, "event_timer", pdo.event_timer),
    ] {
        if let Some(value) = value {
            out.parameters
                .push(member.sub(sub, name, u16_type, READ_WRITE, i64::from(value)));
        }
    }
}

fn mapping_object(pdo: &PdoMapping, index: u16, mapped: &[u32], out: &mut PdoObjects) {
    let record = record(pdo, index, "mapping", "mapping parameter", out);
    let member = Member {
        pdo,
        record: &record,
        index,
    };
    let count = mapped.len() as i64;
    let count = member.sub(0, "count", DataType::Unsigned(1), READ_WRITE, count);
    out.parameters.push(count);
    for (sub, &value) in (1u8..).zip(mapped) {
        let name = format!("entry_{sub}");
        let value = i64::from(value);
        let entry = member.sub(sub, &name, DataType::Unsigned(4), READ_WRITE, value);
        out.parameters.push(entry);
    }
}

/// Adds the record `{pdo}_{suffix}` at `index`; returns its name.
fn record(pdo: &PdoMapping, index: u16, suffix: &str, what: &str, out: &mut PdoObjects) -> String {
    let name = format!("{}_{suffix}", pdo.name);
    out.records.push(ir::Record {
        name: name.clone(),
        kind: ir::RecordKind::Record,
        index,
        doc: Some(format!("{} {what} ({})", label(pdo), pdo.name)),
        source: pdo.source.clone(),
        span: pdo.span.clone(),
    });
    name
}

/// Builds the sub-indices of one record.
struct Member<'a> {
    pdo: &'a PdoMapping,
    record: &'a str,
    index: u16,
}

impl Member<'_> {
    /// Sub-index `subindex` of the record, `{record}_{name}`, with its default.
    fn sub(
        &self,
        subindex: u8,
        name: &str,
        data_type: DataType,
        access: ir::Access,
        default: i64,
    ) -> ir::Parameter {
        ir::Parameter {
            name: format!("{}_{name}", self.record),
            doc: Some(format!("{}: {}.", label(self.pdo), name.replace('_', " "))),
            data_type,
            unit: None,
            scale: None,
            default: Some(Number::Int(default)),
            default_plus_node_id: false,
            range: None,
            allowed: Vec::new(),
            enumeration: None,
            flags: None,
            record: Some(self.record.to_owned()),
            modbus: Vec::new(),
            canopen: vec![ir::ObjectAddress {
                index: self.index,
                subindex,
                access,
                constant: false,
                pdo: ir::Pdo::None,
                variant: None,
                span: self.pdo.span.clone(),
            }],
            rs232: Vec::new(),
            effect: ir::Effect::Immediate,
            command: None,
            variants: Vec::new(),
            source: self.pdo.source.clone(),
            erratum: None,
            safety: false,
            bounds: None,
            stops: None,
            spans: ir::ParameterSpans {
                name: self.pdo.span.clone(),
                data_type: self.pdo.span.clone(),
                ..Default::default()
            },
        }
    }
}
