//! The CiA 301 sequence for changing a PDO mapping (CiA 301 7.5.2.36): the PDO made invalid
//! (COB-ID bit 31), the mapping disabled (sub 0 = 0), the entries written, the count written
//! again, the PDO made valid. A drive refuses a mapping entry written while its mapping is
//! enabled, so a push that changes one writes the whole sequence.

use drivebus::interpret;
use drivegen::ir::Parameter;

use super::loaded::Desired;
use super::plan::Change;

/// The receive and transmit PDO mapping objects.
const MAPPINGS: [std::ops::RangeInclusive<u16>; 2] = [0x1600..=0x17FF, 0x1A00..=0x1BFF];
/// A mapping object's communication object lies this far below it (1600h → 1400h).
const COMMUNICATION_OFFSET: u16 = 0x200;
/// COB-ID bit 31: the PDO does not exist (is invalid).
const INVALID: i128 = 0x8000_0000;

/// The object address of `parameter` (CANopen, else Kinco RS-232, which has the same objects).
fn object(parameter: &Parameter) -> Option<(u16, u8)> {
    let address = parameter.canopen.first().or(parameter.rs232.first())?;
    Some((address.index, address.subindex))
}

fn mapping_of(parameter: &Parameter) -> Option<u16> {
    let (index, _) = object(parameter)?;
    MAPPINGS.iter().any(|r| r.contains(&index)).then_some(index)
}

/// `changes` with each changed PDO mapping written in the CiA 301 sequence, in the place of its
/// first change. `file` gives the count and COB-ID to end with.
pub fn sequence<'d>(changes: Vec<Change<'d>>, file: &[Desired<'d>]) -> Vec<Change<'d>> {
    let mut out: Vec<Change<'d>> = Vec::new();
    let mut pending = changes;
    while !pending.is_empty() {
        let change = pending.remove(0);
        let Some(mapping) = mapping_of(change.parameter) else {
            out.push(change);
            continue;
        };
        let mut group = vec![change];
        let (same, rest): (Vec<_>, Vec<_>) = pending
            .into_iter()
            .partition(|c| mapping_of(c.parameter) == Some(mapping));
        group.extend(same);
        pending = rest;
        let cob = (mapping - COMMUNICATION_OFFSET, 1);
        pending.retain(|c| object(c.parameter) != Some(cob));
        out.extend(mapping_sequence(mapping, group, file));
    }
    out
}

/// One mapping's sequence around its changed entries.
fn mapping_sequence<'d>(
    mapping: u16,
    mut entries: Vec<Change<'d>>,
    file: &[Desired<'d>],
) -> Vec<Change<'d>> {
    let in_file = |address: (u16, u8)| file.iter().find(|d| object(d.parameter) == Some(address));
    let count = in_file((mapping, 0));
    let cob = in_file((mapping - COMMUNICATION_OFFSET, 1));
    entries.retain(|c| object(c.parameter).is_some_and(|(_, sub)| sub != 0));
    entries.sort_by_key(|c| object(c.parameter));
    let step = |d: &Desired<'d>, bytes: Vec<u8>| Change {
        parameter: d.parameter,
        current: Vec::new(),
        wanted: bytes,
        line: d.line,
        invalid: None,
    };
    let mut out = Vec::new();
    if let Some(cob) = cob {
        let raw = interpret::raw::to_int(cob.parameter.data_type, &cob.bytes).unwrap_or_default();
        out.push(step(
            cob,
            interpret::raw::from_int(cob.parameter.data_type, raw | INVALID),
        ));
    }
    if let Some(count) = count {
        out.push(step(count, interpret::raw::zero(count.parameter.data_type)));
    }
    out.extend(entries);
    out.extend(count.map(|c| step(c, c.bytes.clone())));
    out.extend(cob.map(|c| step(c, c.bytes.clone())));
    out
}
