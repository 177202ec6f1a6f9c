//! An application outside the drivegen workspace, built by `scripts/consumer.sh` against the
//! packaged crates only: it simulates a Lafert Smartris from the description inside the packaged
//! `lafert-smartris` crate and reads typed values from it over Modbus TCP.

use std::error::Error;

use drivebus::prelude::*;
use lafert_smartris::Smartris;

fn main() -> Result<(), Box<dyn Error>> {
    let description = std::env::args()
        .nth(1)
        .ok_or("usage: drive-consumer <the lafert-smartris description folder>")?;
    let sim = drivesim::Simulator::load(&description)?;
    // The manual's worked example (RTU Modbus manual §2.2): DC link 0x1356 = 49.50 V.
    sim.preset("bus_dc_link", 0x1356)?.preset("operation_mode", 2)?;
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1))?;
    let bus = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default())?;
    let mut drive = Smartris::modbus(bus, UnitId(1));
    let dc_link: Volts = drive.bus_dc_link().read()?;
    println!("bus_dc_link {dc_link:?}");
    println!("operation_mode {:?}", drive.operation_mode().read()?);
    Ok(())
}
