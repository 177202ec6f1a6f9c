//! The Modbus side of the simulator: the register map, the sans-I/O server core, and blocking
//! TCP, RTU (serial) and RTU over TCP loops around it.

mod command_register;
pub mod map;
pub mod read_blocks;
pub mod rtu;
pub mod rtu_over_tcp;
pub mod server;
pub mod tcp;
pub mod units;

pub use server::ModbusServer;
pub use units::Units;
