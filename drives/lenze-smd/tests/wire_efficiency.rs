//! Wire efficiency of the drive status (#24-#29), counted on the RTU wire: `read_many` of the six
//! registers plans the documented 6-word block read (`[modbus] read_blocks`, one request), as
//! `status()` does, against one request per register (six accessor reads, what the planner did
//! before it knew the blocks). A measurement with exact expected counts, not a timed test; the
//! numbers are in the README and docs/benchmarks.md.

#[path = "support/scripted_line.rs"]
mod scripted_line;

use drivebus::modbus::client::Client;
use drivebus::modbus::rtu::RtuFraming;
use drivebus::modbus::{ModbusLink, UnitId};
use lenze_smd::{params, LenzeSmd};
use peer_support::modbus_crc::with_crc;
use scripted_line::{client, ScriptedLine};

const SA: u8 = 0x0A;

/// The six words of the status block, #24 first.
const STATUS: [u16; 6] = [0x0201, 0x01F4, 0x6406, 0x010B, 0x0600, 0x1801];

/// Requests sent, bytes sent and bytes received.
fn traffic(line: &ScriptedLine, answers: &[Vec<u8>]) -> (usize, usize, usize) {
    let sent = line.sent.iter().map(Vec::len).sum();
    (line.sent.len(), sent, answers.iter().map(Vec::len).sum())
}

/// The drive's answer to a read of `words`.
fn answer(words: &[u16]) -> Vec<u8> {
    let mut pdu = vec![SA, 0x03, 2 * words.len() as u8];
    pdu.extend(words.iter().flat_map(|w| w.to_be_bytes()));
    with_crc(&pdu)
}

type Drive = LenzeSmd<ModbusLink<Client<ScriptedLine, RtuFraming>>>;

fn drive(answers: &[Vec<u8>]) -> Drive {
    LenzeSmd::modbus(
        client(ScriptedLine::answering(answers.to_vec())),
        UnitId(SA),
    )
}

#[test]
fn read_many_of_the_status_registers_is_one_block_read() {
    let block = [answer(&STATUS)];
    let mut d = drive(&block);
    let (command, actual, load, direction, source, fault) = d
        .read_many((
            params::CommandSpeed,
            params::ActualSpeed,
            params::LoadAndStatus,
            params::DirectionAndControlMode,
            params::SpeedSourceAndReference,
            params::FaultAndCommandedDirection,
        ))
        .unwrap();
    let line = d.into_link().into_bus().into_stream();
    assert_eq!(line.sent, [with_crc(&[SA, 0x03, 0x00, 0x18, 0x00, 0x06])]);
    assert_eq!(traffic(&line, &block), (1, 8, 17));
    // The words land in their own parameters, #24 first.
    assert!((actual.0 - 50.0).abs() < 1e-9, "{actual:?}");
    let status = lenze_smd::StatusBlock::decode(STATUS).unwrap();
    assert_eq!(
        (command, actual, load, direction, source, fault),
        (
            status.command_speed,
            status.actual_speed,
            status.load_and_status,
            status.direction_and_control_mode,
            status.speed_source_and_reference,
            status.fault_and_commanded_direction
        )
    );
}

#[test]
fn two_status_registers_and_another_take_two_requests() {
    let answers = [answer(&STATUS), answer(&[0x0064])];
    let mut d = drive(&answers);
    d.read_many((
        params::ActualSpeed,
        params::FaultAndCommandedDirection,
        params::SerialSpeedCommand,
    ))
    .unwrap();
    let line = d.into_link().into_bus().into_stream();
    assert_eq!(line.sent.len(), 2);
    assert_eq!(line.sent[0], with_crc(&[SA, 0x03, 0x00, 0x18, 0x00, 0x06]));
}

#[test]
fn one_request_per_register_takes_six() {
    let singles: Vec<Vec<u8>> = STATUS.iter().map(|w| answer(&[*w])).collect();
    let mut d = drive(&singles);
    d.command_speed().read().unwrap();
    d.actual_speed().read().unwrap();
    d.load_and_status().read().unwrap();
    d.direction_and_control_mode().read().unwrap();
    d.speed_source_and_reference().read().unwrap();
    d.fault_and_commanded_direction().read().unwrap();
    let line = d.into_link().into_bus().into_stream();
    assert_eq!(traffic(&line, &singles), (6, 48, 42));
}
