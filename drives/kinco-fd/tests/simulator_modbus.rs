//! The generated crate against the simulated Kinco FD (drivesim, built from the same
//! description) over Modbus TCP on 127.0.0.1: the speed-mode sequence of 10.5, the store
//! command, and the exception answer the manual prints for FC 0x03 (0x81, line 2424); and the
//! simulated drive's Modbus server directly: the manual's 2-register statusword read (line 2488),
//! the FC 0x10 exception (0x90, line 2460) and the speed ramp of the profile acceleration.

use drivebus::modbus::client::{ModbusTcpClient, TcpConfig};
use drivebus::modbus::{RegisterBus, Table, UnitId};
use drivebus::units::Rpm;
use drivebus::{BusError, Error};
use kinco_fd::types::ModesOfOperation;
use kinco_fd::{KincoFd, Store};

fn simulator() -> drivesim::Simulator {
    drivesim::Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../descriptions/kinco-fd"
    ))
    .unwrap()
}

#[test]
fn speed_mode_sequence_round_trips_through_the_simulator() {
    let sim = simulator();
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1)).unwrap();
    let bus = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default()).unwrap();
    let mut drive = KincoFd::modbus(bus, UnitId(1)).give_encoder_resolution(10_000);
    drive
        .modes_of_operation()
        .write(ModesOfOperation::VELOCITY)
        .unwrap();
    drive.target_velocity().write(Rpm(150.0)).unwrap();
    drive.controlword().write_raw(0x0F).unwrap();
    assert_eq!(
        drive.modes_of_operation().read().unwrap(),
        ModesOfOperation::VELOCITY
    );
    assert_eq!(drive.target_velocity().read().unwrap(), Rpm(150.0));
    assert_eq!(drive.target_velocity().read_raw().unwrap(), 409_600);
    // The simulator accepts exactly the command values of 2FF0h sub 1 (1 and 10).
    drive.store(Store::ControlLoop).unwrap();
    drive.store(Store::InitialiseControlLoop).unwrap();
}

#[test]
fn the_fc3_exception_comes_back_as_0x81_and_is_decoded_as_an_exception() {
    let sim = simulator();
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1)).unwrap();
    let mut bus = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default()).unwrap();
    let mut out = [0u16; 1];
    // 0x0001 is no register of the drive (the map is discontinuous, line 2395).
    let refused = bus.read_registers(UnitId(1), Table::Holding, 0x0001, &mut out);
    assert_eq!(
        refused,
        Err(BusError::ModbusException {
            function: 0x03,
            code: drivebus::modbus::ExceptionCode::IllegalDataAddress
        })
    );
}

#[test]
fn a_store_value_the_register_does_not_take_is_refused_before_sending() {
    let sim = simulator();
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1)).unwrap();
    let bus = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default()).unwrap();
    let mut drive = KincoFd::modbus(bus, UnitId(1));
    let refused = drive.store_data().write_raw(2);
    assert!(matches!(refused, Err(Error::Value(_))), "{refused:?}");
}

#[test]
fn the_simulated_drive_answers_the_fc3_exception_as_the_manual_prints_it() {
    let sim = simulator();
    let server = sim.modbus_server();
    let mut out = [0u8; drivebus::modbus::pdu::MAX_PDU];
    let read_unknown = [0x03, 0x00, 0x01, 0x00, 0x01];
    let len = sim.with(|drive| server.handle(drive, &read_unknown, &mut out));
    assert_eq!(out[..len], [0x81, 0x02], "0x81, not 0x83 (line 2424)");
    let write_read_only = [0x06, 0x32, 0x00, 0x00, 0x01]; // statusword 0x3200
    let len = sim.with(|drive| server.handle(drive, &write_read_only, &mut out));
    assert_eq!(out[0], 0x86, "FC 0x06 answers 0x86 (line 2440)");
    assert_eq!(len, 2);
}

/// Answers one request PDU; the answer PDU.
fn answer(sim: &drivesim::Simulator, request: &[u8]) -> Vec<u8> {
    let server = sim.modbus_server();
    let mut out = [0u8; drivebus::modbus::pdu::MAX_PDU];
    let len = sim.with(|drive| server.handle(drive, request, &mut out));
    out[..len].to_vec()
}

#[test]
fn the_simulated_drive_answers_the_manuals_two_register_statusword_read() {
    // 01 03 32 00 00 02 CA B3 (lines 2488, 2498, 2513): the CRC is the printed one ...
    let printed = [0x01, 0x03, 0x32, 0x00, 0x00, 0x02];
    assert_eq!(
        drivebus::modbus::crc::crc16_modbus(&printed).to_le_bytes(),
        [0xCA, 0xB3]
    );
    // ... and the drive answers 4 bytes: the statusword, then 0x3201 (not described: 0).
    let sim = simulator();
    let one = answer(&sim, &[0x03, 0x32, 0x00, 0x00, 0x01]);
    assert_eq!(one[..2], [0x03, 0x02]);
    let two = answer(&sim, &printed[1..]);
    assert_eq!(two[..2], [0x03, 0x04]);
    assert_eq!(two[2..4], one[2..4], "the statusword first");
    assert_eq!(two[4..], [0x00, 0x00]);
    // Only the declared read: 0x3201 alone, or 3 registers, stay refused (discontinuous map).
    assert_eq!(answer(&sim, &[0x03, 0x32, 0x01, 0x00, 0x01]), [0x81, 0x02]);
    assert_eq!(answer(&sim, &[0x03, 0x32, 0x00, 0x00, 0x03]), [0x81, 0x02]);
}

#[test]
fn an_out_of_range_fc16_write_is_answered_0x90() {
    // K_Velocity_FF 0 ~ 100 (line 1751): 1000 written with FC 0x10 is refused with 0x90 (line 2460).
    let sim = simulator();
    let refused = answer(&sim, &[0x10, 0x68, 0x20, 0x00, 0x01, 0x02, 0x03, 0xE8]);
    assert_eq!(refused, [0x90, 0x03]);
    let taken = answer(&sim, &[0x10, 0x68, 0x20, 0x00, 0x01, 0x02, 0x00, 0x64]);
    assert_eq!(taken, [0x10, 0x68, 0x20, 0x00, 0x01]);
}

#[test]
fn the_simulated_motor_ramps_to_the_target_speed_with_the_profile_acceleration() {
    // Mode 3 follows Target_Speed with the profile acceleration (line 1325, [[ramp]]):
    // 100000 DEC (610.352 rps/s at resolution 10000, line 1966) is 100000 speed DEC per ms, so
    // 150 rpm (409600 DEC, line 2364) is reached in 4.1 ms.
    // A drive of its own, not the shared simulator: time passes only by `tick`.
    let device = drivegen::check(
        concat!(env!("CARGO_MANIFEST_DIR"), "/../../descriptions/kinco-fd").as_ref(),
    )
    .device
    .unwrap();
    let server = drivesim::modbus::ModbusServer::new(&device, None);
    let drive = std::cell::RefCell::new(drivesim::Drive::new(device));
    let answer = |request: &[u8]| {
        let mut out = [0u8; drivebus::modbus::pdu::MAX_PDU];
        let len = server.handle(&mut drive.borrow_mut(), request, &mut out);
        out[..len].to_vec()
    };
    let write = |address: u16, words: &[u16]| {
        let mut pdu = vec![0x10];
        pdu.extend(address.to_be_bytes());
        pdu.extend((words.len() as u16).to_be_bytes());
        pdu.push(2 * words.len() as u8);
        for w in words {
            pdu.extend(w.to_be_bytes());
        }
        assert_eq!(answer(&pdu)[0], 0x10, "write {address:#06x}");
    };
    write(0x4B00, &[0x86A0, 0x0001]); // profile acceleration 100000
    write(0x4C00, &[0x86A0, 0x0001]); // profile deceleration 100000
    write(0x3500, &[3]); // speed mode
    write(0x6F00, &[0x4000, 0x0006]); // 409600 DEC = 150 rpm
    for controlword in [0x06, 0x07, 0x0F] {
        write(0x3100, &[controlword]);
    }
    let speed = || {
        let read = answer(&[0x03, 0x3B, 0x00, 0x00, 0x02]);
        let low = u16::from_be_bytes([read[2], read[3]]);
        let high = u16::from_be_bytes([read[4], read[5]]);
        (u32::from(high) << 16 | u32::from(low)) as i32
    };
    let tick = |ms: u64| {
        drive
            .borrow_mut()
            .tick(std::time::Duration::from_millis(ms))
    };
    tick(1);
    assert_eq!(speed(), 100_000, "one ms of acceleration");
    tick(2);
    assert_eq!(speed(), 300_000);
    tick(2);
    assert_eq!(speed(), 409_600, "reached, not passed");
    write(0x6F00, &[0, 0]);
    tick(1);
    assert_eq!(speed(), 309_600, "decelerates at the profile deceleration");
}

#[test]
fn after_a_quick_stop_0x06_then_0x0f_enables_again() {
    // "After quick stop, the controlword needs to be set to 0x06 before 0x0F for enabling"
    // (line 1196); 0x0B is the quick stop (line 1935).
    let sim = simulator();
    let control = |word: u16| {
        let [high, low] = word.to_be_bytes();
        assert_eq!(answer(&sim, &[0x06, 0x31, 0x00, high, low])[0], 0x06);
        let status = answer(&sim, &[0x03, 0x32, 0x00, 0x00, 0x01]);
        u16::from_be_bytes([status[2], status[3]])
    };
    for word in [0x06, 0x07] {
        control(word);
    }
    let enabled = control(0x0F);
    assert_eq!(enabled & 0x6F, 0x27, "operation enabled: {enabled:#06x}");
    let stopped = control(0x0B);
    assert_ne!(stopped & 0x6F, 0x27, "quick stop: {stopped:#06x}");
    control(0x06);
    let again = control(0x0F);
    assert_eq!(again & 0x6F, 0x27, "enabled again: {again:#06x}");
}

/// A serial line that delivers `input` once and then fails, recording what the drive sends.
struct Line {
    input: std::collections::VecDeque<u8>,
    sent: Vec<u8>,
}

impl drivebus::stream::ByteStream for Line {
    fn send(&mut self, bytes: &[u8]) -> Result<(), BusError> {
        self.sent.extend_from_slice(bytes);
        Ok(())
    }

    fn receive(
        &mut self,
        buf: &mut [u8],
        _deadline: std::time::Instant,
    ) -> Result<usize, BusError> {
        if self.input.is_empty() {
            return Err(BusError::Io(std::io::ErrorKind::UnexpectedEof));
        }
        let n = buf.len().min(self.input.len());
        for (slot, byte) in buf.iter_mut().zip(self.input.drain(..n)) {
            *slot = byte;
        }
        Ok(n)
    }

    fn discard_input(&mut self) -> Result<(), BusError> {
        self.input.clear();
        Ok(())
    }
}

#[test]
fn a_broadcast_to_station_0_is_executed_and_not_answered() {
    // "if station No. is 00, message belongs to broadcast message. All Modbus slaves will accept
    // this message" (line 2534): the speed-mode write of 10.5 (line 2485) sent to station 0.
    let mut frame = vec![0x00, 0x06, 0x35, 0x00, 0x00, 0x03];
    frame.extend(drivebus::modbus::crc::crc16_modbus(&frame).to_le_bytes());
    let sim = simulator();
    let mut line = Line {
        input: frame.into_iter().collect(),
        sent: Vec::new(),
    };
    let ended = drivesim::modbus::rtu::serve(&sim, &mut line, UnitId(1));
    assert_eq!(ended, Err(BusError::Io(std::io::ErrorKind::UnexpectedEof)));
    assert!(line.sent.is_empty(), "no answer to a broadcast");
    let mode = sim.with(|d| d.store().int(d.store().id("modes_of_operation").unwrap()));
    assert_eq!(mode, Some(3), "executed");
}
