//! Wire efficiency of the drive status (#24-#29), counted on the RTU wire: the documented 6-word
//! block read (`status()`, one request) against one request per register (what `read_many`
//! plans under `max_read_registers = 1`). A measurement with exact expected counts, not a timed
//! test; the numbers are in the README.

#[path = "support/scripted_line.rs"]
mod scripted_line;

use drivebus::modbus::{ModbusLink, UnitId};
use lenze_smd::{params, LenzeSmd};
use scripted_line::{client, with_crc, ScriptedLine};

const SA: u8 = 0x0A;

/// Requests sent, bytes sent and bytes received.
fn traffic(line: &ScriptedLine, answers: &[Vec<u8>]) -> (usize, usize, usize) {
    let sent = line.sent.iter().map(Vec::len).sum();
    (line.sent.len(), sent, answers.iter().map(Vec::len).sum())
}

#[test]
fn the_status_block_takes_one_request_instead_of_six() {
    let block = vec![with_crc(&[
        SA, 0x03, 0x0C, 0x02, 0x01, 0x01, 0xF4, 0x64, 0x06, 0x01, 0x0B, 0x06, 0x00, 0x18, 0x01,
    ])];
    let mut d = LenzeSmd::modbus(client(ScriptedLine::answering(block.clone())), UnitId(SA));
    d.status().unwrap();
    let line = d.into_link().into_bus().into_stream();
    assert_eq!(traffic(&line, &block), (1, 8, 17));

    let singles: Vec<Vec<u8>> = [0x0201u16, 0x01F4, 0x6406, 0x010B, 0x0600, 0x1801]
        .iter()
        .map(|w| with_crc(&[SA, 0x03, 0x02, (w >> 8) as u8, *w as u8]))
        .collect();
    let mut d: LenzeSmd<ModbusLink<_>> =
        LenzeSmd::modbus(client(ScriptedLine::answering(singles.clone())), UnitId(SA));
    d.read_many((
        params::CommandSpeed,
        params::ActualSpeed,
        params::LoadAndStatus,
        params::DirectionAndControlMode,
        params::SpeedSourceAndReference,
        params::FaultAndCommandedDirection,
    ))
    .unwrap();
    let line = d.into_link().into_bus().into_stream();
    assert_eq!(traffic(&line, &singles), (6, 48, 42));
}
