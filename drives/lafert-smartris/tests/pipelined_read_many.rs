//! The generated `read_many` over a pipelining Modbus TCP client: values from both register
//! tables reach the bus as one batch and come back typed, against the simulated drive.

use drivebus::modbus::client::{ModbusTcpClient, TcpConfig};
use drivebus::modbus::{RegisterBus, RegisterRead, Table, UnitId};
use drivebus::units::Volts;
use drivebus::BusError;
use lafert_smartris::types::DriveStatus;
use lafert_smartris::{params, Smartris};

/// A bus that counts the batches and reads handed to it before passing them on.
struct Counting<B> {
    bus: B,
    batches: Vec<usize>,
}

impl<B: RegisterBus> RegisterBus for Counting<B> {
    fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        self.batches.push(1);
        self.bus.read_registers(unit, table, start, out)
    }
    fn write_register(&mut self, unit: UnitId, address: u16, value: u16) -> Result<(), BusError> {
        self.bus.write_register(unit, address, value)
    }
    fn write_registers(
        &mut self,
        unit: UnitId,
        start: u16,
        values: &[u16],
    ) -> Result<(), BusError> {
        self.bus.write_registers(unit, start, values)
    }
    fn read_register_batch(
        &mut self,
        unit: UnitId,
        reads: &mut [RegisterRead<'_>],
    ) -> Result<(), BusError> {
        self.batches.push(reads.len());
        self.bus.read_register_batch(unit, reads)
    }
}

#[test]
fn read_many_hands_its_plan_to_the_bus_as_one_pipelined_batch() {
    let sim = drivesim::Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../descriptions/lafert-smartris"
    ))
    .unwrap();
    sim.preset("bus_dc_link", 4950).unwrap();
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1)).unwrap();
    let config = TcpConfig {
        max_in_flight: 8,
        ..TcpConfig::default()
    };
    let client = ModbusTcpClient::connect(server.local_addr(), &config).unwrap();
    let bus = Counting {
        bus: client,
        batches: Vec::new(),
    };
    let mut drive = Smartris::modbus(bus, UnitId(1));
    let (status, volts, address) = drive
        .read_many((
            params::DriveStatus,
            params::BusDcLink,
            params::ModbusAddress,
        ))
        .unwrap();
    assert_eq!(status, DriveStatus::STANDBY);
    assert_eq!(volts, Volts(49.5));
    assert_eq!(address, 1, "the described default drive address");
    let link = drive.into_link();
    // The Smartris refuses reads over addresses it does not list (`read_gaps = false`), but
    // 0x0061..=0x0063 are listed: input 0x0060..=0x0064 is one read, holding 0x0028 the other.
    assert_eq!(link.into_bus().batches, [2], "one batch of two reads");
}
