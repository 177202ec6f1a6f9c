//! The generated crate against the simulated Kinco FD (drivesim, built from the same
//! description) over Modbus TCP on 127.0.0.1: the speed-mode sequence of 10.5, the store
//! command, and the exception answer the manual prints for FC 0x03 (0x81, line 2424).

use drivebus::modbus::transport::{ModbusTcpClient, TcpConfig};
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
