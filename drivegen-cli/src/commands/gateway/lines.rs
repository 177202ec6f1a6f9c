//! Which drives share a connection: the `[[drive]]`s naming the same serial line (Modbus RTU
//! units) or the same CAN bus (CANopen nodes) are served through one, by one poller. A Modbus
//! TCP drive keeps a connection of its own (a TCP gateway takes several), and so does a Kinco
//! RS-232 drive (its line is point to point: two drives naming one are refused).

use super::exposed::{Drive, Refusal};
use crate::connect::{drive_id, BusArgs};

/// A connection the gateway opens: its drives, by their index in the gateway's drives, in the
/// file's order.
pub type Line = Vec<usize>;

/// The bus a drive names, when drives can share it.
#[derive(PartialEq)]
enum Shared<'a> {
    Serial(&'a str),
    Can(&'a str),
    Rs232(&'a str),
}

/// The drives grouped by the connection they go through, each group in the order of its first
/// drive. Drives sharing a line must have different ids on it and the same line settings.
pub fn lines(drives: &[Drive]) -> Result<Vec<Line>, Refusal> {
    let mut lines: Vec<Line> = Vec::new();
    for (index, drive) in drives.iter().enumerate() {
        let sharing = shared(&drive.bus).and_then(|bus| {
            lines
                .iter_mut()
                .find(|line| shared(&drives[line[0]].bus).as_ref() == Some(&bus))
        });
        match sharing {
            Some(line) => {
                for &other in line.iter() {
                    may_share(&drives[other], drive)?;
                }
                line.push(index);
            }
            None => lines.push(vec![index]),
        }
    }
    Ok(lines)
}

fn shared(bus: &BusArgs) -> Option<Shared<'_>> {
    if let Some(path) = &bus.serial {
        return Some(Shared::Serial(path));
    }
    if let Some(backend) = &bus.can {
        return Some(Shared::Can(backend));
    }
    bus.kinco_rs232.as_deref().map(Shared::Rs232)
}

/// Whether `drive` may go through the connection `first` opens.
fn may_share(first: &Drive, drive: &Drive) -> Result<(), Refusal> {
    let refuse = |why: String| Err((drive.line, format!("drive `{}`: {why}", drive.name)));
    if drive.bus.kinco_rs232.is_some() {
        return refuse(format!(
            "bus: the Kinco RS-232 line is drive `{}`'s: one drive a line",
            first.name
        ));
    }
    let (id, first_id) = (
        drive_id(&drive.bus, &drive.device),
        drive_id(&first.bus, &first.device),
    );
    if let (Ok(id), Ok(first_id)) = (id, first_id) {
        if id == first_id {
            let kind = if drive.bus.can.is_some() {
                "node_id"
            } else {
                "unit"
            };
            return refuse(format!(
                "bus: {kind} {id} on this line is drive `{}`'s",
                first.name
            ));
        }
    }
    if settings(&drive.bus) != settings(&first.bus) {
        return refuse(format!(
            "bus: shares its line with drive `{}`, so its baud, parity, stop_bits, bitrate and timeout_ms must be the same",
            first.name
        ));
    }
    Ok(())
}

/// The settings of a line, which the drives on it share.
fn settings(bus: &BusArgs) -> (Option<u32>, &str, u8, Option<u32>, u64) {
    (
        bus.baud,
        &bus.parity,
        bus.stop_bits,
        bus.bitrate,
        bus.timeout_ms,
    )
}
