//! A description whose variants the drive reports (`selected_by`) is served in the variant its
//! selecting parameter holds: the Lenze smd in PC507 when #50 is preset to 507, in its default
//! PC400 otherwise.

use drivebus::modbus::transport::{ModbusTcpClient, TcpConfig};
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
                Err(BusError::ModbusException { code: 2, .. })
            ),
            "#{D38_PC507} is not a PC400 register (number {number})"
        );
    }
}
