//! The Modbus server over TCP against drivebus's client: access, ranges, allowed values, unknown
//! addresses, function codes and limits answered with the described exception codes.

use drivebus::modbus::client::{ModbusTcpClient, TcpConfig};
use drivebus::modbus::{RegisterBus, RegisterRead, Table, UnitId};
use drivebus::BusError;
use drivesim::Simulator;

const UNIT: UnitId = UnitId(1);

fn fixture() -> (Simulator, ModbusTcpClient, drivesim::modbus::tcp::TcpServer) {
    let sim = Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/enforcement.toml"
    ))
    .unwrap();
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UNIT).unwrap();
    let client = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default()).unwrap();
    (sim, client, server)
}

fn exception(result: Result<(), BusError>) -> u8 {
    match result {
        Err(BusError::ModbusException { code, .. }) => code.code(),
        other => panic!("expected an exception, got {other:?}"),
    }
}

#[test]
fn starts_from_the_described_defaults() {
    let (_sim, mut client, _server) = fixture();
    let mut regs = [0u16; 3];
    client
        .read_registers(UNIT, Table::Holding, 0x0010, &mut regs[..1])
        .unwrap();
    assert_eq!(regs[0], 100);
    client
        .read_registers(UNIT, Table::Input, 0x0010, &mut regs[..1])
        .unwrap();
    assert_eq!(regs[0], 0, "no default: 0");
}

#[test]
fn writes_are_checked_against_range_and_allowed_values() {
    let (_sim, mut client, _server) = fixture();
    client
        .write_register(UNIT, 0x0010, (-3000i16) as u16)
        .unwrap();
    assert_eq!(exception(client.write_register(UNIT, 0x0010, 3001)), 0x03);
    assert_eq!(
        exception(client.write_register(UNIT, 0x0010, (-3001i16) as u16)),
        0x03
    );
    assert_eq!(exception(client.write_register(UNIT, 0x0012, 2)), 0x03);
    client.write_register(UNIT, 0x0012, 1).unwrap();
    let mut regs = [0u16; 1];
    client
        .read_registers(UNIT, Table::Holding, 0x0010, &mut regs)
        .unwrap();
    assert_eq!(regs[0] as i16, -3000, "refused writes leave the value");
}

#[test]
fn access_and_addresses_are_enforced() {
    let (_sim, mut client, _server) = fixture();
    let mut regs = [0u16; 1];
    assert_eq!(
        exception(client.read_registers(UNIT, Table::Holding, 0x0011, &mut regs)),
        0x02,
        "write-only"
    );
    assert_eq!(
        exception(client.read_registers(UNIT, Table::Holding, 0x0099, &mut regs)),
        0x02,
        "unknown"
    );
    assert_eq!(
        exception(client.write_register(UNIT, 0x0099, 1)),
        0x02,
        "unknown"
    );
    assert_eq!(
        exception(client.read_registers(UNIT, Table::Holding, 0x0099, &mut regs)),
        0x02,
        "unknown"
    );
    assert_eq!(
        exception(client.write_register(UNIT, 0x0099, 1)),
        0x02,
        "unknown"
    );
    // Input 0x0010 is read-only by nature; holding 0x0013 does not exist.
    assert_eq!(exception(client.write_register(UNIT, 0x0013, 1)), 0x02);
    client.write_register(UNIT, 0x0011, 7).unwrap();
}

#[test]
fn reads_may_span_gaps_next_to_documented_registers() {
    let (_sim, mut client, _server) = fixture();
    let mut regs = [0xFFFFu16; 2];
    client
        .read_registers(UNIT, Table::Holding, 0x0012, &mut regs)
        .unwrap();
    assert_eq!(regs, [0, 0], "0x0013 is a gap; read_gaps defaults to true");
}

#[test]
fn limits_and_function_codes_are_enforced() {
    let (_sim, mut client, _server) = fixture();
    let mut five = [0u16; 5];
    assert_eq!(
        exception(client.read_registers(UNIT, Table::Holding, 0x0010, &mut five)),
        0x03
    );
    assert_eq!(
        exception(client.write_registers(UNIT, 0x0010, &[1, 2, 3])),
        0x03
    );
    let mut coils = [false; 1];
    let refused = drivebus::modbus::BitBus::read_coils(&mut client, UNIT, 0, &mut coils);
    assert_eq!(
        exception(refused),
        0x01,
        "FC 0x01 is not among the device's functions"
    );
}

#[test]
fn two_word_values_follow_the_word_order() {
    let (_sim, mut client, _server) = fixture();
    client
        .write_registers(UNIT, 0x0020, &[0x4240, 0x000F])
        .unwrap();
    let mut regs = [0u16; 2];
    client
        .read_registers(UNIT, Table::Holding, 0x0020, &mut regs)
        .unwrap();
    assert_eq!(regs, [0x4240, 0x000F]);
}

#[test]
fn another_units_requests_get_no_answer() {
    let (_sim, _client, server) = fixture();
    let config = TcpConfig {
        timeout: std::time::Duration::from_millis(200),
        retry: drivebus::modbus::retry::RetryPolicy::reads(0),
        ..TcpConfig::default()
    };
    let mut client = ModbusTcpClient::connect(server.local_addr(), &config).unwrap();
    let mut regs = [0u16; 1];
    let result = client.read_registers(UnitId(9), Table::Holding, 0x0010, &mut regs);
    assert_eq!(result, Err(BusError::Timeout));
}

/// The server reads its connection request by request, so a pipelining client's batch (sent in
/// one write) is answered in full, an exception included.
#[test]
fn pipelined_requests_are_answered_in_turn() {
    let (_sim, _client, server) = fixture();
    let config = TcpConfig {
        max_in_flight: 8,
        ..TcpConfig::default()
    };
    let mut client = ModbusTcpClient::connect(server.local_addr(), &config).unwrap();
    let (mut holding, mut input, mut unknown) = ([0u16; 1], [0u16; 1], [0u16; 1]);
    let mut reads = [
        RegisterRead::new(Table::Holding, 0x0010, &mut holding),
        RegisterRead::new(Table::Input, 0x7000, &mut unknown),
        RegisterRead::new(Table::Input, 0x0010, &mut input),
    ];
    assert_eq!(
        client
            .read_register_batch(UNIT, &mut reads)
            .map_err(|e| e.modbus_exception()),
        Err(Some(drivebus::modbus::ExceptionCode::IllegalDataAddress))
    );
    assert_eq!(reads.map(|read| read.done), [true, false, true]);
    assert_eq!((holding, input), ([100], [0]), "the described defaults");
}

#[test]
fn the_kinco_quick_stop_mode_decides_where_a_quick_stop_leads() {
    // Kinco FD over Modbus: controlword 3100h, statusword 3200h, quick stop mode (605Ah) 3400h
    // (manual lines 1935, 1936, 2128). The simulator ticks before every request, so a quick
    // stop's automatic transition 12 (codes 1-4) has happened by the next read.
    let sim = Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../descriptions/kinco-fd"
    ))
    .unwrap();
    let server = sim.modbus_server();
    let request = |pdu: &[u8]| {
        let mut out = [0u8; drivebus::modbus::pdu::MAX_PDU];
        let len = sim.with(|drive| server.handle(drive, pdu, &mut out));
        out[..len].to_vec()
    };
    let write = |address: u16, value: u16| {
        let [a, b] = address.to_be_bytes();
        let [c, d] = value.to_be_bytes();
        assert_eq!(
            request(&[0x06, a, b, c, d])[0],
            0x06,
            "write {address:#06x}"
        );
    };
    let statusword = || {
        let read = request(&[0x03, 0x32, 0x00, 0x00, 0x01]);
        u16::from_be_bytes([read[2], read[3]])
    };
    let quick_stop_with = |mode: u16| {
        write(0x3400, mode);
        for controlword in [0x06, 0x07, 0x0F] {
            write(0x3100, controlword);
        }
        assert_eq!(statusword(), 0x0037, "operation enabled");
        write(0x3100, 0x0B);
        statusword()
    };
    assert_eq!(
        quick_stop_with(0),
        0x0040,
        "0 stop without control: switched off"
    );
    assert_eq!(
        quick_stop_with(2),
        0x0040,
        "2 quick stop ramp, then switched off"
    );
    assert_eq!(quick_stop_with(6), 0x0017, "6 stays in quick stop active");
    write(0x3100, 0x0F);
    assert_eq!(statusword(), 0x0037, "transition 16 with code 6");
}
