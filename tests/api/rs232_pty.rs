//! The generated API of the RS-232 fixture talks to the simulator through a real socat pty pair:
//! the manual's speed-mode sequence (section 9.4, lines 2361–2365), point-to-point and in a
//! multi-point loop, and the typed errors a wrong station, a corrupted answer, a cut-short
//! answer and an echo out of place give, each naming the parameter and its object.

use std::io::{Read, Write};
use std::time::Duration;

use drivebus::rs232::client::{open_line, Rs232Client, Rs232Config};
use drivebus::rs232::{LoopMode, Rs232Error, Rs232Link, StationId};
use drivebus::stream::ByteStream;
use drivebus::units::Rpm;
use drivebus::{BusError, Error};
use drivegen_tests::kinco_rs232::KincoRs232;
use drivesim::Simulator;
use peer_support::{pty_pair, PtyPair};

const TIMEOUT: Duration = Duration::from_millis(300);

type Drive = KincoRs232<Rs232Link<Rs232Client<drivebus::stream::SerialStream>>>;

fn fixture() -> Simulator {
    let sim =
        Simulator::load(concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures/kinco-rs232")).unwrap();
    sim.preset("encoder_resolution", 10_000).unwrap();
    sim
}

fn config(mode: LoopMode) -> Rs232Config {
    Rs232Config {
        timeout: TIMEOUT,
        mode,
        ..Rs232Config::default()
    }
}

/// A simulated drive at station 1 on the server end of a fresh pty pair; the thread ends with
/// an I/O error once socat is gone.
fn simulated(sim: &Simulator, mode: LoopMode) -> PtyPair {
    let pty = pty_pair();
    let mut stream = open_line(pty.server.to_str().unwrap(), &config(mode)).unwrap();
    let mut server = sim.rs232_server(StationId(1), mode);
    std::thread::spawn(move || drivesim::rs232::serve(&mut server, &mut stream));
    pty
}

fn drive(pty: &PtyPair, station: u8, mode: LoopMode) -> Drive {
    let bus = Rs232Client::open(pty.client.to_str().unwrap(), config(mode)).unwrap();
    KincoRs232::rs232(bus, StationId(station))
}

fn raw(sim: &Simulator, name: &str) -> i128 {
    sim.with(|drive| drive.store().int(drive.store().id(name).unwrap()).unwrap())
}

fn run_speed_mode(drive: &mut Drive, sim: &Simulator) {
    drive.operation_mode().write(3i8).unwrap();
    drive.target_speed().write(Rpm(150.0)).unwrap();
    drive.controlword().write(0x000Fu16).unwrap();
    assert_eq!(raw(sim, "operation_mode"), 3);
    assert_eq!(raw(sim, "target_speed"), 409_600, "line 2364: 00 40 06 00");
    assert_eq!(raw(sim, "controlword"), 0x0F);
    assert_eq!(drive.target_speed().read().unwrap(), Rpm(150.0));
    // The simulator runs the CiA 402 state machine on 6040h / 6041h.
    let statusword = drive.statusword().read().unwrap();
    assert_eq!(i128::from(statusword), raw(sim, "statusword"));
}

#[test]
fn the_speed_mode_sequence_runs_point_to_point() {
    let sim = fixture();
    let pty = simulated(&sim, LoopMode::PointToPoint);
    run_speed_mode(&mut drive(&pty, 1, LoopMode::PointToPoint), &sim);
}

#[test]
fn the_speed_mode_sequence_runs_in_a_multi_point_loop() {
    let sim = fixture();
    let pty = simulated(&sim, LoopMode::MultiPoint);
    run_speed_mode(&mut drive(&pty, 1, LoopMode::MultiPoint), &sim);
}

fn rs232_error(error: Error) -> (&'static str, u16, Rs232Error) {
    match error {
        Error::Bus {
            parameter,
            cause:
                BusError::Rs232Exchange {
                    index,
                    subindex: 0,
                    error,
                },
        } => (parameter, index, error),
        other => panic!("not an RS-232 failure: {other:?}"),
    }
}

#[test]
fn an_unused_station_is_silence_or_an_unanswered_loop() {
    let sim = fixture();
    let pty = simulated(&sim, LoopMode::PointToPoint);
    let error = drive(&pty, 7, LoopMode::PointToPoint).statusword().read();
    assert_eq!(
        rs232_error(error.unwrap_err()),
        ("statusword", 0x6041, Rs232Error::Silence)
    );
    let sim = fixture();
    let pty = simulated(&sim, LoopMode::MultiPoint);
    let error = drive(&pty, 7, LoopMode::MultiPoint).statusword().read();
    assert_eq!(
        rs232_error(error.unwrap_err()),
        ("statusword", 0x6041, Rs232Error::NoAnswer)
    );
}

#[test]
fn the_loop_mode_must_match_the_drives() {
    let sim = fixture();
    let pty = simulated(&sim, LoopMode::MultiPoint);
    let error = drive(&pty, 1, LoopMode::PointToPoint).controlword().read();
    assert_eq!(
        rs232_error(error.unwrap_err()),
        ("controlword", 0x6040, Rs232Error::EchoOutOfPlace)
    );
}

/// A drive that answers each telegram with `reply(telegram)`, by hand, on the server end.
fn scripted(reply: fn(&[u8; 10]) -> Vec<u8>) -> PtyPair {
    let pty = pty_pair();
    let mut port = open_line(
        pty.server.to_str().unwrap(),
        &config(LoopMode::PointToPoint),
    )
    .unwrap();
    std::thread::spawn(move || -> Result<(), BusError> {
        let mut telegram = [0u8; 10];
        let mut got = 0;
        loop {
            let deadline = std::time::Instant::now() + Duration::from_secs(5);
            got += port.receive(&mut telegram[got..], deadline)?;
            if got == 10 {
                port.send(&reply(&telegram))?;
                got = 0;
            }
        }
    });
    pty
}

#[test]
fn corrupted_and_cut_short_answers_are_typed_errors() {
    // Echo the telegram back with the "written" command and a broken checksum.
    let pty = scripted(|t| {
        let mut answer = *t;
        answer[1] = 0x60;
        answer.to_vec()
    });
    let error = drive(&pty, 1, LoopMode::PointToPoint)
        .controlword()
        .write(0x0006u16);
    assert!(matches!(
        rs232_error(error.unwrap_err()),
        ("controlword", 0x6040, Rs232Error::Checksum { .. })
    ));
    let pty = scripted(|t| t[..6].to_vec());
    let error = drive(&pty, 1, LoopMode::PointToPoint)
        .controlword()
        .write(0x0006u16);
    assert_eq!(
        rs232_error(error.unwrap_err()),
        ("controlword", 0x6040, Rs232Error::Short { received: 6 })
    );
}

#[test]
fn the_pty_carries_the_manuals_bytes() {
    // Line 2332 "Set Target_position = 50000", sent by the generated API, read off the wire.
    let pty = pty_pair();
    let mut peer = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .open(&pty.server)
        .unwrap();
    let mut drive = drive(&pty, 1, LoopMode::PointToPoint);
    let writer = std::thread::spawn(move || drive.target_position().write(50_000i32));
    let mut telegram = [0u8; 10];
    peer.read_exact(&mut telegram).unwrap();
    assert_eq!(
        telegram,
        [0x01, 0x23, 0x7A, 0x60, 0x00, 0x50, 0xC3, 0x00, 0x00, 0xEF]
    );
    peer.write_all(&[0x01, 0x60, 0x7A, 0x60, 0x00, 0, 0, 0, 0, 0xC5])
        .unwrap();
    writer.join().unwrap().unwrap();
}
