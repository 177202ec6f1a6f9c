//! The Lenze smd description served from its data: the variant its selecting parameter holds
//! (`selected_by`: PC507 when #50 is preset to 507, the default PC400 otherwise), the read
//! blocks beyond one register per read, and the commands sharing register #1.

use drivebus::modbus::client::{ModbusTcpClient, TcpConfig};
use drivebus::modbus::{RegisterBus, Table, UnitId};
use drivebus::BusError;
use drivesim::Simulator;

const UNIT: UnitId = UnitId(1);
/// d38 PI enable exists only in PC507, at #124 (manual line 961).
const D38_PC507: u16 = 124;

fn read(sim: &Simulator, register: u16) -> Result<u16, BusError> {
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UNIT).unwrap();
    let mut client = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default()).unwrap();
    let mut word = [0u16; 1];
    client.read_registers(UNIT, Table::Holding, register, &mut word)?;
    Ok(word[0])
}

fn lenze() -> Simulator {
    Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../descriptions/lenze-smd"
    ))
    .unwrap()
}

#[test]
fn the_preset_configuration_number_selects_the_variant_served() {
    let sim = lenze();
    sim.preset("parameter_configuration", 507).unwrap();
    assert_eq!(read(&sim, 50), Ok(507));
    assert_eq!(read(&sim, D38_PC507), Ok(0));
}

#[test]
fn an_unknown_number_serves_the_default_variant() {
    for number in [400, 0, 401] {
        let sim = lenze();
        sim.preset("parameter_configuration", number).unwrap();
        assert_eq!(read(&sim, 50), Ok(number as u16));
        assert!(
            matches!(
                read(&sim, D38_PC507),
                Err(BusError::ModbusException {
                    code: drivebus::modbus::ExceptionCode::IllegalDataAddress,
                    ..
                })
            ),
            "#{D38_PC507} is not a PC400 register (number {number})"
        );
    }
}

fn read_words(sim: &Simulator, register: u16, count: usize) -> Result<Vec<u16>, BusError> {
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UNIT).unwrap();
    let mut client = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default()).unwrap();
    let mut words = vec![0u16; count];
    client.read_registers(UNIT, Table::Holding, register, &mut words)?;
    Ok(words)
}

#[test]
fn the_status_block_and_c99_are_the_only_multi_register_reads() {
    let sim = lenze();
    sim.preset("parameter_configuration", 507).unwrap();
    // #24 and #25 show the motor: the frequency it is commanded to and the one it turns at. A
    // started drive with a ramp time of 0 reaches the serial speed at once.
    sim.preset("control_source", 11).unwrap();
    sim.preset("acceleration_time", 0).unwrap();
    sim.preset("serial_speed_command", 400).unwrap();
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UNIT).unwrap();
    let mut client = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default()).unwrap();
    client.write_register(UNIT, 48, 0).unwrap();
    client.write_register(UNIT, 1, 0x0008).unwrap();
    // #24 answers 1 or 6 words (manual line 617) ...
    assert_eq!(read_words(&sim, 24, 6).unwrap()[..2], [400, 400]);
    assert_eq!(read_words(&sim, 24, 1), Ok(vec![400]));
    // ... and nothing else: 2 words at #24, 2 words at #25, 2 parameters at #51.
    for (register, count) in [(24, 2), (25, 2), (51, 2)] {
        assert!(
            matches!(
                read_words(&sim, register, count),
                Err(BusError::ModbusException {
                    code: drivebus::modbus::ExceptionCode::IllegalDataValue,
                    ..
                })
            ),
            "{count} words at #{register}"
        );
    }
    // C99 is a 4-word read at its one register (#95 in PC507, line 926); #96 is c01.
    assert_eq!(read_words(&sim, 95, 4).map(|w| w.len()), Ok(4));
    assert_eq!(read_words(&sim, 96, 1), Ok(vec![50]), "c01 default 5.0 s");
}

#[test]
fn every_command_of_register_1_is_accepted_and_others_refused() {
    // Table 8 (manual lines 538-551): 0x0001 ... 0x0200, one bit per write, once the controls
    // are unlocked (C01 = 11, #48 = 0; section 4.5); 0x0002 locks again.
    let sim = lenze();
    sim.preset("control_source", 11).unwrap();
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UNIT).unwrap();
    let mut client = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default()).unwrap();
    client.write_register(UNIT, 48, 0).unwrap();
    for word in [
        0x0001, 0x0004, 0x0008, 0x0040, 0x0080, 0x0100, 0x0200, 0x0002,
    ] {
        assert_eq!(client.write_register(UNIT, 1, word), Ok(()), "{word:#06x}");
    }
    client.write_register(UNIT, 48, 0).unwrap();
    assert!(matches!(
        client.write_register(UNIT, 1, 0x0010),
        Err(BusError::ModbusException {
            code: drivebus::modbus::ExceptionCode::IllegalDataValue,
            ..
        })
    ));
}
