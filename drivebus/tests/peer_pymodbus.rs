//! Against independent implementations: pymodbus 3.16.1 serving Modbus TCP, RTU-over-TCP and RTU
//! on a socat pty pair, and pyModbusTCP 0.3.1 serving pipelined Modbus TCP requests. Each test
//! starts its own peer processes and stops them by PID.
//!
//! Python comes from `DRIVEGEN_PYTHON`, else `.venv/bin/python` at the workspace root, else
//! `python3`. Missing peers fail the test with instructions; `tests/peers/setup.sh` installs them.
#![cfg(feature = "modbus")]

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use drivebus::link::ReadRequest;
use drivebus::modbus::client::{
    ModbusTcpClient, RtuOverTcpClient, SerialConfig, SerialRtuClient, TcpConfig,
};
use drivebus::modbus::retry::RetryPolicy;
use drivebus::modbus::{
    BitBus, ExceptionCode, ModbusAddress, ModbusLimits, ModbusLink, RegisterBus, RegisterRead,
    Table, UnitId, WordOrder,
};
use drivebus::{BusError, Link};
use peer_support::{pty_pair, python, workspace_root, Process, SETUP_HINT};

const UNIT: UnitId = UnitId(1);
/// Starts the pymodbus server with `args` and waits for its first stdout line.
fn start_server(args: &[&str]) -> (Process, String) {
    start_peer("modbus_server.py", args)
}

/// Starts `tests/peers/<script>` with `args` and waits for its first stdout line.
fn start_peer(script: &str, args: &[&str]) -> (Process, String) {
    let python = python();
    let script = workspace_root().join("tests/peers").join(script);
    let mut child = Command::new(&python)
        .arg(&script)
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start {} ({e}); {SETUP_HINT}", python.display()));
    let stdout = child.stdout.take().expect("piped stdout");
    let process = Process::new(child);
    let mut line = String::new();
    BufReader::new(stdout)
        .read_line(&mut line)
        .expect("read the peer's stdout");
    assert!(
        !line.is_empty(),
        "the peer {} exited before it was ready (are its packages installed for {}?); {SETUP_HINT}",
        script.display(),
        python.display()
    );
    (process, line.trim().to_owned())
}

fn tcp_server(mode: &str) -> (Process, String) {
    port_of(start_server(&[mode]))
}

fn port_of((process, line): (Process, String)) -> (Process, String) {
    let port = line
        .strip_prefix("PORT ")
        .unwrap_or_else(|| panic!("unexpected peer output {line:?}"));
    (process, format!("127.0.0.1:{port}"))
}

fn tcp_config() -> TcpConfig {
    TcpConfig {
        timeout: Duration::from_secs(2),
        ..TcpConfig::default()
    }
}

/// The register and bit traffic every transport must carry the same way.
fn exercise<B: RegisterBus + BitBus>(bus: &mut B) {
    let mut status = [0u16; 17];
    bus.read_registers(UNIT, Table::Input, 0x60, &mut status)
        .unwrap();
    assert_eq!(status[0], 0x1060);
    assert_eq!(status[16], 0x1070);
    assert_eq!([status[11], status[12]], [0x5678, 0x1234]);

    bus.write_register(UNIT, 0x30, 777).unwrap();
    bus.write_registers(UNIT, 0x40, &[1, 2, 3]).unwrap();
    let mut back = [0u16; 4];
    bus.read_registers(UNIT, Table::Holding, 0x40, &mut back[..3])
        .unwrap();
    assert_eq!(back[..3], [1, 2, 3]);
    bus.read_registers(UNIT, Table::Holding, 0x30, &mut back[..1])
        .unwrap();
    assert_eq!(back[0], 777);

    let mut coils = [false; 10];
    bus.read_coils(UNIT, 0, &mut coils).unwrap();
    assert_eq!(coils, core::array::from_fn(|i| i % 2 == 0));
    bus.write_coil(UNIT, 1, true).unwrap();
    bus.write_coils(UNIT, 8, &[false, true, true]).unwrap();
    bus.read_coils(UNIT, 0, &mut coils).unwrap();
    assert!(coils[1] && !coils[8] && coils[9]);
    let mut inputs = [false; 7];
    bus.read_discrete_inputs(UNIT, 0, &mut inputs).unwrap();
    assert_eq!(inputs, core::array::from_fn(|i| i % 3 == 0));

    // Exceptions come back typed, with their meaning.
    let mut one = [0u16; 1];
    let missing = bus
        .read_registers(UNIT, Table::Holding, 0x0200, &mut one)
        .unwrap_err();
    assert_eq!(
        missing,
        BusError::ModbusException {
            function: 0x03,
            code: drivebus::modbus::ExceptionCode::IllegalDataAddress
        }
    );
    assert_eq!(
        missing.modbus_exception(),
        Some(ExceptionCode::IllegalDataAddress)
    );
    let refused = bus.write_register(UNIT, 0x28, 0).unwrap_err();
    assert_eq!(
        refused.modbus_exception(),
        Some(ExceptionCode::IllegalDataValue)
    );
    assert_eq!(
        refused.to_string(),
        "Modbus exception 0x03 (illegal data value) to function 0x06"
    );
    let refused = bus.write_registers(UNIT, 0x27, &[5, 300]).unwrap_err();
    assert_eq!(
        refused,
        BusError::ModbusException {
            function: 0x10,
            code: drivebus::modbus::ExceptionCode::IllegalDataValue
        }
    );
    // The client is still in step after the exceptions.
    bus.read_registers(UNIT, Table::Holding, 0x28, &mut one)
        .unwrap();
    assert_eq!(one, [1]);
}

fn pair(table: Table, address: u16) -> ModbusAddress {
    ModbusAddress {
        table,
        address,
        words: 2,
        word_order: WordOrder::LowFirst,
    }
}

fn one(table: Table, address: u16) -> ModbusAddress {
    ModbusAddress {
        table,
        address,
        words: 1,
        word_order: WordOrder::HighFirst,
    }
}

/// Values through the generated-code path: 32-bit LOW/HIGH pairs and a planned batch read.
fn exercise_link<B: RegisterBus>(bus: B) {
    let mut link = ModbusLink::new(bus, UNIT, ModbusLimits::SPEC);
    let mut out = [0u8; 4];
    assert_eq!(link.read(&pair(Table::Input, 0x6B), &mut out), Ok(4));
    assert_eq!(u32::from_le_bytes(out), 0x1234_5678);

    link.write(&pair(Table::Holding, 0x50), &0xCAFE_F00Du32.to_le_bytes())
        .unwrap();
    let mut raw = [0u16; 2];
    link.bus_mut()
        .read_registers(UNIT, Table::Holding, 0x50, &mut raw)
        .unwrap();
    assert_eq!(raw, [0xF00D, 0xCAFE], "LOW word first");

    let (mut a, mut b, mut c) = ([0u8; 2], [0u8; 4], [0u8; 2]);
    let mut batch = [
        ReadRequest {
            address: one(Table::Input, 0x60),
            buf: &mut a,
            len: 0,
        },
        ReadRequest {
            address: pair(Table::Input, 0x6B),
            buf: &mut b,
            len: 0,
        },
        ReadRequest {
            address: one(Table::Input, 0x70),
            buf: &mut c,
            len: 0,
        },
    ];
    link.read_many(&mut batch).unwrap();
    assert_eq!(batch.each_ref().map(|r| r.len), [2, 4, 2]);
    assert_eq!(u16::from_le_bytes(a), 0x1060);
    assert_eq!(u32::from_le_bytes(b), 0x1234_5678);
    assert_eq!(u16::from_le_bytes(c), 0x1070);

    let mut bad = [0u8; 2];
    assert_eq!(
        link.read(&one(Table::Input, 0x71), &mut bad),
        Err(BusError::ModbusException {
            function: 0x04,
            code: drivebus::modbus::ExceptionCode::IllegalDataAddress
        })
    );
}

#[test]
fn modbus_tcp_against_pymodbus() {
    let (_server, addr) = tcp_server("tcp");
    let mut client = ModbusTcpClient::connect(&addr, &tcp_config()).unwrap();
    exercise(&mut client);
    exercise_link(client);
}

/// A pipelined batch, an exception in the middle of it, and a planned `read_many` spanning both
/// tables, against pyModbusTCP 0.3.1 (pymodbus 3.16.1 answers only the first of several requests
/// that arrive together, so it cannot be the peer here).
#[test]
fn pipelined_modbus_tcp_against_pymodbustcp() {
    let (_server, addr) = port_of(start_peer("pipelining_server.py", &[]));
    let config = TcpConfig {
        max_in_flight: 8,
        ..tcp_config()
    };
    let mut client = ModbusTcpClient::connect(&addr, &config).unwrap();
    let (mut status, mut holding, mut missing, mut last) =
        ([0u16; 17], [0u16; 4], [0u16; 1], [0u16; 2]);
    let mut reads = [
        RegisterRead::new(Table::Input, 0x60, &mut status),
        RegisterRead::new(Table::Holding, 0x10, &mut holding),
        RegisterRead::new(Table::Holding, 0x0200, &mut missing),
        RegisterRead::new(Table::Input, 0x6F, &mut last),
    ];
    assert_eq!(
        client.read_register_batch(UNIT, &mut reads),
        Err(BusError::ModbusException {
            function: 0x03,
            code: drivebus::modbus::ExceptionCode::IllegalDataAddress
        })
    );
    assert_eq!(reads.map(|read| read.done), [true, true, false, true]);
    assert_eq!(
        [status[0], status[11], status[16]],
        [0x1060, 0x5678, 0x1070]
    );
    assert_eq!(holding, [0x10, 0x11, 0x12, 0x13]);
    assert_eq!(last, [0x106F, 0x1070]);

    let mut link = ModbusLink::new(client, UNIT, ModbusLimits::SPEC);
    let (mut a, mut b) = ([0u8; 4], [0u8; 2]);
    let mut batch = [
        ReadRequest {
            address: pair(Table::Input, 0x6B),
            buf: &mut a,
            len: 0,
        },
        ReadRequest {
            address: one(Table::Holding, 0x28),
            buf: &mut b,
            len: 0,
        },
    ];
    link.read_many(&mut batch).unwrap();
    assert_eq!(u32::from_le_bytes(a), 0x1234_5678);
    assert_eq!(u16::from_le_bytes(b), 1, "holding 0x0028 (drive address)");
}

#[test]
fn rtu_over_tcp_against_pymodbus() {
    let (_server, addr) = tcp_server("rtu-over-tcp");
    let mut client = RtuOverTcpClient::connect(&addr, &tcp_config()).unwrap();
    exercise(&mut client);
    exercise_link(client);
}

fn serial_config() -> SerialConfig {
    SerialConfig {
        timeout: Duration::from_secs(2),
        ..SerialConfig::new(19_200)
    }
}

#[test]
fn rtu_on_a_pty_against_pymodbus() {
    let pty = pty_pair();
    let (client_end, server_end) = (pty.client.clone(), pty.server.clone());
    let (_server, ready) = start_server(&["rtu", server_end.to_str().unwrap()]);
    assert_eq!(ready, "READY");
    let mut client = SerialRtuClient::open(client_end.to_str().unwrap(), &serial_config()).unwrap();
    exercise(&mut client);
    exercise_link(client);
}

#[test]
fn silence_on_a_pty_ends_in_a_timeout() {
    let pty = pty_pair();
    let client_end = pty.client.clone();
    let config = SerialConfig {
        timeout: Duration::from_millis(200),
        retry: RetryPolicy::reads(1),
        ..SerialConfig::new(19_200)
    };
    let mut client = SerialRtuClient::open(client_end.to_str().unwrap(), &config).unwrap();
    let started = Instant::now();
    let mut out = [0u16; 1];
    assert_eq!(
        client.read_registers(UNIT, Table::Holding, 0, &mut out),
        Err(BusError::Timeout)
    );
    // Two attempts of 200 ms; the bound only proves the call ends, not timing precision.
    assert!(started.elapsed() < Duration::from_secs(10));
    assert_eq!(client.write_register(UNIT, 0, 1), Err(BusError::Timeout));
}
