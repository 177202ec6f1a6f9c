//! `drivesim`: a simulated drive built from any drivegen description.
//!
//! The [`Drive`] holds every parameter's raw value (described defaults, 0 where none) and runs
//! the behaviours the description calls for ([`behaviour`]): the CiA 402 state machine, the
//! description's own `[state_machine]`, command registers, a motor whose speed follows the
//! setpoint along the described ramp, and the write lock and serial watchdog of `[lock]`,
//! `[[unlock]]` and `[watchdog]` (writes refused with the described exception until unlocked; a
//! timeout ends the unlock and applies the action the description maps). Protocol fronts expose it:
//!
//! * [`modbus`] — a sans-I/O server core ([`modbus::ModbusServer`]) enforcing access, ranges,
//!   allowed values, unknown addresses, function codes and the device's limits with the exception
//!   codes the description names; blocking TCP ([`modbus::tcp::TcpServer`]) and RTU
//!   ([`modbus::rtu::serve`]) loops, each serving one drive or several
//!   by unit id ([`modbus::Units`]).
//! * [`canopen`] — the object dictionary view with CiA 301 abort codes, and a [`canopen::Node`]
//!   (boot-up, NMT, heartbeat, SDO) running on any CAN backend of `drivebus`, alone or
//!   with other nodes on one bus ([`canopen::nodes`]).
//! * [`rs232`] — the Kinco RS-232 protocol from the parameters' `rs232` addresses: a sans-I/O
//!   [`rs232::Rs232Server`] (point-to-point or multi-point loop) and a blocking loop
//!   ([`rs232::serve`]) on a serial port or pty.
//!
//! ```
//! use drivebus::modbus::client::{ModbusTcpClient, TcpConfig};
//! use drivebus::modbus::{RegisterBus, Table, UnitId};
//!
//! let sim = drivesim::Simulator::load(concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/lafert-smartris"))?;
//! let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1))?;
//! let mut client = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default())?;
//! let mut status = [0u16; 1];
//! client.read_registers(UnitId(1), Table::Input, 0x0060, &mut status)?;
//! assert_eq!(status[0], 0x0002); // STANDBY after power-on
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod behaviour;
pub mod canopen;
pub mod drive;
mod identity;
pub mod modbus;
pub mod raw;
pub mod refusal;
pub mod rs232;
mod simulator;
pub mod store;
mod variant_selection;

pub use drive::Drive;
pub use refusal::Refusal;
pub use simulator::{SimError, Simulator};
